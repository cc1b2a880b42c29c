[main]
name = ball3
RGBColor = 0 0 1
shapeType = extrusionSolid
shapeFile = ball3.exs
density = 7850
thickness = 0.01
correctOrigin = 1
[startPosition]
x = 0.175
y = 0.057008
z = 0
Rx = 0
Ry = 0
Rz = 0.1
[startVelocity]
x = 0
y = 0
z = 0
Rx = 0
Ry = 0
Rz = 0
