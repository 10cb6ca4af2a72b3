"""The V+ words the parser recognises by position (spec §2.4-2.5): which words start an
instruction, which take a parenthesised unit (``WRITE (lun) ...``), which are functions callable
without parentheses, and which gpl2py parses without running (tier 3).

One table per question, so that "is X an instruction" has one answer; what an instruction *means*
is in :mod:`gpl2py.vplus.semantics` and :mod:`gpl2py.vplus.lower`.
"""

from __future__ import annotations

#: Instructions parsed by the generic shape ``WORD [(unit)] items [= items] [modifiers]``.
GENERIC = frozenset("""
MOVE MOVES APPRO APPROS DEPART DEPARTS DRIVE MOVET MOVEST MOVEF MOVESF READY ALIGN BREAK BRAKE DELAY
SPEED ACCEL DURATION COARSE FINE NULL NONULL OVERLAP NOOVERLAP SINGLE MULTIPLE ABOVE BELOW LEFTY
RIGHTY FLIP NOFLIP CPON CPOFF OPEN OPENI CLOSE CLOSEI RELAX RELAXI TOOL BASE PAYLOAD
SIGNAL BITS RESET TYPE PROMPT WAIT WAIT.EVENT SET.EVENT CLEAR.EVENT RELEASE LOCK ABORT CYCLE.END
HALT STOP PAUSE PROCEED IGNORE ENABLE DISABLE RUNSIG TIMER PARAMETER SWITCH SELECT AIO.OUT KEYMODE
DECOMPOSE DEFBELT SETBELT WINDOW ATTACH DETACH READ WRITE FOPEN FOPENR FOPENW FOPENA FOPEND FCLOSE
FDELETE FEMPTY FSEEK FCMND SETDEVICE TIME SOLVE.ANGLES SOLVE.TRANS ALTON ALTER ALTOFF AMOVE
CALIBRATE WAIT.START
""".split())

#: Instructions gpl2py parses but does not run (spec §2.6, tier 3): graphics, vision, VME shared
#: memory, monitor commands, network protocols.  Reaching one at run time raises *Not implemented*.
TIER3 = frozenset("""
GTYPE GCOLOR GTRANS GPANEL GARC GCHAIN GCLEAR GCLIP GCOPY GFLOOD GICON GLINE GLINES GLOGICAL GPOINT
GRECTANGLE GSCAN GTEXTURE GSLIDE FSET GETEVENT VDISPLAY VPICTURE VLOCATE VWINDOW VTRAIN VDEF.AOI
IOPUTB IOPUTW IOPUTL IOPUTF IOPUTD IOPUTS IOTAS MCS SEE DEF.DIO INT.EVENT
""".split())

#: Instructions whose first part is a parenthesised unit (a LUN, a window, a camera) when written
#: with one: ``WRITE (lun) $msg, /S``, ``ATTACH (lun, 4) "TCP"``, ``ACCEL (1) 100, 100``.
UNIT = frozenset("""
ATTACH DETACH READ WRITE FOPEN FOPENR FOPENW FOPENA FOPEND FCLOSE FDELETE FEMPTY FSEEK FCMND FSET
SETDEVICE GETEVENT ACCEL PROMPT
""".split()) | frozenset(w for w in TIER3 if w.startswith(("G", "V")))

#: Words that may end an instruction: SPEED 25 MMPS ALWAYS, DURATION 0.5 ALWAYS.
MODIFIERS = frozenset("ALWAYS MONITOR MMPS IPS".split())

#: Words that start (or close) a structured block, parsed by the parser itself.
STRUCTURE = frozenset("IF ELSE ELSEIF ELIF END CASE VALUE ANY DO UNTIL WHILE FOR EXIT NEXT GOTO".split())

#: Functions usable without parentheses (spec §2.5: ``RANDOM*10``, ``HERE``, ``DEST``).
ZERO_ARG = frozenset("""
HERE DEST TOOL BASE NULL PI RANDOM TRUE FALSE ON OFF #PHERE #PDEST #PLATCH LATCH HAND ID FREE TPS
PRIORITY $ID $DEFAULT STATE
""".split())

#: Instructions and functions of V+ that gpl2py reads and checks but the runtime layer does not
#: simulate yet (docs/design/vplus-runtime.md lists what it has): each is warning GPL4126 and
#: raises *Not implemented* naming it if the program reaches it.
UNSIMULATED = frozenset("""
AIO.OUT ALIGN ALTER ALTOFF ALTON AMOVE CALIBRATE CYCLE.END DEFBELT FCMND FEMPTY FSEEK KEYMODE MOVEF MOVESF
PAYLOAD PROCEED RUNSIG SETBELT SETDEVICE SOLVE.ANGLES SOLVE.TRANS TIME WAIT.START WINDOW
BCD DCB $UNPACK $ID $DEFAULT FREE ID TASK PENDANT AIO.IN AIO.INS DEVICE STATE LATCHED LATCH #PLATCH BELT
BSTATUS
""".split())
