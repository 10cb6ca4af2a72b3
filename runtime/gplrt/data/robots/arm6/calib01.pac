' Robot calibration parameter data file
' Controller: six-axis articulated arm (gplrt default)
' System software: gplrt default database (ours, not from a real controller)
' File creation date: 11-21-2026

Begin: 1.0

DI: 16000, 0, 0, 0, "Robot serial number" = "GPLRT-ARM6"
DI: 16050, 0, 0, 0, "Kinematic dimensional constants" = 400, 50, 350,
     35, 350, 80, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0
DI: 16051, 0, 0, 0, "Tool set at restart" = 0, 0, 100, 0, 0, 0
DI: 16052, 0, 0, 0, "Base set at restart" = 0, 0, 0, 0, 0, 0
DI: 16075, 0, 0, 0, "Joint max hard stop limit" = 182, 137, 167, 272,
     127, 362
DI: 16076, 0, 0, 0, "Joint min hard stop limit" = -182, -137, -167,
     -272, -127, -362
DI: 16077, 0, 0, 0, "Joint max soft stop limit" = 180, 135, 165, 270,
     125, 360
DI: 16078, 0, 0, 0, "Joint min soft stop limit" = -180, -135, -165,
     -270, -125, -360

End:

' End of file
