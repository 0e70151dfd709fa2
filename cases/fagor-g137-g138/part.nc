; Fagor 8070 G137 (linear transition) with G138 (direct activation and cancellation).
; Six episodes, each: G41 activation, one compensated move, G40 cancellation.
; The activation and the cancellation both turn RIGHT (outside for G41) by the
; episode's angle: line-line and line-arc (arc G2 R10, 90 deg), 60/120/170 deg.
G90 G17 G21 F600 G137 G138
; episode 1: line, 60 deg
G00 X-10 Y-17.320508
G41 D1
G01 X0 Y0
G01 X20 Y0
G40 G01 X30 Y-17.320508
; episode 2: line, 120 deg
G00 X110 Y-17.320508
G41 D1
G01 X100 Y0
G01 X120 Y0
G40 G01 X110 Y-17.320508
; episode 3: line, 170 deg
G00 X219.696155 Y-3.472964
G41 D1
G01 X200 Y0
G01 X220 Y0
G40 G01 X200.303845 Y-3.472964
; episode 4: arc, 60 deg
G00 X290 Y-17.320508
G41 D1
G01 X300 Y0
G02 X310 Y-10 I0 J-10
G40 G01 X292.679492 Y-20
; episode 5: arc, 120 deg
G00 X410 Y-17.320508
G41 D1
G01 X400 Y0
G02 X410 Y-10 I0 J-10
G40 G01 X392.679492 Y0
; episode 6: arc, 170 deg
G00 X519.696155 Y-3.472964
G41 D1
G01 X500 Y0
G02 X510 Y-10 I0 J-10
G40 G01 X506.527036 Y9.696155
