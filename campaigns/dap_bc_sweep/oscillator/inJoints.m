function inJoints
    include_global

    J1 = Joint_struct;
    J1.type = 'tran';       % the block slides along x on the ground
    J1.iPindex = 1;
    J1.jPindex = 2;
    J1.iUindex = 1;
    J1.jUindex = 2;

    Joints = [J1];
