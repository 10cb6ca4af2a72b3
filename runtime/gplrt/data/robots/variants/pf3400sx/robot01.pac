' Robot kinematic module parameter data file
' Controller: variant overlay: PreciseFlex 3400SX
' System software: gplrt default database (ours, not from a real controller)
' File creation date: 11-21-2026

Begin: 1.0

DI: 2002, 0, 0, 0, "Robot name" = "PreciseFlex 3400SX"
DI: 2007, 0, 0, 0, "Robot model number or version" = 3400

End:

' End of file
