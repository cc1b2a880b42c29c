[main]
name = bob
RGBColor = 0.8 0.1 0.1
shapeFile = bob.exs
density = 7850
thickness = 0.01
[startPosition]
x = -0.21538504897053495
y = -0.270978726152989
z = 0
Rx = 0
Ry = 0
Rz = -2.0707963267948966
[startVelocity]
x = 0
y = 0
z = 0
Rx = 0
Ry = 0
Rz = 0
