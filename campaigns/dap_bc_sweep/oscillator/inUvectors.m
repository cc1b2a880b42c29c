function inUvectors
    include_global

    U1 = Unit_struct;       % sliding axis on the block
    U1.Bindex = 1;
    U1.ulocal = [1; 0];

    U2 = Unit_struct;       % sliding axis on the ground
    U2.Bindex = 0;
    U2.ulocal = [1; 0];

    Uvectors = [U1; U2];
