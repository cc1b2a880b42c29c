[main]
name = foot
virtualToBody = bird
RGBColor = 0 0.4 1
shapeFile = foot.exs
[startPosition]
x = 0
y = 0
z = 0
Rx = 0
Ry = 0
Rz = -0.2788
[startVelocity]
x = 0
y = 0
z = 0
Rx = 0
Ry = 0
Rz = -7.4583
