function inAnimate
    include_global

    Points_anim = [];

    Bodies(1).shape = 'rect';
    Bodies(1).W = 0.2;
    Bodies(1).H = 0.2;

    xmin = -0.2; xmax = 1.6;
    ymin = -0.2; ymax = 0.6;
