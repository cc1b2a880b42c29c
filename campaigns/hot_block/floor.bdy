[main]
name = floor
shapeType = extrusionSolid
shapeFile = floor.exs
correctOrigin = 0
[Mass properties]
mass = 1.0
InertiaZZ = 1.0
[startPosition]
x = 0.0
y = 0.0
Rz = 0.0
[startVelocity]
x = 0.0
y = 0.0
Rz = 0.0
