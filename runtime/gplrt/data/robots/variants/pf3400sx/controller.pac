' Motion controller parameter data file
' Controller: variant overlay: PreciseFlex 3400SX
' System software: gplrt default database (ours, not from a real controller)
' File creation date: 11-21-2026

Begin: 1.0

DI: 109, 0, 0, 0, "Controller name" = "PreciseFlex 3400SX (gplrt default)"

End:

' End of file
