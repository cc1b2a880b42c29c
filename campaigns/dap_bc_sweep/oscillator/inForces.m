function inForces
    include_global

    F1 = Force_struct;
    F1.type = 'ptp';        % the spring between the block and the ground
    F1.iPindex = 1;
    F1.jPindex = 2;
    F1.k = 20;
    F1.L0 = 0.5;

    Forces = [F1];
