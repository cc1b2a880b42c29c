[main]
name = body
shapeType = extrusionSolid
shapeFile = body.exs
correctOrigin = 0
[Mass properties]
mass = 1.0
InertiaZZ = 0.0008666666666666667
[startPosition]
x = 0.0
y = 0.01
Rz = 0.0
[startVelocity]
x = 1.2
y = 0.0
Rz = 0.0
