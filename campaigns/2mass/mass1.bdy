[main]
name = mass1
RGBcolor = 0 1 0
shapeType = extrusionSolid
shapeFile = mass1.exs
density = 2500
thickness = 0.02
correctOrigin =0
[startPosition]
x = -0.005
y = 0.15
z = 0
Rx = 0
Ry = 0
Rz=3.1459
[startVelocity]
x = 0
y = -1
z = 0
Rx = 0
Ry = 0
Rz=0
