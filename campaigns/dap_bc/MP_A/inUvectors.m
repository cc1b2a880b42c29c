function inUvectors
    include_global

    V1 = Unit_struct;       % strut axis on the wheel knuckle
    V1.Bindex = 1;
    V1.ulocal = [0.47; -0.88];

    V2 = Unit_struct;       % strut axis on the upper strut
    V2.Bindex = 3;
    V2.ulocal = [1; 0];

    Uvectors = [V1; V2];
