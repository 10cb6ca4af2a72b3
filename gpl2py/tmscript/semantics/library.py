"""The TMscript built-ins the front end knows: name -> (fewest, most arguments; ``None`` = any).

The runtime (``gplrt.tm.library``) implements each of them under the same name; a test keeps the
two in step.  ``DEFERRED`` names the built-ins whose first argument is not evaluated at the call
but later or repeatedly (spec §2, "Deferred arguments": ThreadRun, WaitFor's condition), which the
lowering wraps in a ``lambda``.  ``RETURNS`` gives the type of what a built-in returns where the
checks need it.
"""

from __future__ import annotations

BUILTINS: dict[str, tuple[int, int | None]] = {
    # threads and script control (L1815-L2064, L7707-L8032)
    "ThreadRun": (1, 2), "ThreadID": (0, 0), "ThreadState": (0, 1), "ThreadExit": (0, 1),
    "Exit": (0, 2), "Pause": (0, 0), "Resume": (0, 0), "WaitFor": (1, 2), "Sleep": (1, 1),
    "Display": (1, 4),
    # Listen node (L7447-L7706, L17642-L18305)
    "ScriptExit": (0, 1), "ListenPacket": (1, 2), "ListenSend": (2, 3),
    # motion and the motion queue (L15515-L17228); the float[6] forms and the scalar forms
    "QueueTag": (1, 2), "WaitQueueTag": (1, 2), "StopAndClearBuffer": (0, 1),
    "PTP": (6, 15), "Line": (6, 12), "Circle": (8, 19), "PLine": (5, 10),
    "Move_PTP": (6, 11), "Move_Line": (6, 11), "Move_PLine": (5, 10),
    "ChangeBase": (1, 6), "ChangeTCP": (1, 16), "ChangeLoad": (1, 1),
    "PVTEnter": (0, 1), "PVTExit": (0, 0), "PVTPoint": (3, 13), "PVTPause": (0, 0), "PVTResume": (0, 0),
    # Ethernet Slave (L19694-L20556)
    "svr_read": (1, 1), "svr_write": (2, 2),
    # conversions, strings, arrays, checksums, time (L2066-L7446)
    "Length": (1, 1), "Ctrl": (1, 1), "GetString": (1, 5), "GetBytes": (1, 3), "GetNowStamp": (0, 2),
    "GetNow": (0, 1), "GetVarValue": (1, 1), "VarSync": (1, None), "GetToken": (3, 5), "GetAllTokens": (3, 4),
    "ValueReverse": (1, 2),
    "String_ToInteger": (1, 2), "String_ToFloat": (1, 2), "String_ToDouble": (1, 2),
    "String_IndexOf": (2, 3), "String_LastIndexOf": (2, 3), "String_Substring": (2, 4),
    "String_Split": (2, 3), "String_Replace": (3, 3), "String_Trim": (1, 3), "String_ToLower": (1, 1),
    "String_ToUpper": (1, 1), "String_ToByte": (1, 2), "Byte_ToString": (1, 2),
    "Byte_ToInt16": (1, 3), "Byte_ToInt32": (1, 2), "Byte_ToFloat": (1, 2), "Byte_ToDouble": (1, 2),
    "Byte_Concat": (2, None),
    "Array_Append": (2, 2), "Array_Insert": (3, 3), "Array_Remove": (2, 3), "Array_Equals": (2, 5),
    "Array_IndexOf": (2, 3), "Array_LastIndexOf": (2, 3), "Array_Reverse": (1, 2), "Array_Sort": (1, 2),
    "Array_SubElements": (2, 3),
    "XOR8": (1, 3), "SUM8": (1, 3), "SUM16": (1, 3), "SUM32": (1, 3), "CRC16": (1, 4), "CRC32": (1, 3),
    # files in the sandbox (L9907-L12366)
    "File_ReadBytes": (1, 1), "File_ReadText": (1, 1), "File_ReadLines": (1, 3), "File_NextLine": (0, 2),
    "File_NextEOF": (0, 0), "File_WriteBytes": (2, 5), "File_WriteText": (2, 5), "File_WriteLine": (2, 5),
    "File_WriteLines": (2, 5), "File_Exists": (1, 1), "File_Length": (1, 1), "File_Delete": (1, None),
    "File_Copy": (2, 3), "File_Replace": (3, 3), "File_GetToken": (3, 5), "File_CopyImage": (2, 4),
    "File_GetImage": (0, 1),
    "File_GetAllTokens": (3, 4),
    # the SerialPort class on the simulated robot's virtual ports (L12367-L13395)
    "com_open": (1, 1), "com_close": (1, 1), "com_read": (1, 5), "com_read_string": (1, 5),
    "com_write": (2, 4), "com_writeline": (2, 4),
    # vision jobs on the simulated vision backend (L17229-L17641)
    "Vision_DoJob": (1, 1), "Vision_DoJob_PTP": (3, 4), "Vision_DoJob_Line": (2, 4),
    "Vision_IsJobAvailable": (1, 1), "Vision_GetOutputArraySize": (1, 2), "Vision_GetOutputArrayValue": (2, 3),
    "Vision_GetTriggerJobOutputCount": (1, 1), "Vision_GetTriggerJobOutputValue": (1, 1),
    # the Socket class's TCP client (L13396-L14356)
    "socket_open": (1, 1), "socket_close": (1, 1), "socket_read": (1, 5), "socket_read_string": (1, 5),
    "socket_send": (2, 4), "socket_sendline": (2, 4),
    # the ModbusTCP/ModbusRTU classes' preset and user-defined reads and writes (L18324-L19693)
    "modbus_open": (1, 1), "modbus_close": (1, 1), "modbus_read": (2, 5), "modbus_read_int16": (5, 6),
    "modbus_read_int32": (5, 6), "modbus_read_float": (5, 6), "modbus_read_double": (5, 6),
    "modbus_read_string": (5, 6), "modbus_write": (3, 6),
    # math in degrees (L8033-L9400) and pose math (L9393-L9900)
    "abs": (1, 1), "pow": (2, 2), "sqrt": (1, 1), "ceil": (1, 1), "floor": (1, 1), "round": (1, 2),
    "random": (0, 2), "sum": (1, None), "average": (1, None), "min": (1, None), "max": (1, None),
    "d2r": (1, 1), "r2d": (1, 1), "sin": (1, 1), "cos": (1, 1), "tan": (1, 1), "asin": (1, 1),
    "acos": (1, 1), "atan": (1, 1), "atan2": (2, 2), "log": (1, 2), "log10": (1, 1), "norm2": (1, 1),
    "dist": (2, 2), "trans": (2, 3), "inversetrans": (1, 2), "applytrans": (2, 3), "changeref": (2, 3),
    "interpoint": (3, 3), "points2coord": (3, 9), "intercoord": (2, 2),
}

#: Built-ins that find variables by a name given at run time (L6650, L7626): the lowering passes
#: them the variables visible at the call.
BY_NAME = frozenset({"GetVarValue", "VarSync"})

#: Built-ins whose first argument is a deferred statement or condition (spec §2).
DEFERRED = frozenset({"ThreadRun"})
#: WaitFor defers its first argument only in the two-argument form ``WaitFor(cond, ms)`` (L7865).
DEFERRED_WITH_TWO = frozenset({"WaitFor"})

#: Class types (L12376-L25700) the runtime has; a declaration of another is reported as not
#: supported yet, never translated to a call that fails at run time.
CLASSES: frozenset[str] = frozenset({"TPoint", "TBase", "TTCP", "Socket", "SerialPort", "ModbusTCP", "ModbusRTU"})
#: How many values a device class's declaration takes (L12376, L13398, L18326, L18531).
CLASS_ARGUMENTS: dict[str, tuple[int, ...]] = {
    "SerialPort": (2, 5, 6, 9), "ModbusRTU": (2, 5, 6, 9), "Socket": (2, 3), "ModbusTCP": (1, 2, 3)}
#: The device classes: closed when the block that declares them is left (L1320, L1335-L1345).
DEVICES = frozenset(CLASS_ARGUMENTS)

#: The manual's member attributes (name -> "R" or "RW") of the teach classes (L15023, L15169,
#: L15467) and of what a parameterized object's index gives (L14397-L14860).  Which of them the
#: runtime implements is read from its classes (``members_data``, generated by ``members_gen``);
#: a documented one it lacks is "not supported yet" (GPL5314), any other is not a member (GPL5317).
_POINT = {"Value": "RW", "Joint": "RW", "Pose": "RW", "Flange": "R", "BaseName": "R", "TCPName": "R",
          "TeachValue": "R", "TeachJoint": "R", "TeachPose": "R"}
_BASE = {"Value": "RW", "Type": "R", "TeachValue": "R"}
_TCP = {"Value": "RW", "Mass": "RW", "MOI": "RW", "MCF": "RW", "TeachValue": "R", "TeachMass": "R",
        "TeachMOI": "R", "TeachMCF": "R"}
_FT = {**dict.fromkeys(("X", "Y", "Z", "TX", "TY", "TZ", "F3D", "T3D", "Value", "ForceValue", "TorqueValue",
                        "RefCoordX", "RefCoordY", "RefCoordZ", "RefCoordTX", "RefCoordTY", "RefCoordTZ",
                        "RefCoordF3D", "RefCoordT3D", "RefCoordForceValue", "RefCoordTorqueValue", "Model"),
                       "R"), "Zero": "RW"}
DOCUMENTED_MEMBERS: dict[str, dict[str, str]] = {
    "TPoint": _POINT, "Point": _POINT, "TBase": _BASE, "Base": _BASE, "TTCP": _TCP, "TCP": _TCP,
    "VPoint": {"Value": "RW", "BaseName": "R", "TeachValue": "R"},
    # ControlBox, EndModule, ExtModuleN; SI and SO are the Safety module's
    "IO": {"DI": "R", "DO": "RW", "AI": "R", "AO": "RW", "InstantDI": "R", "InstantDO": "RW", "InstantAI": "R",
           "InstantAO": "RW", "SI": "R", "SO": "R"},
    "Robot": {"CoordRobot": "R", "CoordBase": "R", "Joint": "R", "BaseName": "R", "TCPName": "R",
              "CameraLight": "RW", "InstantCameraLight": "RW", "TCPForce3D": "R", "TCPSpeed3D": "R"},
    "FT": _FT,
    "Socket": {}, "SerialPort": {}, "ModbusTCP": {}, "ModbusRTU": {},
}
#: The manual's member methods (``base5.GetValue(0)``, L15169; ``mbus1.Preset(...)``, L18372).
DOCUMENTED_METHODS: dict[str, frozenset[str]] = {
    "TBase": frozenset({"GetValue", "SetValue"}),
    "ModbusTCP": frozenset({"Preset", "IODDPreset"}), "ModbusRTU": frozenset({"Preset", "IODDPreset"})}

#: Parameterized objects: ``Item[index].Attribute`` without a declaration (L14355-L14860).
OBJECTS = frozenset({"Point", "Base", "TCP", "VPoint", "IO", "Robot", "FT"})

#: What a built-in returns, where a check needs the type (the rest: unknown).
RETURNS: dict[str, str] = {
    "Length": "int", "ThreadID": "int", "ThreadRun": "int", "ThreadState": "int", "ThreadExit": "int",
    "QueueTag": "bool", "WaitQueueTag": "int", "GetNowStamp": "int", "String_ToInteger": "int",
    "String_IndexOf": "int", "ScriptExit": "bool", "File_Length": "int", "File_Exists": "bool",
    "File_NextEOF": "bool",
}
