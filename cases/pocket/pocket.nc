%
(The pocket case as ISO G-code: the same contour as pocket.pmc, cutter)
(radius 3 given as a 6 mm diameter with G41.1, feed 30 mm/s = F1800)
G21 G17 G90 G94
G0 X20 Y20 Z5
G1 Z-2 F1800
G41.1 D6
G1 X0 Y20
Y6
G3 X6 Y0 I6 J0
G1 X25
Y8
X35
Y0
X54
G3 X60 Y6 I0 J6
G1 Y34
G3 X54 Y40 I-6 J0
G1 X40
G2 X20 Y40 I-10 J0
G1 X6
G3 X0 Y34 I0 J-6
G1 Y20
G40
G1 X20
G1 Z5
M30
%
