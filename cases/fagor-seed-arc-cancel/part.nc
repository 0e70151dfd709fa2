; Fagor CNC 8070 Programming manual (ref 0504), 9.1.5 "Cancellation of tool
; radius compensation", "End of the compensation without programmed movement",
; first example: G40 in a block that does not move the plane axes (G91 Y0).
; The block is "G91 G40 Y0" exactly as the manual writes it, with G03 still
; modal: no centre and no motion in the plane make it a zero-length move.
; Before the excerpt: compensation on (G41) by a straight activation along -X,
; tangent to the arc, ending at the excerpt's start (X0 Y0).
G90 G17 G21 F600
G00 X20 Y0
G41 D1
G01 X0 Y0
; -- the manual's excerpt --
G90
G03 X-20 Y-20 I0 J-20
G91 G40 Y0
G01 X-20
