[main]
name = ball2
RGBColor = 0 0.6 0
shapeType = extrusionSolid
shapeFile = ball2.exs
density = 7850
thickness = 0.01
correctOrigin = 1
[startPosition]
x = 0.105
y = 0.045376
z = 0
Rx = 0
Ry = 0
Rz = 0.05
[startVelocity]
x = 0
y = 0
z = 0
Rx = 0
Ry = 0
Rz = 0
