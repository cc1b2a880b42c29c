[main]
name = bird
RGBColor = 0 0.4 1
shapeFile = bird.exs
density = 1000
thickness = 0.005
[Mass properties]
mass = 0.0045
InertiaZZ = 7e-07
[startPosition]
x = 0.024223866098297464
y = -0.004346411346104019
z = 0
Rx = 0
Ry = 0
Rz = -0.2788
[startVelocity]
x = -0.04125606292432726
y = -0.40613505164100433
z = 0
Rx = 0
Ry = 0
Rz = -7.4583
