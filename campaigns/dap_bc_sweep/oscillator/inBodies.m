function inBodies
    include_global

    B1 = Body_struct;       % the block
    B1.m = 1.0;
    B1.J = 0.1;
    B1.r = [0.6; 0];        % 0.1 m beyond the spring's undeformed length

    Bodies = [B1];
