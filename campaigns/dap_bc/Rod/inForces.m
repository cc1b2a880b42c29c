function inForces
    include_global

    S1 = Force_struct;
    S1.type = 'weight';

    S2 = Force_struct;
    S2.type = 'user';       % contact of the two ends with the ground, see user_force

    Forces = [S1; S2];
