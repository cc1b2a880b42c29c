[main]
name = bird
RGBColor = 0 0.4 1
shapeType = extrusionSolid
shapeFile = bird.exs
density = 1000
thickness = 0.005
correctOrigin = 0
[Mass properties]
mass = 0.0045
InertiaZZ = 7e-07
[startPosition]
x = 0.0242238661
y = -0.0043464113
z = 0
Rx = 0
Ry = 0
Rz = -0.2788
[startVelocity]
x = -0.0412560629
y = -0.4061350516
z = 0
Rx = 0
Ry = 0
Rz = -7.4583
