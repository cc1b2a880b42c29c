[main]
name = ball5
RGBColor = 0.6 0 0.8
shapeType = extrusionSolid
shapeFile = ball5.exs
density = 7850
thickness = 0.01
correctOrigin = 1
[startPosition]
x = 0.31
y = 0.060808
z = 0
Rx = 0
Ry = 0
Rz = 0.2
[startVelocity]
x = 0
y = 0
z = 0
Rx = 0
Ry = 0
Rz = 0
