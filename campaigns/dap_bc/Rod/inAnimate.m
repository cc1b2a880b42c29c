function inAnimate
    include_global

    Points_anim = [];

    Bodies(1).shape = 'line';
    Bodies(1).H = 2.0;

    xmin = -1.5; xmax = 1.5;
    ymin = -0.5; ymax = 2.0;
