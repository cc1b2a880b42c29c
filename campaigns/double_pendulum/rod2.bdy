[main]
name = rod2
RGBColor = 0.4 0.4 0.4
shapeFile = rod2.exs
density = 7850
thickness = 0.01
[startPosition]
x = -0.17942813357521975
y = -0.20516003401121108
z = 0
Rx = 0
Ry = 0
Rz = -2.0707963267948966
[startVelocity]
x = 0
y = 0
z = 0
Rx = 0
Ry = 0
Rz = 0
