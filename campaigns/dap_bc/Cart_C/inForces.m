function inForces
    include_global

    F1 = Force_struct;
    F1.type = 'weight';   % include the weight

    F2 = Force_struct;
    F2.type = 'user';     % motor torque, see user_force

    Forces = [F1; F2];
