[main]
name = ball1
RGBColor = 1 0 0
shapeType = extrusionSolid
shapeFile = ball1.exs
density = 7850
thickness = 0.01
correctOrigin = 1
[startPosition]
x = 0.04
y = 0.037156
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
