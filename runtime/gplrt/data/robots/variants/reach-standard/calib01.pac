' Robot calibration parameter data file
' Controller: variant overlay: PF400 standard reach (225/210 mm links)
' System software: gplrt default database (ours, not from a real controller)
' File creation date: 11-21-2026

Begin: 1.0

DI: 16050, 0, 0, 0, "Kinematic dimensional constants" = 0, 225, 210,
     0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0

End:

' End of file
