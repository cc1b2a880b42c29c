[main]
name = ringSideU
RGBColor = 1 1 0
shapeFile = ringSideU.exs
density = 1000
thickness = 0.005
[startPosition]
x = 1.576687206060764e-05
y = 2.896883652729927e-05
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
