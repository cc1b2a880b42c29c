function inForces
    include_global

    F1 = Force_struct;
    F1.type = 'ptp';        % spring between the slider and the ground
    F1.iPindex = 2;
    F1.jPindex = 1;
    F1.k = 20;
    F1.L0 = 0.6;

    F2 = Force_struct;
    F2.type = 'weight';

    Forces = [F1; F2];
