points = 5
%%data
0 0.5 0.5 0 0
-0.04 -0.04 0 0 -0.04
%%enddata
