"""Every diagnostic gpl2py can emit: its stable code, severity and wording (mypy's message_registry).

Codes are stable: once released, a code keeps its meaning.  Ranges belong to layers so that a
newcomer can tell from the number where a message comes from:

* ``GPL1000``-``GPL1099`` lexer              * ``GPL1100``-``GPL1399`` parser
* ``GPL1400``-``GPL1499`` project loading    * ``GPL2000``-``GPL2999`` semantic analysis
* ``GPL3000``-``GPL3499`` lowering / output  * ``GPL3500``-``GPL3999`` stubs for missing code
* ``GPL9000``-``GPL9999`` internal errors and command-line usage

``docs/diagnostics.md`` is generated from this module (``python -m gpl2py.messages``); a test keeps
the two in step.  Templates use ``str.format`` fields.
"""

from __future__ import annotations

import enum
import re
import sys
from dataclasses import dataclass


class Severity(enum.Enum):
    """How bad a diagnostic is (``gpl2py.diagnostics`` re-exports it): defined here, below the
    diagnostics, so that the two modules do not import each other."""

    ERROR = "error"
    WARNING = "warning"
    NOTE = "note"

_REGISTRY: dict[str, Message] = {}


# "a {field}" in a template becomes "an {field}" when the value starts with A, E, I or O (not U:
# "a user", "a Unit"); the inserted values themselves (names, code) are never touched
_A_FIELD = re.compile(r"\b([Aa]) \{(\w+)\}")
_VOWELS = frozenset("AEIOaeio")


@dataclass(frozen=True, slots=True)
class Message:
    code: str
    severity_name: str  # "error" | "warning" | "note"
    template: str
    doc: str = ""

    @property
    def severity(self) -> Severity:
        return Severity(self.severity_name)

    @property
    def runtime(self) -> int | None:
        """The controller's error code that a line translated despite this error raises when it
        is reached (:data:`RUNTIME_CODES`), or None for an error that is not about a line the
        program runs (a project file, the command line)."""
        return RUNTIME_CODES.get(self.code)

    @property
    def notes(self) -> str:
        """``doc``, and what the translation does with a line that keeps the error."""
        runtime = self.runtime
        if runtime is None:
            return self.doc
        kept = (f"Translated anyway (--keep-going, or the error ignored), the code it affects raises "
                f"error {runtime} *{RUNTIME_TEXTS[runtime]}* when the program reaches it.")
        return f"{self.doc} {kept}" if self.doc else kept

    def format(self, **args: object) -> str:
        """The template filled in.  Templates say "a {src} value"; when the inserted word starts
        with a vowel the article becomes "an" ("an Integer value", "an Exception"), so callers
        pass bare type names.  A value longer than :data:`MAX_QUOTED` characters is cut
        (:func:`quoted`)."""
        if not args:
            return self.template
        args = {k: quoted(v) if isinstance(v, str) else v for k, v in args.items()}

        def article(m: re.Match[str]) -> str:
            value = str(args.get(m.group(2), ""))
            return f"{m.group(1)}n {{{m.group(2)}}}" if value[:1] in _VOWELS else m.group(0)

        return _A_FIELD.sub(article, self.template).format(**args)


#: The longest value a message inserts whole: a name, a literal's text, a token, a path.  A token
#: can be a whole file (a number of a million digits was quoted whole, a megabyte of message).
MAX_QUOTED = 200
_QUOTED_HEAD, _QUOTED_TAIL = 120, 60


def quoted(value: str) -> str:
    """``value``, or, when it is longer than :data:`MAX_QUOTED`, its first 120 and last 60
    characters around ``...`` (a path keeps its file name, a literal both its ends)."""
    if len(value) <= MAX_QUOTED:
        return value
    return f"{value[:_QUOTED_HEAD]}...{value[-_QUOTED_TAIL:]}"


def _error(code: str, template: str, doc: str = "") -> Message:
    return _register(Message(code, "error", template, doc))


def _warning(code: str, template: str, doc: str = "") -> Message:
    return _register(Message(code, "warning", template, doc))


def _register(message: Message) -> Message:
    if message.code in _REGISTRY:
        raise AssertionError(f"duplicate diagnostic code {message.code}")
    _REGISTRY[message.code] = message
    return message


def message(code: str) -> Message:
    """The registry entry of ``code`` (``"GPL2001"``)."""
    if code not in _REGISTRY:
        all_messages()  # (a front end's code: its module registers it)
    return _REGISTRY[code]


#: The front ends' own message modules (docs/design/frontends.md, "Diagnostics"): imported when
#: every message is listed, so explain and docs/diagnostics.md show them too.
FRONTEND_MESSAGES = ("gpl2py.vplus.messages", "gpl2py.tmscript.messages")


def all_messages() -> list[Message]:
    import importlib

    for name in FRONTEND_MESSAGES:
        importlib.import_module(name)
    return sorted(_REGISTRY.values(), key=lambda m: m.code)


# --- lexer (GPL1000-GPL1099) -------------------------------------------------------------------

LEX_INVALID_CHAR = _error(
    "GPL1001",
    "invalid character {char} in GPL source",
    "GPL source is 7-bit ASCII outside comments; a stray character (often a typographic quote or dash "
    "pasted from a document) cannot start any token.",
)
LEX_UNTERMINATED_STRING = _error(
    "GPL1002",
    "unterminated string literal: add the closing '\"' on this line",
    "String literals cannot span lines; use ' _' continuation and '&' to build long strings.",
)
LEX_LONG_STRING = _warning(
    "GPL1003",
    "string literal is {length} characters long; the manual limits string literals to 128",
    "The manual limits literals (not String values) to 128 characters (spec AMB-35).",
)
LEX_NON_ASCII_STRING = _error(
    "GPL1004",
    "non-ASCII character {char} in a string literal; GPL strings are 7-bit ASCII (use Chr())",
)
LEX_COMMENT_AFTER_CONTINUATION = _warning(
    "GPL1005",
    "comment after the line continuation ' _'; GPL may reject this, the comment is kept as a "
    "trailing comment of the statement",
    "VB forbids it; exported GPL code sometimes has it, so gpl2py accepts it and keeps the text.",
)
LEX_LITERAL_SUFFIX = _error(
    "GPL1006",
    "type character or suffix '{suffix}' after the number {number} is not supported in GPL",
    "GPL has no literal type characters (725L, 1.5!, ...); separate the number from the next word.",
)
LEX_LITERAL_RANGE = _error(
    "GPL1007",
    "numeric literal {text} is out of range",
    "Hex and octal literals are 32-bit; reals, and decimal integers (one past the Integer range is "
    "a Double), must fit in a Double.",
)
LEX_CONDITIONAL_DIRECTIVE = _warning(
    "GPL1008",
    "'{directive}' line is ignored: GPL has no conditional compilation, both branches are compiled",
    "Lines starting with '#' are ignored by GPL (spec §1.4, AMB-27).",
)
LEX_LONG_IDENTIFIER = _error(
    "GPL1009",
    "name '{name}...' is {length} characters long; GPL names have at most 128 characters",
)
LEX_MISPLACED_HASH = _error(
    "GPL1010",
    "'#' must be the first character of a line (a '#Region' style line)",
)

# --- parser (GPL1100-GPL1399) ------------------------------------------------------------------

PARSE_EXPECTED = _error("GPL1100", "expected {expected}, found {found}")
PARSE_EXPECTED_EXPRESSION = _error("GPL1101", "expected an expression, found {found}")
PARSE_TRAILING_TOKENS = _error(
    "GPL1102",
    "unexpected {found} after the end of the statement",
    "GPL allows one statement per line; anything after a complete statement must be a comment.",
)
PARSE_UNSUPPORTED = _error(
    "GPL1103",
    "{what} is not supported in GPL{hint}",
    "A Visual Basic construct that the GPL manuals exclude or never document (spec §15).",
)
PARSE_UNMATCHED_END = _error(
    "GPL1104",
    "'{closer}' without a matching '{opener}'",
)
PARSE_UNCLOSED_BLOCK = _error(
    "GPL1105",
    "'{opener}' block is not closed: expected '{closer}' before {found}",
    "Reported at the statement that opens the block.",
)
# GPL1106 (a declaration inside a block) is retired, never to be reused: the manual (§3.2.6) forbids
# it, but the vendor's code declares inside If/Select/For blocks and the controller compiles it
# (docs/design/real-code.md).
PARSE_MISSING_TYPE = _error(
    "GPL1107",
    "'{name}' has no type: add an 'As' clause",
    "The data type must always be specified (manual §3.2.8).",
)
PARSE_NOT_A_STATEMENT = _error(
    "GPL1108",
    "{what} cannot be used as a statement",
)
PARSE_STATEMENT_OUTSIDE_PROCEDURE = _error(
    "GPL1109",
    "statements must be inside a Sub, Function or Property; found {found} in {container}",
)
PARSE_OUTSIDE_MODULE = _error(
    "GPL1110",
    "{what} must be declared inside a Module",
    "Only modules (and, as an extension, classes) may appear at the outer level of a file.",
)
PARSE_COLON_SEPARATOR = _error(
    "GPL1111",
    "':' cannot separate statements in GPL (one statement per line)",
    "A ':' is only valid after a label at the start of a line.  A line with only ':' is a "
    "documentation ellipsis in the manuals, not code.",
)
PARSE_NEW_NEEDS_ONE_NAME = _error(
    "GPL1112",
    "a declaration with 'New' or '=' must declare exactly one variable",
    "Manual §3.2.9-3.2.11.",
)
PARSE_ARRAY_INITIALIZER = _error(
    "GPL1113",
    "array variables cannot have an initializer in GPL",
)
PARSE_ARRAY_RANK = _error(
    "GPL1114",
    "arrays have 1 to 4 dimensions; '{name}' has {rank}",
)
PARSE_DUPLICATE_CLAUSE = _error(
    "GPL1115",
    "a Try statement has at most one {clause}",
)
PARSE_CATCH_NEEDS_VARIABLE = _error(
    "GPL1116",
    "Catch needs an exception variable in GPL (for example 'Catch ex')",
)
PARSE_TOO_DEEP = _error(
    "GPL1117",
    "{what} nested too deeply (more than {limit} levels)",
)
PARSE_ELSE_IF = _warning(
    "GPL1118",
    "'Else If' on one line is read as 'ElseIf'",
)
PARSE_BLOCK_IN_SINGLE_LINE_IF = _error(
    "GPL1119",
    "{what} cannot appear in a single-line If; use a block If ... End If",
)
PARSE_FUNCTION_NEEDS_TYPE = _error(
    "GPL1120",
    "{what} '{name}' needs a return type ('As type')",
)
PARSE_PROPERTY_NEEDS_ACCESSOR = _error(
    "GPL1121",
    "Property '{name}' needs a Get or a Set block",
)
PARSE_DO_TWO_CONDITIONS = _error(
    "GPL1122",
    "a Do loop can test its condition at the top or at the bottom, not both",
)
PARSE_MISPLACED_DECLARATION = _error(
    "GPL1123",
    "{what} cannot be declared {where}",
)
PARSE_CASE_OUTSIDE_SELECT = _error(
    "GPL1124",
    "statements in a Select must follow a 'Case' line",
)
PARSE_BAD_MODIFIER = _error(
    "GPL1125",
    "'{modifier}' is not allowed {where}",
)

# --- project loading (GPL1400-GPL1499) ---------------------------------------------------------

PATH_NOT_FOUND = _error(
    "GPL1400",
    "no such file or folder: {path}",
    "The path given to gpl2py does not exist.",
)
NOT_A_PROJECT = _error(
    "GPL1401",
    "not a GPL project or source file: {path}",
    "gpl2py reads a project folder, a Project.gpr file, or a single .gpl/.gpo source file.",
)
NO_SOURCES = _error(
    "GPL1402",
    "no GPL source files (.gpl, .gpo) in {path}",
    "A folder without Project.gpr is read as every .gpl/.gpo file in it; this one has none.",
)
CANNOT_READ = _error(
    "GPL1403",
    "cannot read {path}: {reason}",
    "The operating system refused to read the file (permissions, a folder where a file was expected, ...).",
)
BINARY_FILE = _error(
    "GPL1404",
    "{path} is not a text file: {what}",
    "GPL sources are ASCII text. NUL bytes, UTF-16 encoding or mostly control characters mean the file "
    "is binary or was saved in the wrong encoding; re-save it as ASCII.",
)
SOURCE_NOT_FOUND = _error(
    "GPL1405",
    "source file {name} named in Project.gpr not found in {folder}",
    "Every ProjectSource line must name a file in the project folder (names are matched "
    "case-insensitively, as on the controller).",
)
PROTECTED_SKIPPED = _warning(
    "GPL1406",
    "skipping vendor-protected file {name}: protected (.gpp) sources cannot be read or translated",
    "A .gpp file (or any file starting with '#Protected|) is encrypted vendor code. The rest of the "
    "project is still translated; calls into the protected code will not resolve.",
)
GPR_BAD_LINE = _error(
    "GPL1407",
    "cannot understand this Project.gpr line; expected KEY=\"value\"",
    "Project.gpr holds one KEY=\"value\" per line between ProjectBegin and ProjectEnd; lines "
    "starting with ' are comments.",
)
GPR_UNKNOWN_KEY = _warning(
    "GPL1408",
    "unknown Project.gpr key {key}; kept but not used",
    "gpl2py understands ProjectName, ProjectStart and ProjectSource. Other keys are kept in "
    "Project.extra_keys so later tools can read them.",
)
GPR_MISSING_BEGIN = _error(
    "GPL1409",
    "Project.gpr does not start with ProjectBegin",
    "The first line that is not a ' comment must be ProjectBegin.",
)
GPR_MISSING_END = _error(
    "GPL1410",
    "Project.gpr has no ProjectEnd",
    "The file is probably truncated; the lines read so far are used.",
)
GPR_TEXT_AFTER_END = _warning(
    "GPL1411",
    "text after ProjectEnd is ignored",
    "",
)
GPR_DUPLICATE_KEY = _warning(
    "GPL1412",
    "{key} given more than once; the first value {value} is used",
    "ProjectName and ProjectStart may appear once.",
)
GPR_DUPLICATE_SOURCE = _warning(
    "GPL1413",
    "source file {name} is listed more than once; later entries are ignored",
    "Each module is loaded once, at its first position in the ProjectSource order.",
)
GPR_NO_START = _warning(
    "GPL1414",
    "Project.gpr has no ProjectStart; the project has no start procedure",
    "The project can be checked and imported, but not run on its own.",
)
GPR_NO_SOURCES = _error(
    "GPL1415",
    "Project.gpr lists no ProjectSource files",
    "",
)
GPR_BAD_SOURCE_NAME = _error(
    "GPL1416",
    "source file name {name} must be a plain file name inside the project folder",
    "ProjectSource names a file in the project folder; absolute paths and '..' are not allowed.",
)
GPR_BAD_EXTENSION = _error(
    "GPL1417",
    "source file {name} is not a GPL source (.gpl, .gpo or .gpp)",
    "",
)
AMBIGUOUS_FILE_NAME = _warning(
    "GPL1418",
    "{name} matches several files that differ only in case ({candidates}); using {chosen}",
    "The controller's file system is case-insensitive, so only one of these files could exist there.",
)
GPR_EMPTY_VALUE = _error(
    "GPL1419",
    "{key} has an empty value",
    "",
)

SOURCE_NOT_REGULAR = _error(
    "GPL1420",
    "{path} is not a regular file ({what}); GPL sources are files",
    "Only regular files are read: a device (/dev/zero never ends), a pipe (nothing may ever be "
    "written to it) or a socket named as a source would make gpl2py wait or read forever "
    "(docs/security.md).",
)
SOURCE_TOO_LARGE = _error(
    "GPL1421",
    "{path} is {size}, more than the {limit} gpl2py reads from one file",
    "A real GPL source is far smaller (the TCS's largest is under 200 kB). The limit keeps a "
    "hostile or mistaken input from taking minutes and gigabytes; raise it with --max-source-mb "
    "or GPL2PY_MAX_SOURCE_MB (docs/security.md, \"Input size\").",
)
PROJECT_TOO_LARGE = _error(
    "GPL1422",
    "the project's sources pass {limit} with {path}; it and the files after it are not read",
    "All sources of a project together may be four times the size of one file "
    "(--max-source-mb, GPL2PY_MAX_SOURCE_MB).",
)
SOURCE_OUTSIDE_PROJECT = _error(
    "GPL1423",
    "{path} is a link to {target}, outside the project folder; sources must be inside it",
    "A project names files in its own folder (ProjectSource names with '..' or an absolute path are "
    "refused too): a link out of it could make gpl2py show the lines of any file on the machine "
    "in its diagnostics or comments (docs/security.md).",
)


# --- semantic analysis (GPL2000-GPL2999) -------------------------------------------------------

UNDECLARED_NAME = _error(
    "GPL2001",
    "'{name}' is not declared",
    "Every variable must be declared with Dim, Static, Const, Public or Private (spec §6.1); "
    "check the spelling, or qualify a name from another module as Module.Name.",
)
DUPLICATE_DECLARATION = _error(
    "GPL2002",
    "'{name}' is already declared in this {scope} (line {line})",
    "Names must be unique within a procedure, class or module regardless of their kind (§6.4). "
    "One exception, from real code: Dims of one name and one type in two blocks of a procedure that "
    "do not contain one another (Then and Else, two Cases) declare the same local again.",
)
UNKNOWN_TYPE = _error(
    "GPL2003",
    "unknown type '{name}'",
    "A type is a primitive (Integer, Double, String ...), a built-in class or a class declared in "
    "the project (qualified as Module.Class from another module).",
)
WRONG_ARG_COUNT = _error(
    "GPL2004",
    "'{name}' takes {expected} argument(s), {given} given",
    "GPL has no ParamArray; Optional parameters (an extension) may be left out.",
)
TYPE_MISMATCH = _error(
    "GPL2005",
    "type mismatch: a {src} value cannot be used as {dst}",
    "Numbers, Booleans and Strings convert into each other (§4.2); objects and arrays only "
    "match their own class or element type (§4.2 rule 12).",
)
AMBIGUOUS_NAME = _error(
    "GPL2006",
    "'{name}' is ambiguous: it is Public in modules {where}; qualify it as Module.{name}",
    "The module prefix may be omitted only when the Public name is unique among all modules (§6.4).",
)
NO_SUCH_MEMBER = _error(
    "GPL2007",
    "{owner} has no member '{member}'",
    "",
)
NOT_ASSIGNABLE = _error(
    "GPL2008",
    "cannot assign to {what}",
    "Only variables, array elements, fields and properties with a Set block can be assigned (§10.1).",
)
SUB_AS_VALUE = _error(
    "GPL2009",
    "'{name}' is a Sub and has no value",
    "A Sub call is a statement by itself; only a Function can appear in an expression (§9.1).",
)
PRIVATE_MEMBER = _error(
    "GPL2010",
    "'{name}' is Private to {owner}",
    "Module and class members are Private by default (§6.4); declare it Public to use it here.",
)
NOT_INDEXABLE = _error(
    "GPL2012",
    "'{name}' is not an array, procedure or delegate and cannot take arguments",
    "",
)
NO_CTOR_OVERLOAD = _error(
    "GPL2013",
    "no Sub New of {cls} takes {count} argument(s) of these types",
    "Overloads of New are chosen by argument count, then by argument types (§8.3).",
)
BAD_OPERANDS = _error(
    "GPL2014",
    "operator {op} cannot be applied to {left} and {right}",
    "Arithmetic needs numbers, Booleans or Strings; 'Is' compares object references (§4.4).",
)
BAD_RETURN = _error(
    "GPL2015",
    "{detail}",
    "A Function returns a value with 'Return expr'; a Sub uses 'Return' without a value (§9.1).",
)
EXIT_OUTSIDE = _error(
    "GPL2016",
    "'Exit {kind}' is not inside a {kind} block",
    "",
)
UNKNOWN_LABEL = _error(
    "GPL2017",
    "label '{name}' is not defined in this procedure",
    "GoTo targets a label in the same procedure (§10.7).",
)
DUPLICATE_LABEL = _error(
    "GPL2018",
    "label '{name}' is defined twice in this procedure",
    "",
)
START_NOT_FOUND = _error(
    "GPL2019",
    "the start procedure '{name}' is not a Sub of this project",
    "ProjectStart names a Public Sub without parameters, as 'Proc' or 'Module.Proc' (§12.3).",
)
BYREF_TEMPORARY = _warning(
    "GPL2020",
    "argument for ByRef parameter '{name}' is not a variable; the procedure gets a temporary copy",
    "Only variables, array elements and fields can be passed by reference (§9.3, AMB-33).",
)
ME_OUTSIDE_INSTANCE = _error(
    "GPL2021",
    "'Me' can only be used in a non-Shared procedure of a class",
    "§8.3: Me is the object of the current instance procedure.",
)
PROPERTY_ACCESS = _error(
    "GPL2022",
    "property '{name}' is {what}",
    "A property with only Get cannot be assigned; one with only Set cannot be read (§8.3).",
)
NOT_A_VALUE = _error(
    "GPL2023",
    "'{name}' is a {what}, not a value",
    "",
)
SUBSCRIPT_COUNT = _error(
    "GPL2024",
    "'{name}' has {rank} dimension(s) but {given} subscript(s) are given",
    "",
)
START_NOT_PUBLIC = _warning(
    "GPL2025",
    "the start procedure '{name}' should be declared Public",
    "The manual requires a Public start procedure (§12.3); it is started anyway (AMB-20).",
)
NOT_AN_ARRAY = _error(
    "GPL2026",
    "'{name}' is not an array",
    "ReDim and array members apply to array variables (§7).",
)
CONST_ASSIGN = _error(
    "GPL2027",
    "'{name}' is a Const and cannot be assigned",
    "Only the declaration's initializer sets a Const (§6.2).",
)
NOT_AN_OBJECT = _error(
    "GPL2028",
    "a {type} value has no member '{member}'",
    "",
)
ADDRESSOF_TARGET = _error(
    "GPL2029",
    "AddressOf needs a procedure, not {what}",
    "A delegate is bound to a Sub or Function, or to a method of an object (§9.4).",
)
RESERVED_NAME = _error(
    "GPL2030",
    "'{name}' is reserved for procedures the controller generates",
    "_Init and _New are generated by the GPL compiler and cannot be declared (§8.3, §12.2).",
)

IMPLICIT_TO_STRING = _warning(
    "GPL2031",
    "a {src} value is stored into a String without CStr; it is converted with the CStr rules",
    "The manuals always convert numbers to text with CStr; the implicit conversion is accepted "
    "(spec AMB-11).",
)
START_ASSUMED_MAIN = _warning(
    "GPL2032",
    "the project names no start procedure (no Project.gpr or no ProjectStart): starting {name}, "
    "its only Public Sub Main",
    "A folder without Project.gpr, or a single file, runs its one Public parameterless Sub Main "
    "(gpl2py's decision; a controller needs ProjectStart). With none or several, the package can "
    "be imported but not run.",
)
REQUIRED_AFTER_OPTIONAL = _error(
    "GPL2033",
    "parameter '{name}' follows an Optional parameter and must be Optional too",
    "Optional parameters (an extension, as in VB) come last: arguments are matched by position, "
    "so a required one after an Optional one could never be left out.",
)
START_PROTECTED = _error(
    "GPL2034",
    "the start procedure '{name}' is not in the readable sources: it is presumably in a protected "
    "(.gpp) source, whose code is not available, so the project cannot be started from it",
    "Reported instead of GPL2019 when the project has protected files (GPL1406): gpl2py skips them, "
    "so a ProjectStart defined there cannot be translated or run. Name a readable Public Sub as "
    "ProjectStart (for example a small Main that calls into the rest) to translate the project.",
)
NO_OBJECT_TYPE = _error(
    "GPL2035",
    "GPL has no Object type: declare the class of the objects it holds (late binding is not supported)",
    "Manual [000 L852-855]: every object in GPL has an explicit class; a variable, parameter or "
    "result cannot be declared As Object (unless the project itself declares a class named Object).",
)
NEW_OF_GLOBAL_CLASS = _error(
    "GPL2036",
    "'{cls}' has only Shared members and cannot be created with New",
    "Move, Robot, Controller, Signal, Math and Console exist once per controller; a variable of such "
    "a class (real code declares them as shorthands) reaches the Shared members without an object.",
)

AMBIGUOUS_OVERLOAD = _error(
    "GPL2040",
    "the call of '{name}' is ambiguous: {candidates} fit these arguments equally well",
    "Overloads are chosen by argument count, then by how little converting the arguments costs "
    "(same type, then widening numbers, then narrowing, then String <-> number); convert an "
    "argument (CInt, CDbl, CStr ...) so that one overload fits best.",
)
NO_OVERLOAD = _error(
    "GPL2041",
    "no overload of '{name}' takes {count} argument(s) of these types; declared: {candidates}",
    "Each call must fit one of the procedure's parameter lists in number and types (an object "
    "only fits a parameter of its own class).",
)
CONST_CYCLE = _error(
    "GPL2042",
    "Const '{name}' is defined in terms of itself: {cycle}",
    "Constants are evaluated when the project is translated, whatever the module order; a chain "
    "of Consts that leads back to its start has no value.",
)

# --- lowering and output (GPL3000-GPL3499) -----------------------------------------------------

GOTO_INTO_BLOCK = _error(
    "GPL3001",
    "GoTo {name} jumps into a For loop from outside it; a For body is entered only through its "
    "For line",
    "A jump into a For body would leave the loop's saved limit and step undefined (§10.7); VB "
    "rejects it too. Jumps into an If, ElseIf, Else, While, Do or Case body are accepted (the "
    "statement is entered past its test), as are jumps out of any block.",
)
GOTO_ACROSS_TRY = _error(
    "GPL3002",
    "GoTo {name} enters a Try, Catch or Finally block from outside it, or leaves a Finally block; "
    "only a Catch may jump back into its own Try",
    "Such a jump has no defined meaning (§11.3) and VB rejects it too. A jump out of a Try or Catch "
    "block is accepted: the manual calls it illegal, but the vendor's TCS makes it and the "
    "controller runs it (docs/design/real-code.md; the Finally runs on the way out).",
)
EXIT_TRY_IN_FINALLY = _error(
    "GPL3003",
    "'Exit Try' is not allowed in a Finally block",
    "§11.4.",
)
# GPL3006 (a GoTo out of a Try or Catch block) is retired, never to be reused: the manual (§11.3)
# calls the jump illegal, but the vendor's TCS jumps out of a Try (Class_command.gpl:288) and the
# controller compiles and runs it (docs/design/real-code.md).
OUTPUT_ERROR = _error(
    "GPL3004",
    "cannot write {path}: {detail}",
    "",
)
NOT_SUPPORTED = _error(
    "GPL3005",
    "{what} is not supported by the transpiler",
    "",
)
NESTED_TOO_DEEPLY = _error(
    "GPL3007",
    "this statement is nested too deeply for Python: {detail}",
    "GPL allows deeper nesting than CPython compiles: at most 20 loop and try blocks around a "
    "statement of one function (a For over a variable range is 2, a Catch 2, a Catch with a "
    "Finally 3) and at most 99 levels of indentation (a method's body starts inside its classes). "
    "Move the inner part into a Sub or Function of its own (docs/security.md, \"Nesting\").",
)

# --- stubs for missing code (GPL3500-GPL3999) --------------------------------------------------

STUB_PROTECTED = _warning(
    "GPL3501",
    "'{name}' is not declared in the readable sources; assuming the protected code defines it: "
    "{consequence}",
    "Reported once per name, only in projects with protected (.gpp) files (elsewhere an unknown "
    "name stays error GPL2001). Without an implementation the message says that a stub raising "
    "-204 is generated; the rest of the project runs. Supply a Python implementation with --stubs "
    "DIR (the message then names the file; gpl2py ships a few stand-ins of its own, used when "
    "--stubs has none), or make this an error with --strict (same code, severity error; the "
    "message then says so).",
)
STUB_BUILTIN_MEMBER = _warning(
    "GPL3502",
    "{owner} has no member '{member}' in the simulated controller: {consequence}",
    "Reported once per member. The member may exist on a newer controller, or is not simulated. "
    "Supply a Python implementation with --stubs DIR, or make this an error with --strict (same code, "
    "severity error).",
)
# The {consequence} of GPL3501 and GPL3502: what becomes of the stub, as it happens.
STUB_RAISES = "a stub is generated that raises error -204 if the program uses it"
STUB_IMPLEMENTED = "{provider} implements it"
STUB_STRICT = "--strict makes every stub an error, so nothing is generated for it"
STUB_IMPLEMENTED_STRICT = "{provider} implements it, but --strict makes every stub an error"

STUBS_DIR_ERROR = _error(
    "GPL3503",
    "--stubs {path}: {detail}",
    "The --stubs folder must exist and hold Python files that parse.",
)

# --- internal and usage (GPL9000-GPL9999) ------------------------------------------------------

INTERNAL_ERROR = _error(
    "GPL9000",
    "internal error in gpl2py while processing this input: {detail}",
    "A bug in gpl2py, never in your program. Please report it with the input that caused it. "
    "Exit status 2, as for a wrong command line: gpl2py could not do its job (set "
    "GPL2PY_TRACEBACK=1 to see the Python traceback).",
)
USAGE_ERROR = _error(
    "GPL9001",
    "{detail}",
    "The command line is wrong (unknown command or option, missing argument). Run gpl2py --help. "
    "Exit status 2.",
)
DUMP_AST_NEEDS_FILE = _error(
    "GPL9002",
    "dump-ast takes one .gpl or .gpo source file, not {path}",
    "To check a whole project use gpl2py check. Exit status 2.",
)

CONFIG_ERROR = _error(
    "GPL9003",
    "{path}: {detail}",
    "The [tool.gpl2py] table of pyproject.toml is wrong: not valid TOML, an unknown key, or a value "
    "of the wrong type (docs/cli.md, \"Configuration\"). Exit status 2, as for the command line.",
)
BAD_SUPPRESSION = _warning(
    "GPL9004",
    "'{code}' in a gpl2py: ignore comment suppresses nothing: {problem}",
    "A ' gpl2py: ignore[...] comment names codes (GPL2014) or their prefixes (GPL20), separated by "
    "commas; ' gpl2py: ignore without brackets suppresses every diagnostic of its line.",
)


# --- what a line translated despite an error raises ------------------------------------------

#: The run-time error of code translated despite its error (``--keep-going``, ``--ignore``, a
#: ``gpl2py: ignore`` comment): the controller's own error for the same fault, from its error
#: table (spec/gpl-dictionary.md §8; the numbers are the controller's, the texts its messages), so
#: that the program's Try/Catch can handle it as it would handle any GPL error.  The controller
#: itself refuses to start a project that does not compile (-742 *Compilation errors*); gpl2py
#: runs the rest of it, and the line that did not compile raises the error the controller's
#: compiler names.  An error with no code here (a Project.gpr line, the command line) is about no
#: line the program runs.  docs/design/lowering.md, "Code that keeps an error".
RUNTIME_CODES: dict[str, int] = {
    "GPL1001": -720, "GPL1002": -704, "GPL1004": -720, "GPL1006": -717, "GPL1007": -706,
    "GPL1009": -713, "GPL1010": -720,
    "GPL1100": -712, "GPL1101": -712, "GPL1102": -722, "GPL1103": -712, "GPL1104": -724,
    "GPL1105": -748, "GPL1107": -726, "GPL1108": -712, "GPL1109": -733, "GPL1110": -733,
    "GPL1111": -722, "GPL1112": -761, "GPL1113": -790, "GPL1114": -766, "GPL1115": -748,
    "GPL1116": -712, "GPL1117": -735, "GPL1119": -712, "GPL1120": -726, "GPL1121": -784,
    "GPL1122": -712, "GPL1123": -733, "GPL1124": -748, "GPL1125": -719,
    "GPL2001": -729, "GPL2002": -727, "GPL2003": -725, "GPL2004": -741, "GPL2005": -738,
    "GPL2006": -772, "GPL2007": -729, "GPL2008": -760, "GPL2009": -730, "GPL2010": -729,
    "GPL2012": -730, "GPL2013": -741, "GPL2014": -738, "GPL2015": -712, "GPL2016": -748,
    "GPL2017": -723, "GPL2018": -736, "GPL2021": -787, "GPL2022": -784, "GPL2023": -730,
    "GPL2024": -766, "GPL2026": -730, "GPL2027": -760, "GPL2028": -729, "GPL2029": -780,
    "GPL2030": -721, "GPL2033": -741, "GPL2035": -725, "GPL2036": -778, "GPL2040": -764,
    "GPL2041": -741, "GPL2042": -790,
    # GoTo and Exit Try: a branch the controller does not permit
    "GPL3001": -785, "GPL3002": -785, "GPL3003": -785,
    # what gpl2py cannot translate (the controller runs it): as a stub, -204 Not implemented
    "GPL3005": -204, "GPL3007": -204,
}
#: The controller's texts of the codes above (gplrt.lang.error_codes has them all; the
#: translator does not import the runtime).
RUNTIME_TEXTS: dict[int, str] = {
    -204: "Not implemented", -704: "Missing quote mark", -706: "Value too large",
    -712: "Invalid syntax", -713: "Symbol too long", -717: "Invalid number format",
    -719: "Illegal use of keyword", -720: "Unexpected character in expression",
    -721: "Conflict with reserved keyword", -722: "Unexpected text at end of line",
    -723: "Invalid statement label", -724: "Invalid End keyword", -725: "Unknown data type",
    -726: "Data type required", -727: "Cannot redefine symbol", -729: "Undefined symbol",
    -730: "Invalid symbol type", -733: "Not a top-level statement", -735: "Too many nested blocks",
    -736: "Duplicate statement label", -738: "Invalid data type", -741: "Argument mismatch",
    -742: "Compilation errors", -748: "No matching control structure",
    -760: "Invalid assignment", -761: "Cannot have list of variables", -764: "Invalid procedure overload",
    -766: "Array index mismatch", -772: "Ambiguous Public reference", -778: "Objects not allowed for class",
    -780: "Unsupported procedure reference", -784: "Invalid property", -785: "Branch not permitted",
    -787: "Invalid in shared procedure", -790: "Invalid static initializer",
}
#: What code raises when the error that took its meaning is not known (an error reported on
#: another line of a continued statement): the controller's refusal of a project that does not compile.
COMPILATION_ERRORS = -742


def markdown() -> str:
    """The text of docs/diagnostics.md."""
    out = [
        "# gpl2py diagnostics",
        "",
        "Generated from `gpl2py/messages.py` by `python -m gpl2py.messages > docs/diagnostics.md`;",
        "do not edit by hand. Codes are stable. Each diagnostic prints as",
        "`path:line:col: severity GPLnnnn: message`, followed by the source line and a caret.",
        "A source line over 200 characters is shown as a window of 200 around the column, a value",
        "a message quotes (a name, a literal) as its first 120 and last 60 characters when over 200.",
        "",
        "| Code | Severity | Message | Notes |",
        "|---|---|---|---|",
    ]
    for m in all_messages():
        text = m.template.replace("|", "\\|")
        doc = m.notes.replace("|", "\\|")
        out.append(f"| {m.code} | {m.severity_name} | {text} | {doc} |")
    return "\n".join(out) + "\n"


if __name__ == "__main__":
    # (run as __main__, this module is a second copy; the front ends register into gpl2py.messages)
    from gpl2py.messages import markdown as _markdown

    sys.stdout.write(_markdown())
