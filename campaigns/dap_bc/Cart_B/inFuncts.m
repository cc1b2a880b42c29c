function inFuncts
    include_global

    F1 = Funct_struct;      % rear wheel speeds up to 2*pi rad/s clockwise in 2 s
    F1.type = 'c';
    F1.t_end = 2.0;
    F1.dfdt_end = -2*pi;

    Functs = [F1];
