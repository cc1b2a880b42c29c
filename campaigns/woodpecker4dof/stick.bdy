[main]
name = stick
RGBColor = 0.6 0.4 0.2
shapeFile = stick.exs
density = 700
thickness = 0.005
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
