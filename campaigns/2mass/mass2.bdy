[main]
name = mass2
RGBcolor = 0.5 0.5 0.5
shapeType = extrusionSolid
shapeFile = mass2.exs
density = 2500
thickness = 0.02
correctOrigin = 0
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
