[main]
name = ringSideR
virtualToBody = ring
RGBColor = 1 1 0
shapeFile = ringSideR.exs
density = 1000
thickness = 0.005
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
