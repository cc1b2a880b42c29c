[main]
name = ball4
RGBColor = 1 0.6 0
shapeType = extrusionSolid
shapeFile = ball4.exs
density = 7850
thickness = 0.01
correctOrigin = 1
[startPosition]
x = 0.245
y = 0.060613
z = 0
Rx = 0
Ry = 0
Rz = 0.15
[startVelocity]
x = 0
y = 0
z = 0
Rx = 0
Ry = 0
Rz = 0
