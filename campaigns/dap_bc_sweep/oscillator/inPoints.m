function inPoints
    include_global

    P1 = Point_struct;      % the block's centre
    P1.Bindex = 1;
    P1.sPlocal = [0; 0];

    P2 = Point_struct;      % the spring's anchor, on the ground
    P2.Bindex = 0;
    P2.sPlocal = [0; 0];

    Points = [P1; P2];
