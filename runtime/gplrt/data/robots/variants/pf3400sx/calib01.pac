' Robot calibration parameter data file
' Controller: variant overlay: PreciseFlex 3400SX
' System software: gplrt default database (ours, not from a real controller)
' File creation date: 11-21-2026

Begin: 1.0

DI: 16000, 0, 0, 0, "Robot serial number" = "PF34-00000"
DI: 16075, 0, 0, 0, "Joint max hard stop limit" = 402, 95, 350, 962,
     135
DI: 16076, 0, 0, 0, "Joint min hard stop limit" = 0, -95, 10, -962,
     69
DI: 16077, 0, 0, 0, "Joint max soft stop limit" = 401.5, 93, 348,
     960, 134
DI: 16078, 0, 0, 0, "Joint min soft stop limit" = 1.5, -93, 12, -960,
     69

End:

' End of file
