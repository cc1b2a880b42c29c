points = 5
%%data
-0.5 0.5 0.5 -0.5 -0.5
-0.1 -0.1 0 0 -0.1
%%enddata
