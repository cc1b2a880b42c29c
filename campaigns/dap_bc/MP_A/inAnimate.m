function inAnimate
    include_global

    Points_anim = [];

    xmin = 0.0; xmax = 0.9;
    ymin = -0.1; ymax = 0.9;
