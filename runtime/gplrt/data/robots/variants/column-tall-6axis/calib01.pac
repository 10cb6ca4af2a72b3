' Robot calibration parameter data file
' Controller: variant overlay: 1160 mm column on a 6-axis PF400 with rail
' System software: gplrt default database (ours, not from a real controller)
' File creation date: 11-21-2026

Begin: 1.0

DI: 16075, 0, 0, 0, "Joint max hard stop limit" = 1163, 95, 350, 962,
     135, 502
DI: 16076, 0, 0, 0, "Joint min hard stop limit" = 0, -95, 10, -962,
     69, -502
DI: 16077, 0, 0, 0, "Joint max soft stop limit" = 1161.5, 93, 348,
     960, 134, 500
DI: 16078, 0, 0, 0, "Joint min soft stop limit" = 1.5, -93, 12, -960,
     69, -500

End:

' End of file
