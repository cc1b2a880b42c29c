function inPoints
    include_global

    P1 = Point_struct;      % rear axle on the cart
    P1.Bindex = 1;
    P1.sPlocal = [-0.3; -0.1];

    P2 = Point_struct;      % front axle on the cart
    P2.Bindex = 1;
    P2.sPlocal = [ 0.3; -0.1];

    P3 = Point_struct;      % rear wheel centre
    P3.Bindex = 2;
    P3.sPlocal = [ 0; 0];

    P4 = Point_struct;      % front wheel centre
    P4.Bindex = 3;
    P4.sPlocal = [ 0; 0];

    Points = [P1; P2; P3; P4];
