function inForces
    include_global

    S1 = Force_struct;
    S1.type = 'ptp';        % suspension spring-damper E-F
    S1.iPindex = 9;
    S1.jPindex = 10;
    S1.k = 90000;
    S1.L0 = 0.23;
    S1.dc = 1100;

    S2 = Force_struct;
    S2.type = 'user';       % tire, see user_force
    S2.k = 50000;
    S2.L0 = 0.35;
    S2.dc = 1000;

    S3 = Force_struct;
    S3.type = 'weight';

    Forces = [S1; S2; S3];
