[main]
name = rod1
RGBColor = 0.6 0.6 0.6
shapeFile = rod1.exs
density = 7850
thickness = 0.01
[startPosition]
x = -0.07173560908995226
y = -0.06967067093471656
z = 0
Rx = 0
Ry = 0
Rz = -2.3707963267948964
[startVelocity]
x = 0
y = 0
z = 0
Rx = 0
Ry = 0
Rz = 0
