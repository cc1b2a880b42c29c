function inUvectors
    include_global

    V1 = Unit_struct;       % strut axis on the wheel knuckle
    V1.Bindex = 1;
    V1.ulocal = [0.47; -0.88];

    Uvectors = [V1];
