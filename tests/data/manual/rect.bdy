[main]
name = rect
virtualToBody =
RGBColor = 0 1 0
shapeType = extrusionSolid
shapeFile = rect.exs
density = 7900
thickness = 0.1
maximumDisplacementFactor = 0.1
skinThickness = 0.001 % not needed by default
correctOrigin = 1 % 1=True, 0=False
[Mass properties]
mass = 1
InertiaXX = 0.004
InertiaXY = 0.004
InertiaXZ = 0.004
InertiaYY = 0.004
InertiaYZ = 0.004
InertiaZZ = 0.004
[startPosition]
x = 0
y = 1.1
z = 0
Rx = 0
Ry = 0
Rz = 0
[startVelocity]
x = 0
y = 1.1
z = 0
Rx = 0
Ry = 0
Rz = 0
