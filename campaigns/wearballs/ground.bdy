[main]
name = ground
RGBColor = 0.5 0.5 0.5
shapeType = extrusionSolid
shapeFile = ground.exs
density = 7850
thickness = 0.01
correctOrigin = 0
[startPosition]
x = 0.002
y = 0
z = 0
Rx = 0
Ry = 0
Rz = 0.08
[startVelocity]
x = 0
y = 0.3141592654
z = 0
Rx = 0
Ry = 0
Rz = 0
