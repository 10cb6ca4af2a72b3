' Robot kinematic module parameter data file
' Controller: six-axis articulated arm (gplrt default)
' System software: gplrt default database (ours, not from a real controller)
' File creation date: 11-21-2026

Begin: 1.0

DI: 2000, 0, 0, 0, "Number of axes" = 6
DI: 2002, 0, 0, 0, "Robot name" = "Six-axis articulated arm (gplrt default)"
DI: 2003, 0, 0, 0, "Axis mask" = 63
DI: 2004, 0, 0, 0, "Number of extra, non-servoed, axes" = 0
DI: 2007, 0, 0, 0, "Robot model number or version" = 2000
DI: 2104, 0, 0, 0, "Enable robot operation" = 1
DI: 2700, 0, 0, 0, "100% joint speeds in (mm or deg)/sec" = 250, 250,
     300, 400, 400, 600
DI: 2701, 0, 0, 0, "100% Cartesian speeds in (mm or deg)/sec" = 1000,
     360
DI: 2702, 0, 0, 0, "100% joint accels in (mm or deg)/sec^2" = 1000,
     1000, 1200, 2000, 2000, 3000
DI: 2703, 0, 0, 0, "100% Cartesian accels in (mm or deg)/sec^2" = 4000,
     1440
DI: 2704, 0, 0, 0, "Max %speed allowed" = 100
DI: 2705, 0, 0, 0, "Max %accel allowed" = 100
DI: 2706, 0, 0, 0, "Max %decel allowed" = 100
DI: 2708, 0, 0, 0, "Default %speed" = 50
DI: 2709, 0, 0, 0, "Default Cartesian rotation %speed" = 0
DI: 2710, 0, 0, 0, "Default %accel" = 100
DI: 2711, 0, 0, 0, "Default %decel" = 100
DI: 2712, 0, 0, 0, "Default max accel ramp time in sec" = 0.1
DI: 2713, 0, 0, 0, "Default max decel ramp time in sec" = 0.1

End:

' End of file
