"""The TMscript front end's diagnostics, GPL5000-GPL5999 (docs/design/frontends.md):
5000-5299 syntax, 5300-5699 semantics, 5700-5999 lowering and project loading.

Registered in gpl2py.messages' one registry, so explain, --select and docs/diagnostics.md see
them like GPL's."""

from __future__ import annotations

from gpl2py.messages import _error, _warning

# --- syntax (GPL5000-GPL5299) ----------------------------------------------------------------
TM_INVALID_CHAR = _error("GPL5001", "invalid character {char} in a TMscript source")
TM_UNTERMINATED_STRING = _error(
    "GPL5002", "unterminated string literal: add the closing '\"' on this line",
    "A TMscript string ends on its line; a '\"' inside is written '\"\"' (manual L591).")
TM_UNTERMINATED_COMMENT = _error("GPL5003", "'/*' comment is not closed")
TM_BAD_NUMBER = _error("GPL5004", "malformed number {text}")
TM_EXPECTED = _error("GPL5100", "expected {expected}, found {found}")
TM_EXPECTED_EXPRESSION = _error("GPL5101", "expected an expression, found {found}")
TM_TRAILING = _error(
    "GPL5102", "unexpected {found} after the end of the statement",
    "TMscript has one statement per line (manual L1351); there is no ';' between statements.")
TM_NOT_HERE = _error("GPL5103", "{what} is not allowed {where}")
TM_NOT_ASSIGNABLE = _error("GPL5104", "the left side of '{op}' must be a variable, an array element or an item")
TM_PRIORITY_ARGUMENT = _error(
    "GPL5105", "{name}() as a priority command takes a literal {allowed}",
    "Priority commands support the command definitions only, not variables (manual L18185-L18190).")

# --- semantics (GPL5300-GPL5699) -------------------------------------------------------------
TM_REDECLARED = _error(
    "GPL5300", "'{name}' is already declared{where}",
    "A local may not repeat a name of the same function or a define global (manual L1286-L1301); in "
    "a Listen node the variables of earlier packets count (L17838-L17851).")
TM_BARE_WORD = _warning(
    "GPL5301", "'{name}' is not a declared variable: it is the string \"{name}\"",
    "An undeclared word used as a value compiles as a string, with a warning (manual L602-L605).")
TM_UNKNOWN_FUNCTION = _error("GPL5302", "'{name}' is not a function of TMscript or of this project")
TM_ARGUMENT_COUNT = _error("GPL5303", "{name}() takes {expected} argument{s}, not {given}")
TM_BAD_CAST = _error("GPL5304", "cannot cast {src} to {dst}",
                     "A bool does not convert to a number and a scalar not to an array (manual L833, L874-L881).")
TM_DIVISION_BY_ZERO = _error("GPL5305", "division by zero")
TM_RETURN_VALUE = _error("GPL5306", "{what}")
TM_BREAK_OUTSIDE = _error("GPL5307", "'{word}' outside a loop{switch}")
TM_BYTE_LITERAL = _error("GPL5308", "{value} is out of the range of a byte (0 to 255)",
                         "'byte b = -100' is a compile error (manual L554-L565).")
TM_INCREMENT = _error("GPL5309", "'{op}' needs an integer variable (manual L785-L790)")
TM_MAIN_MISSING = _error("GPL5310", "the script project has no 'main' section")
TM_SECTION_TWICE = _error("GPL5311", "the '{name}' section is given twice")
TM_INTERPOLATION = _warning(
    "GPL5315", "'{name}' inside the string is replaced by the value of the variable {name} (deprecated)",
    "A variable's name in single quotes inside a string is its value, for compatibility (manual L628-L656); "
    "write \"...\" + {name} + \"...\" instead.")
TM_UNSUPPORTED = _error("GPL5314", "{what} is not supported yet by gpl2py")
TM_NOT_INDEXABLE = _error(
    "GPL5316", "{what} cannot be indexed: only an array variable or a parameterized object can",
    "Brackets follow an array (a[2]), a string's characters are not indexed, and the parameterized "
    "objects take a name (IO[\"ControlBox\"], Point[\"P1\"], manual L14365). An undeclared word is "
    "a string (GPL5301), not an object.")
TM_UNKNOWN_MEMBER = _error(
    "GPL5317", "'{name}' is not a member of {owner}",
    "The members of the teach classes (TPoint, TBase, TTCP) and of the parameterized objects (Point[...], "
    "Base[...], TCP[...], VPoint[...], IO[...], Robot[0], FT[...]) are the manual's tables (L14397-L15514); "
    "the other types have none.")
TM_READ_ONLY_MEMBER = _warning(
    "GPL5318", "{owner}.{name} is read only: assigning it is an invalid operation and changes nothing",
    "The manual marks the read-only members' writes \"Read only, invalid operation\" (L14433, L14481).")

# --- lowering and loading (GPL5700-GPL5999) --------------------------------------------------
TM_NO_SOURCES = _error("GPL5700", "{path} holds no TMscript source (.tms, .tmscript)")
TM_NESTED_TOO_DEEPLY = _error(
    "GPL5701", "this statement is nested too deeply for Python: {detail}",
    "TMscript nests loops deeper than CPython compiles: at most 20 loops (while, for, do...while) "
    "around a statement of one function, and 99 levels of indentation. Move the inner part into a "
    "function of its own (docs/security.md, \"Nesting\").")
