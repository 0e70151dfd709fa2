; Fagor CNC 8070 Programming manual (ref 0504), 9.1.5 "Cancellation of tool
; radius compensation", "End of the compensation without programmed movement",
; second example: G40 in a block that programs the current position (X-30).
; Before the excerpt: compensation on (G41) by a straight activation along -Y
; ending at the excerpt's start (X0 Y0).
G90 G17 G21 F600
G00 X0 Y20
G41 D1
G01 X0 Y0
; -- the manual's excerpt --
G90
G01 X-30
G01 G40 X-30
G01 X25 Y-25
