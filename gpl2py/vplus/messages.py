"""Every diagnostic of the V+ front end: codes GPL4000-GPL4999 (docs/design/frontends.md).

4000-4299 syntax (lexer, parser, data sections), 4300-4699 semantics, 4700-4999 lowering.  They are
registered in the one registry of :mod:`gpl2py.messages` (``--select``, ``explain``, the generated
docs/diagnostics.md), which imports this module when it lists every message.
"""

from __future__ import annotations

from gpl2py.messages import _error, _warning

# --- lexer ---------------------------------------------------------------------------------------
BAD_CHARACTER = _error("GPL4001", "unexpected character {char} in V+ source",
                       "V+ source is printable ASCII: names, numbers, strings and the operators of the "
                       "V+ Language User's Guide (spec §1.2-1.4).")
UNTERMINATED_STRING = _error("GPL4002", "string not closed before the end of the line",
                             "A V+ string is written on one line between double quotes and cannot hold a "
                             "double quote (User's Guide, string constants).")
BAD_NUMBER = _error("GPL4003", "invalid number {text}",
                    "Numbers are decimal (13.65, 1E+38), ^B binary, ^H hexadecimal or ^ octal.")
BAD_ASCII_CONSTANT = _error("GPL4004", "' must be followed by one printable character",
                            "'A is the numeric value of the character A (User's Guide, ASCII constants).")

# --- parser --------------------------------------------------------------------------------------
EXPECTED = _error("GPL4100", "expected {what}, found {found}")
UNKNOWN_INSTRUCTION = _error("GPL4101", "unknown V+ instruction {name}",
                             "The line starts with a name that is neither a V+ instruction nor followed by "
                             "'=' (an assignment).")
OUTSIDE_PROGRAM = _error("GPL4102", "statement outside a program: a V+ file holds .PROGRAM ... .END "
                         "blocks and data sections",
                         "Every program begins with a .PROGRAM line and ends with a .END line (User's "
                         "Guide, program format).")
MISSING_DOT_END = _error("GPL4103", ".PROGRAM {name} has no .END",
                         "A program must end with a .END line.")
BLOCK_NOT_CLOSED = _error("GPL4104", "{block} is not closed: END expected before {where}",
                          "IF, CASE, WHILE and FOR blocks end with END; DO ends with UNTIL.")
NO_BLOCK = _error("GPL4105", "{word} without a matching {block}",
                  "V+ reports *Control structure error* for such a program.")
LATE_DECLARATION = _error("GPL4106", "{kind} must come before the first executable instruction",
                          "AUTO, LOCAL and GLOBAL lines must precede every executable line of the "
                          "program (User's Guide L857-863).")
BAD_LABEL = _error("GPL4107", "step label {text} is not an integer from 0 to 65535",
                   "Step labels are integers 0..65535 at the start of a line (User's Guide L804-809).")
DUPLICATE_LABEL = _error("GPL4108", "step label {label} is already used in {program} (line {line})")
BAD_DATA_LINE = _error("GPL4109", "cannot read this line of the {section} section: {reason}",
                       "A data section (.LOCATIONS, .REALS, .STRINGS) holds one 'name value...' per line, "
                       "as V+'s STORE writes it (docs/design/vplus.md).")
UNKNOWN_SECTION = _error("GPL4110", "unknown section {name}",
                         "A V+ file holds .PROGRAM, .LOCATIONS, .REALS, .DOUBLES and .STRINGS sections.")
TOO_DEEP = _error("GPL4111", "expression nested too deeply")
NO_SOURCES = _error("GPL4112", "no V+ source files (.v2, .pg) in {path}")
BLOCKS_TOO_DEEP = _error("GPL4113", "blocks nested more than {limit} deep",
                         "gpl2py reads IF, CASE, WHILE, DO and FOR blocks nested at most {limit} deep (deeper ones "
                         "would exhaust the parser's stack); the rest of the program is skipped to its .END. "
                         "Move the inner part into a program of its own and CALL it.".replace("{limit}", "50"))

DIALECT_IF_THEN = _warning("GPL4120", "IF without THEN is the robot-sandbox dialect, not V+: read as IF ... THEN",
                           "The V+ simulator robot-sandbox accepted IF without THEN; a controller "
                           "rejects the line. It is read as IF ... THEN so that the program runs.")
DIALECT_WHILE_DO = _warning("GPL4121", "WHILE without DO is the robot-sandbox dialect, not V+: read as WHILE ... DO",
                            "The V+ simulator robot-sandbox accepted WHILE without DO; a controller "
                            "rejects the line.")
DIALECT_ELSEIF = _warning("GPL4122", "{word} is the robot-sandbox dialect, not V+: read as ELSE with a nested IF",
                          "V+ has no ELSEIF (User's Guide, IF...THEN...ELSE); the robot-sandbox simulator "
                          "accepted ELSEIF and ELIF.")
PRECEDENCE = _warning("GPL4123", "{op} binds tighter than {rel} in V+: this reads ({left} {op} ...) {rel} ...; "
                      "add parentheses to say which is meant",
                      "In V+, AND is evaluated with * and /, OR and XOR with + and -, and the relations "
                      "after them (User's Guide, Order of Operator Evaluation): 'a OR b > c' is "
                      "'(a OR b) > c'.")
UNSUPPORTED_INSTRUCTION = _warning("GPL4124", "{name} is not supported by gpl2py (tier 3 of the V+ spec): "
                                   "it raises *Not implemented* when the program reaches it",
                                   "Graphics, vision, VME and monitor-command instructions parse, and raise "
                                   "*Not implemented* if reached at run time.")
UNSIMULATED = _warning("GPL4126", "{name} is not simulated by gpl2py yet: it raises *Not implemented* when the "
                       "program reaches it",
                       "V+ instructions and functions of the spec's tiers 1 and 2 that the runtime layer "
                       "does not have yet (belts, analog I/O, the pendant, ALTER, SOLVE ...): the program "
                       "is checked and translated, and stops there with the runtime's error.")
DIALECT_SPEED_STRING = _warning("GPL4125", "a string as SPEED's second value is the robot-sandbox dialect: "
                                "read as SPEED ... MONITOR",
                                "V+ writes SPEED value MONITOR; the robot-sandbox simulator took "
                                "SPEED value, \"MONITOR\".")

# --- semantics -----------------------------------------------------------------------------------
UNDEFINED_PROGRAM = _error("GPL4300", "program {name} is not defined in this project",
                           "CALL, EXECUTE and REACT name a program of the project's files; V+ stops with "
                           "*Undefined program or variable name* when it is not resident.")
DUPLICATE_PROGRAM = _warning("GPL4301", "program {name} is defined again (first at {first}): V+ keeps the "
                             "first one loaded",
                             "A V+ LOAD does not replace a program already in memory (User's Guide L3190-3192).")
TYPE_CONFLICT = _warning("GPL4302", "{name} is used as {new} here but as {old} at {where}: V+ stops with "
                         "*Data type different* when both uses run",
                         "A V+ variable has one type, fixed when it is created at run time; V+ loads "
                         "programs that use a name both ways and stops when the second use runs "
                         "(User's Guide L4009-4011). The translation raises that error then.")
ARGUMENT_COUNT = _error("GPL4303", "{name} takes {expected} arguments, {given} given",
                        "Arguments map by position; omitted ones are undefined, extra ones are an error.")
LOCATION_ASSIGNED = _error("GPL4304", "a location cannot be assigned with '=': write SET {name} = ...",
                           "Transformations and precision points are assigned with SET or HERE "
                           "(User's Guide L4173-4178).")
NAME_TRUNCATED = _warning("GPL4305", "{name} has more than 15 characters: V+ knows it as {short}",
                          "Only the first 15 characters of a V+ name are significant (User's Guide "
                          "L3798-3806).")
UNKNOWN_FUNCTION = _error("GPL4306", "unknown V+ function {name}")
UNKNOWN_LABEL = _error("GPL4308", "no step label {label} in program {program}")
EXIT_OUTSIDE_LOOP = _error("GPL4309", "{word} outside a FOR, DO or WHILE loop")
REDECLARED = _warning("GPL4310", "{name} is declared again{detail}")
START_NOT_FOUND = _error("GPL4311", "--start {name}: no such program in this project")

# --- lowering ------------------------------------------------------------------------------------
GOTO_INTO_FOR = _error("GPL4700", "GOTO {label} jumps into a FOR loop from outside it, which gpl2py does not translate",
                      "A GOTO may enter an IF, CASE, WHILE or DO block, as V+ allows (the Guide's disk "
                      "example jumps into a THEN block), jump within one FOR body, and leave FOR loops; "
                      "entering a FOR loop from outside other than through its FOR "
                      "statement would skip the evaluation of its end and step, which V+ does once, when "
                      "the FOR statement runs (User's Guide L4889-4890), so the loop's END would have "
                      "nothing to test.")
EXIT_COUNT = _error("GPL4701", "{word} {count}: {reason}",
                    "EXIT n and NEXT n leave n nested FOR, DO or WHILE loops (the innermost is 1); n must "
                    "be a whole number no greater than the number of loops around the statement.")
NESTED_TOO_DEEPLY = _error(
    "GPL4702", "this statement is nested too deeply for Python: {detail}",
    "V+ nests loops deeper than CPython compiles: at most 20 loop blocks around a statement of one "
    "function (a FOR, WHILE or DO loop is one; with REACTE in the project every instruction that can "
    "fail is one more, and a program with GOTOs runs in a loop of its own) and 99 levels of "
    "indentation. Move the inner part into a program of its own and CALL it (docs/security.md, "
    "\"Nesting\").")

# --- what a line kept with an error raises -----------------------------------------------------------
#: A line translated despite one of these errors (--keep-going, or the error ignored) raises, when
#: the program reaches it, this V+ error (gpl2py.kept; docs/design/vplus.md, "Lines kept with an
#: error"), which REACTE traps; another error of a line, *Program not executable*.  (V+'s numbers
#: are not GPL's: this table is the V+ front end's, beside gpl2py.messages.RUNTIME_CODES.)  The numbers are gplrt.vplus.errors' (the translator does not import
#: the runtime): a line V+ would not have loaded is *Program not executable* (User's Guide L664; the
#: number is unconfirmed), a fault V+ finds only when the line runs is that fault's error.
PROGRAM_NOT_EXECUTABLE = -311
RUNTIME_CODES: dict[str, int] = {
    **dict.fromkeys(("GPL4001", "GPL4002", "GPL4003", "GPL4004", "GPL4100", "GPL4101", "GPL4104",
                     "GPL4105", "GPL4107", "GPL4108", "GPL4111", "GPL4303", "GPL4306", "GPL4308",
                     "GPL4309", "GPL4701"), PROGRAM_NOT_EXECUTABLE),
    "GPL4300": -402,  # *Undefined program or variable name* (L1224-1226), when the CALL runs
    "GPL4304": -407,  # *Data type mismatch*: a real stored into a location (L4009-4011)
    "GPL4700": -430,  # *Not implemented*: V+ runs it, gpl2py does not translate it
    "GPL4113": -430,
    "GPL4702": -430,
}
