[main]
name = ringSideU
RGBColor = 1 1 0
shapeType = extrusionSolid
shapeFile = ringSideU.exs
density = 1000
thickness = 0.005
correctOrigin = 0
[startPosition]
x = 0
y = 0
z = 0
Rx = 0
Ry = 0
Rz = -0.1009
[startVelocity]
x = 0
y = -0.3411
z = 0
Rx = 0
Ry = 0
Rz = 0
