[main]
name = wall
RGBColor = 0.3 0.3 0.3
shapeFile = wall.exs
density = 7850
thickness = 0.01
[startPosition]
x = 0
y = 0
z = 0
Rx = 0
Ry = 0
Rz = 0
[startVelocity]
x = 0
y = 0
z = 0
Rx = 0
Ry = 0
Rz = 0
