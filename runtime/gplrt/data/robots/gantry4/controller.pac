' Motion controller parameter data file
' Controller: PrecisePlace-style XYZ-Theta gantry (gplrt default)
' System software: gplrt default database (ours, not from a real controller)
' File creation date: 11-21-2026

Begin: 1.0

DI: 109, 0, 0, 0, "Controller name" = "PrecisePlace-style gantry (gplrt default)"
DI: 116, 0, 0, 0, "Robot types" = 2, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0,
     0
DI: 600, 0, 0, 0, "Trajectory Generator update period in sec" = 0.004
DI: 601, 0, 0, 0, "System wide test speed in %" = 50
DI: 602, 0, 0, 0, "Rate of change of test speed in %/sec" = 100

End:

' End of file
