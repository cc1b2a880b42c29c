function inAnimate
    include_global

    Points_anim = [];

    Bodies(1).shape = 'rect';
    Bodies(1).W = 0.8;
    Bodies(1).H = 0.1;
    Bodies(2).shape = 'circle';
    Bodies(2).R = 0.1;
    Bodies(3).shape = 'circle';
    Bodies(3).R = 0.1;

    xmin = -0.2; xmax = 3.0;
    ymin = -0.2; ymax = 0.6;
