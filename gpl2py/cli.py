"""The ``gpl2py`` command: argument parsing, running one subcommand, printing diagnostics, exit codes.

Structure: every subcommand is a :class:`Command` (its name, help, how it adds its arguments, and the
function that runs it) in ``COMMANDS``.  The bare form ``gpl2py PROJECT -o OUT`` is handled by
:func:`_route`: when the first argument is not a known command, it is handed to the command marked
``default=True`` (``translate``).

Output contract (``--output-format``, ``gpl2py.formats``):

* ``text``: diagnostics (sorted by file, line, column, each with a caret excerpt; coloured on a
  terminal) on **stderr**, a one-line summary on stderr unless ``--quiet``; stdout carries only
  the command's product (the AST dump), so it can be piped;
* ``json`` (also ``--json``): stdout is exactly one JSON object with ``"schema_version"``, a
  ``"diagnostics"`` list (plus the command's product, e.g. ``"ast"``), nothing on stderr.
  ``--quiet`` does not filter JSON: a program reading it can filter by ``severity`` itself;
* ``sarif``: stdout is one SARIF 2.1.0 log, nothing on stderr;
* ``github``: stdout has one GitHub Actions annotation per diagnostic, the summary on stderr.

Which diagnostics are reported at all is the sink's filter (``gpl2py.selection``: --select,
--ignore, ``' gpl2py: ignore`` comments); defaults come from ``[tool.gpl2py]`` (``gpl2py.config``).

Exit status: 0 no errors (warnings allowed), 1 errors in the input, 2 gpl2py could not do its job:
the command line itself is wrong (GPL9001/GPL9002) or gpl2py failed internally (GPL9000), as ruff
and mypy use 2.  No input produces a Python traceback: an unexpected exception becomes GPL9000 (set
``GPL2PY_TRACEBACK=1`` to see the traceback instead).
"""

from __future__ import annotations

import argparse
import difflib
import os
import re
import sys
import textwrap
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import NoReturn, TextIO

from gpl2py import __version__
from gpl2py import messages as msg
from gpl2py.config import FILE_NAME, Config, ConfigError, discover
from gpl2py.diagnostics import DiagnosticSink, internal_error_span
from gpl2py.formats import FORMATS, wants_colour
from gpl2py.interrupts import stop_status
from gpl2py.outcome import (  # the pieces ``run`` shares (gpl2py.outcome says why they live there)
    Display,
    Outcome,
    add_project_options,
    counts as _counts,
    emit as _emit,
    limits_of,
    new_sink,
    remember as _remember,
)
from gpl2py.project import SOURCE_SUFFIXES, Project, load_project
from gpl2py.selection import Selection, parse_codes
from gpl2py.source import SourceFile

EXIT_OK = 0
EXIT_ERRORS = 1
EXIT_USAGE = 2  # also an internal error (GPL9000): gpl2py, not the input, is at fault
EXIT_OUTPUT_CLOSED = 141  # 128 + SIGPIPE: the reader of our output went away (| head)

_EPILOG = """\
exit status:
  0  no errors (warnings do not change the status)
  1  errors in the GPL input
  2  the command line is wrong (unknown command or option, missing argument),
     or gpl2py failed internally (GPL9000: a bug in gpl2py, please report it)
  141 the output was closed by its reader (gpl2py ... | head): gpl2py stopped quietly
  gpl2py run adds 3 (a GPL thread ended with an unhandled error), 4 (the program
  stalled), 130 (Ctrl-C) and 143 (SIGTERM): see gpl2py run --help

Every diagnostic has a stable code, e.g. "Main.gpl:12:5: error GPL1101: ...";
docs/diagnostics.md explains each code.
"""


class UsageError(Exception):
    """The command line is wrong; carries the message for GPL9001."""


@dataclass(frozen=True)
class Command:
    """One subcommand: ``configure`` adds its arguments, ``run`` does the work."""

    name: str
    help: str
    description: str
    configure: Callable[[argparse.ArgumentParser], None]
    run: Callable[[argparse.Namespace], Outcome]
    default: bool = False  # receives the arguments when the first one is not a command name
    #: replaces the common exit-status text in --help; a function, so that a command's module is
    #: imported only when its parser is built
    epilog: Callable[[], str] | None = None


# --- commands -----------------------------------------------------------------------------------


def _configure_check(parser: argparse.ArgumentParser) -> None:
    parser.add_argument(
        "paths",
        metavar="PATH",
        nargs="*",
        help="a project folder (with or without Project.gpr), a Project.gpr file, or a single "
        ".gpl/.gpo file; several are checked one after the other (default: paths in [tool.gpl2py])",
    )
    add_project_options(parser)


def _run_check(args: argparse.Namespace) -> Outcome:
    """Check every project named, collecting all diagnostics in one run (:func:`check_project`)."""
    out = Outcome(sink=new_sink(args))
    for path in args.paths:
        check_project(path, args, out)
    return out


def check_project(path: str, args: argparse.Namespace, out: Outcome) -> None:
    """Load the project, parse every source and run the semantic pass (names, types, calls: what a
    porting engineer wants to know), collecting all diagnostics in one run.  Nothing is written.

    It is the translation's own pipeline (``gpl2py.transpile``) without keeping the generated
    text, so ``check`` reports exactly what ``translate`` reports: when the analysis finds no
    error, the translation's own checks run too (GoTo targets, nesting that Python cannot
    compile: lowering, in memory), names that only protected (.gpp) files define are stub
    warnings (GPL3501; ``--strict`` makes them errors), ``--stubs DIR`` is read and refused
    (GPL3503) alike, and an internal error in one file leaves the others' diagnostics reported.
    The project's own diagnostics decide (a sink of its own), so the errors of another project
    checked in the same call change nothing here."""
    from gpl2py.transpile import transpile

    sink = out.sink.child()

    def on_load(project: Project) -> None:
        _remember(out, project)
        watch_sources(project, sink)
        out.checked += len(project.sources)

    try:
        transpile(path, sink, stubs_dir=args.stubs, strict=args.strict, loaded=on_load,
                  limits=limits_of(args), keep_modules=False, language=args.language,
                  start=args.start)
    finally:
        out.sink.extend(sink)


def watch_sources(project: Project, sink: DiagnosticSink) -> None:
    """Hand the project's sources to the sink's filter, for their ``gpl2py: ignore`` comments
    (before they are parsed, so the parser's diagnostics are filtered too)."""
    if sink.filter is not None:
        sink.filter.add_sources(project.sources, sink)


def _configure_dump_ast(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("file", metavar="FILE", help="one .gpl or .gpo source file")


def _run_dump_ast(args: argparse.Namespace) -> Outcome:
    """Parse one file and print its syntax tree (for debugging the front end)."""
    from gpl2py.gpl.syntax.ast import dump

    out = Outcome(product_key="ast")
    path = Path(args.file)
    if path.exists() and (path.is_dir() or path.suffix.lower() not in SOURCE_SUFFIXES):
        out.sink.report(msg.DUMP_AST_NEEDS_FILE, None, path=str(path))
        out.usage_error = True
        return out
    project = load_project(path, out.sink)
    if project is None or not project.sources:
        return out
    _remember(out, project)
    unit = _parse(project.sources[0], out.sink)
    out.checked = 1
    out.product = dump(unit)
    return out


def _configure_explain(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("code", metavar="CODE",
                        help="a diagnostic code (GPL2014), or the start of one (GPL20) to list a range")


def _run_explain(args: argparse.Namespace) -> Outcome:
    """Print a code's documentation from the installed package (``gpl2py.messages``, the source of
    docs/diagnostics.md): its severity, message and notes; a prefix lists the codes it covers."""
    out = Outcome(product_key="explain", counts=False)
    code = args.code.strip().upper()
    if code.isdigit():
        code = f"GPL{code}"
    found = [m for m in msg.all_messages() if m.code.startswith(code)] if re.fullmatch(r"GPL\d{0,4}", code) else []
    if not found:
        codes = [m.code for m in msg.all_messages()]
        close = difflib.get_close_matches(code, codes, n=1, cutoff=0.6)
        hint = f"; did you mean {close[0]}?" if close else " (codes are GPL followed by four digits: see gpl2py explain GPL)"
        out.sink.report(msg.USAGE_ERROR, None, detail=f"gpl2py explain: no diagnostic code {args.code!r}{hint}")
        out.usage_error = True
        return out
    if len(found) == 1 and found[0].code == code:
        m = found[0]
        notes = m.notes or "No notes: the message says it all."
        out.product = f"{m.code} ({m.severity_name}): {m.template}\n\n" + textwrap.fill(notes, width=78)
        out.product_json = {"code": m.code, "severity": m.severity_name, "message": m.template, "notes": m.notes}
    else:
        out.product = "\n".join(f"{m.code} ({m.severity_name}): {m.template}" for m in found)
        out.product_json = [{"code": m.code, "severity": m.severity_name, "message": m.template, "notes": m.notes}
                            for m in found]
    return out


def _configure_transpile(parser: argparse.ArgumentParser) -> None:
    parser.add_argument(
        "paths",
        metavar="PROJECT",
        nargs="*",
        help="a project folder (with or without Project.gpr), a Project.gpr file, or one .gpl file; "
        "several are translated one after the other (default: paths in [tool.gpl2py])",
    )
    parser.add_argument("-o", "--output", metavar="OUT", default=".",
                        help="folder that receives the package OUT/<project_name>/ (default: .)")
    parser.add_argument("--keep-going", action="store_true",
                        help="write the package even when there are errors (exit status stays 1)")
    add_project_options(parser)


def _run_transpile(args: argparse.Namespace) -> Outcome:
    """Transpile each project into an importable Python package; nothing of a project with errors
    is written (unless --keep-going), the others are.  Two projects that would make the same
    package are an output error for the second."""
    import time

    from gpl2py.progress import ProgressBar, wants_progress
    from gpl2py.run import count_lines
    from gpl2py.transpile import transpile, write_package

    out = Outcome(sink=new_sink(args))
    started = time.perf_counter()
    written: dict[str, str] = {}  # package -> the path it came from
    lines = 0
    for path in args.paths:
        sink = out.sink.child()
        bar = ProgressBar(sys.stderr, wants_progress(sys.stderr, args.quiet, not args.display.text))
        loaded: list[Project] = []

        def on_load(project: Project, sink: DiagnosticSink = sink, loaded: list[Project] = loaded) -> None:
            loaded.append(project)
            watch_sources(project, sink)

        try:
            output = transpile(path, sink, keep_going=args.keep_going, progress=bar,
                               stubs_dir=args.stubs, strict=args.strict, loaded=on_load,
                               limits=limits_of(args), language=args.language, start=args.start)
        finally:
            bar.close()
        if loaded:
            _remember(out, loaded[0])  # diagnostics show their source lines, also on errors
            out.checked += len(loaded[0].sources)
        if output is not None and output.project is not None:
            if output.package in written:
                sink.report(msg.OUTPUT_ERROR, None, path=str(Path(args.output) / output.package),
                            detail=f"{written[output.package]} is translated to this package already")
            elif write_package(output, args.output, sink):
                written[output.package] = path
                lines += count_lines(output.project)
        if any(d.code == msg.INTERNAL_ERROR.code for d in sink):
            out.failed = True
        out.sink.extend(sink)
    out.written = len(written)
    if written:
        seconds = time.perf_counter() - started
        out.summary = _transpile_summary(out, lines, seconds, len(args.paths))
        out.summary_json = {**_counts(out.sink.sorted()), "files": out.checked, "lines": lines,
                            "seconds": round(seconds, 3), "projects": len(args.paths), "written": len(written)}
    return out


def _transpile_summary(out: Outcome, lines: int, seconds: float, projects: int) -> str:
    from gpl2py.run import transpile_summary

    text = transpile_summary(out.checked, lines, out.sink, seconds, False)
    if projects > 1:  # "transpiled 2 of 3 projects, 9 files (...)": which were written
        text = text.replace("transpiled ", f"transpiled {out.written} of {projects} projects, ", 1)
    return text


def _configure_run(parser: argparse.ArgumentParser) -> None:
    from gpl2py.run import configure

    configure(parser)


def _run_run(args: argparse.Namespace) -> Outcome:
    from gpl2py.run import run_command

    return run_command(args)


def _configure_lsp(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--stdio", action="store_true",
                        help="talk the protocol on stdin/stdout (the default and only transport)")


def _run_lsp(args: argparse.Namespace) -> Outcome:
    """Serve the Language Server Protocol on stdin/stdout until the editor says exit."""
    from gpl2py.run import missing_extra

    out = Outcome(counts=False)
    problem = missing_extra("pygls", "lsp", "gpl2py lsp")
    if problem is not None:
        out.sink.report(msg.USAGE_ERROR, None, detail=problem)
        out.usage_error = True
        return out
    from gpl2py.lsp.server import serve

    serve()
    out.emitted = True
    out.exit_status = EXIT_OK
    return out


def _configure_sweep(parser: argparse.ArgumentParser) -> None:
    from gpl2py.sweep.command import configure

    configure(parser)


def _run_sweep(args: argparse.Namespace) -> Outcome:
    from gpl2py.sweep.command import run_command

    return run_command(args)


def _run_epilog() -> str:
    from gpl2py.run import RUN_EPILOG

    return RUN_EPILOG


COMMANDS: list[Command] = [
    Command(
        name="check",
        help="load a project and report every diagnostic, without translating",
        description="Load GPL projects (or single files), parse and analyse every source file (names, "
        "types, calls, and what the translation checks) and print all diagnostics, sorted by file "
        "and line, each with the offending source line. Nothing is written. Without PATH, the "
        "paths of [tool.gpl2py] in pyproject.toml.",
        configure=_configure_check,
        run=_run_check,
    ),
    Command(
        name="dump-ast",
        help="print the syntax tree of one source file",
        description="Parse one .gpl/.gpo file and print its abstract syntax tree. Meant for "
        "people working on gpl2py itself, or for finding out how a line was understood.",
        configure=_configure_dump_ast,
        run=_run_dump_ast,
    ),
    Command(
        name="explain",
        help="print the documentation of a diagnostic code (gpl2py explain GPL2014)",
        description="Print what a diagnostic code means and what to do about it, from the installed "
        "gpl2py (the text of docs/diagnostics.md). A prefix (GPL20, GPL3) lists the codes it "
        "covers; GPL lists them all.",
        configure=_configure_explain,
        run=_run_explain,
    ),
    Command(
        name="translate",
        help="translate a project into a Python package (the default command)",
        description="Load, check and translate a GPL project into OUT/<project_name>/, a Python "
        "package that runs on the gplrt simulated controller (python -m <project_name>). On "
        "errors nothing is written unless --keep-going; the exit status is then 1.",
        configure=_configure_transpile,
        run=_run_transpile,
        default=True,
    ),
    Command(
        name="run",
        help="translate (cached) and run a project on the simulated controller",
        description="Translate a GPL project (re-using the cached translation when nothing "
        "changed), then run its ProjectStart procedure on a simulated controller: console output "
        "goes to stdout, controller reports and gpl2py's own messages to stderr. Ctrl-C stops "
        "every GPL thread and exits with status 130 (SIGTERM: 143). Example: gpl2py run "
        "samples/pick_and_place --setup samples/notebook/cell_io.py --plot cell.png",
        configure=_configure_run,
        run=_run_run,
        epilog=_run_epilog,
    ),
    Command(
        name="lsp",
        help="serve diagnostics, types and navigation to an editor (Language Server Protocol)",
        description="Run gpl2py's language server on stdin/stdout: the diagnostics of gpl2py check "
        "as you type, hover, go to definition, references, symbols, completion, signature help, "
        "rename and quick fixes (docs/editors.md). Needs the lsp extra: pip install 'gpl2py[lsp]'.",
        configure=_configure_lsp,
        run=_run_lsp,
    ),
    Command(
        name="sweep",
        help="run a project many times with different parameters, on Dask (docs/sweep.md)",
        description="Translate a GPL project once, then run its ProjectStart once per parameter set "
        "of --params on a Dask cluster (a local one, or --scheduler ADDRESS), each run on the virtual "
        "clock after --setup's setup(sim, params), and write one row per run (its parameters, how it "
        "ended, its metrics) to a Parquet file as the runs end. Example: gpl2py sweep "
        "samples/pick_and_place --params samples/sweep/params.toml --setup samples/sweep/setup.py "
        "-o results.parquet --plot cycle.png",
        configure=_configure_sweep,
        run=_run_sweep,
    ),
]


def _parse(source: SourceFile, sink: DiagnosticSink) -> object:
    from gpl2py.gpl.syntax.parser import parse

    return parse(source, sink)


# --- argument parsing ---------------------------------------------------------------------------


class _Parser(argparse.ArgumentParser):
    """argparse, but a bad command line raises :class:`UsageError` instead of exiting."""

    def error(self, message: str) -> NoReturn:
        raise UsageError(f"{self.prog}: {message}")


def _output_options(parser: argparse.ArgumentParser, top: bool) -> None:
    """--output-format (--json), --quiet and --color, accepted before or after the command name.

    Subcommand copies default to SUPPRESS so that they do not overwrite a value given before the
    command name.
    """
    parser.add_argument(
        "--output-format",
        choices=FORMATS,
        default=None if top else argparse.SUPPRESS,
        help="text (default): diagnostics with their source lines on stderr; json: one JSON "
        "object on stdout; sarif: a SARIF 2.1.0 log on stdout (code scanning); github: GitHub "
        "Actions annotations on stdout",
    )
    parser.add_argument(
        "--json",
        dest="output_format",
        action="store_const",
        const="json",
        default=argparse.SUPPRESS,
        help="the same as --output-format json",
    )
    parser.add_argument(
        "-q",
        "--quiet",
        action="store_true",
        default=False if top else argparse.SUPPRESS,
        help="print errors only: no warnings and no summary line",
    )
    parser.add_argument(
        "--color",
        choices=("auto", "always", "never"),
        default="auto" if top else argparse.SUPPRESS,
        help="colour the diagnostics: auto (default) on a terminal, unless $NO_COLOR is set "
        "(or $FORCE_COLOR asks for it elsewhere)",
    )


#: Options that take a value, before the command name or before the project of the bare
#: ``gpl2py [options] PROJECT`` form: ``_route`` skips their value when it looks for the command.
_VALUE_OPTIONS = ("--output-format", "--color", "-o", "--output", "--stubs", "--select", "--ignore",
                  "--config", "--max-source-mb")


def build_parser(only: str | None = "") -> argparse.ArgumentParser:
    """The whole command line's parser; with ``only``, one whose subcommands other than ``only``
    are names without arguments (``None``: none has any), enough to parse a command line routed to
    ``only`` (:func:`_route`) and to print the top-level help.  Why: building every subcommand
    costs a fifth of ``gpl2py check``'s start-up, ``run``'s alone imports the robot catalogue for
    ``--robot``'s choices (benchmarks/check_startup.py)."""
    import textwrap

    parser = _Parser(
        prog="gpl2py",
        description=textwrap.fill(
            "gpl2py translates GPL programs (Brooks / Precise Automation PreciseFlex robot "
            "controllers) into Python that runs on the gplrt simulated controller. "
            "Start with: gpl2py run PROJECT_FOLDER (translate, then run on a simulated "
            "PF400SX), or gpl2py check PROJECT_FOLDER (report problems only). "
            "gpl2py COMMAND --help explains each command.",
            width=78,
        ),
        epilog=_EPILOG,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    parser.add_argument("--version", action="version", version=f"gpl2py {__version__}")
    _output_options(parser, top=True)
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser)
    for command in COMMANDS:
        if only != "" and command.name != only:
            sub.add_parser(command.name, help=command.help)
            continue
        child = sub.add_parser(
            command.name,
            help=command.help,
            description=textwrap.fill(command.description, width=78),
            epilog=command.epilog() if command.epilog is not None else _EPILOG,
            formatter_class=argparse.RawDescriptionHelpFormatter,
        )
        _output_options(child, top=False)
        command.configure(child)
        child.set_defaults(handler=command)
    return parser


def _route(argv: list[str]) -> list[str]:
    """Insert the default command's name when the first argument is not a command (see module doc).

    A first argument that is neither a command nor an existing path, and has no path separator or
    dot, is taken for a mistyped command: ``gpl2py chek X`` says "did you mean 'check'?" instead
    of translating a project called ``chek``."""
    names = [c.name for c in COMMANDS]
    default = next((c for c in reversed(COMMANDS) if c.default), None)
    first = _first_word(argv)
    if default is None or first is None or first in names:
        return argv
    if not Path(first).exists() and not any(ch in first for ch in "./\\"):
        close = difflib.get_close_matches(first, names, n=1, cutoff=0.6)
        hint = f"; did you mean '{close[0]}'?" if close else f" (the commands: {', '.join(names)})"
        raise UsageError(f"gpl2py: {first!r} is neither a command nor a project path{hint}")
    return [default.name, *argv]


def _first_word(argv: Sequence[str]) -> str | None:
    """The first argument that is neither an option nor the value of one before it."""
    skip = False
    for arg in argv:
        if skip:
            skip = False
        elif arg in _VALUE_OPTIONS:
            skip = True
        elif not arg.startswith("-"):
            return arg
    return None


def _did_you_mean(message: str, parser: argparse.ArgumentParser, command: str | None) -> str:
    """argparse's message, with the option or choice the user probably meant appended."""
    if "unrecognized arguments: " in message:
        options = _option_strings(parser, command)
        words = message.split("unrecognized arguments: ", 1)[1].split()
        for word in words:
            if word.startswith("--"):
                close = difflib.get_close_matches(word.split("=", 1)[0], options, n=1, cutoff=0.6)
                if close:
                    return f"{message}; did you mean {close[0]}?"
        return message
    found = re.search(r"invalid choice: '([^']*)' \(choose from (.*)\)", message)
    if found:
        choices = [c.strip().strip("'") for c in found.group(2).split(",")]
        close = difflib.get_close_matches(found.group(1), choices, n=1, cutoff=0.6)
        if close:
            return f"{message}; did you mean {close[0]}?"
    return message


def _option_strings(parser: argparse.ArgumentParser, command: str | None) -> list[str]:
    """The long options of ``command`` (and the ones every command takes)."""
    parsers = [parser]
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction) and command in action.choices:
            parsers.append(action.choices[command])
    return sorted({o for p in parsers for a in p._actions for o in a.option_strings if o.startswith("--")})


# --- output -------------------------------------------------------------------------------------


def _wanted_format(argv: Sequence[str]) -> str:
    """The output format asked for, even on a command line too broken for argparse."""
    found = "text"
    for i, arg in enumerate(argv):
        if arg == "--json":
            found = "json"
        elif arg == "--output-format" and i + 1 < len(argv) and argv[i + 1] in FORMATS:
            found = argv[i + 1]
        elif arg.startswith("--output-format=") and arg.split("=", 1)[1] in FORMATS:
            found = arg.split("=", 1)[1]
    return found


# --- entry point --------------------------------------------------------------------------------


def main(argv: list[str] | None = None) -> int:
    """Run the gpl2py command line; returns the exit status (see ``gpl2py --help``)."""
    try:
        status = _main(argv)
    except BrokenPipeError:  # the reader of stdout or stderr went away (gpl2py ... | head)
        return _output_closed()
    if status == EXIT_OUTPUT_CLOSED:
        return _output_closed()
    return status


def _output_closed() -> int:
    """End quietly after a reader closed our output, as a program that SIGPIPE stops: no message,
    no traceback, status 141.  The stream that cannot be written is pointed at /dev/null, so that
    Python's own flush at exit has nowhere to fail ("Exception ignored ... BrokenPipeError")."""
    for stream in (sys.stdout, sys.stderr):
        try:
            stream.flush()
        except (OSError, ValueError):
            try:
                devnull = os.open(os.devnull, os.O_WRONLY)
                os.dup2(devnull, stream.fileno())
                os.close(devnull)
            except (OSError, ValueError):
                pass
    return EXIT_OUTPUT_CLOSED


def _main(argv: list[str] | None) -> int:
    args_list = list(sys.argv[1:] if argv is None else argv)
    stdout, stderr = sys.stdout, sys.stderr
    fallback = Display(_wanted_format(args_list), False, wants_colour(stderr))
    parser: argparse.ArgumentParser | None = None
    try:
        routed = _route(args_list)
        parser = build_parser(only=_first_word(routed))
        args = parser.parse_args(routed)
    except UsageError as exc:
        parser = parser or build_parser()
        command_name = _first_word(args_list)
        detail = _did_you_mean(str(exc), parser, command_name if command_name in
                               {c.name for c in COMMANDS} else "translate")
        return _usage_failure(detail, parser, fallback, stdout, stderr)
    except SystemExit as exc:  # --help and --version print and "exit" successfully
        return exc.code if isinstance(exc.code, int) else EXIT_OK
    command: Command | None = getattr(args, "handler", None)
    if command is None:
        names = ", ".join(c.name for c in COMMANDS)
        return _usage_failure(f"gpl2py: missing COMMAND (one of: {names})", parser, fallback, stdout, stderr)
    try:
        _settle(args, command)
    except UsageError as exc:
        return _usage_failure(str(exc), parser, args.display, stdout, stderr, usage_line=False)
    except ConfigError as exc:
        out = Outcome(usage_error=True)
        out.sink.report(msg.CONFIG_ERROR, None, path=str(exc.path), detail=exc.detail)
        _emit(out, args.display, stdout, stderr)
        return EXIT_USAGE
    try:
        out = command.run(args)
    except BrokenPipeError:
        raise
    except KeyboardInterrupt as interrupt:  # Ctrl-C, or SIGTERM (gpl2py.entry)
        status, word = stop_status(interrupt)
        stderr.write(f"gpl2py: {word}\n")
        return status
    except Exception as exc:  # noqa: BLE001 - the promise is: never a traceback
        if os.environ.get("GPL2PY_TRACEBACK"):
            raise
        out = Outcome(failed=True)
        out.sink.report(msg.INTERNAL_ERROR, internal_error_span(exc), detail=f"{type(exc).__name__}: {exc}")
    if not out.emitted:
        _emit(out, args.display, stdout, stderr)
    if out.exit_status is not None:
        return out.exit_status
    return status_of(out.sink, out.usage_error)


def status_of(sink: DiagnosticSink, usage_error: bool = False) -> int:
    """The exit status the diagnostics call for: 2 for a usage error or an internal error
    (GPL9000, wherever in the pipeline it was caught), 1 for errors in the input, else 0."""
    if usage_error or any(d.code == msg.INTERNAL_ERROR.code for d in sink):
        return EXIT_USAGE
    return EXIT_ERRORS if sink.has_errors() else EXIT_OK


def _settle(args: argparse.Namespace, command: Command) -> None:
    """Complete the parsed command line: the display, then -- for the commands that read a
    project -- the ``[tool.gpl2py]`` defaults for what the command line left out, the paths, and
    the diagnostics selection.  Raises UsageError or ConfigError."""
    fmt = getattr(args, "output_format", None) or "text"
    args.display = Display(fmt, bool(args.quiet), fmt == "text" and wants_colour(sys.stderr, args.color))
    args.json = fmt == "json"
    unsupported = (command.name in ("dump-ast", "explain") and fmt in ("sarif", "github")) or \
        (command.name == "run" and fmt == "sarif")
    if unsupported:  # say so in text: the format asked for is the one that cannot be written
        args.display = Display("text", False, wants_colour(sys.stderr, args.color))
    if command.name in ("dump-ast", "explain") and fmt in ("sarif", "github"):
        raise UsageError(f"gpl2py {command.name}: --output-format {fmt} is for diagnostics of a "
                         "project (check, translate, run); use text or json")
    if command.name == "run" and fmt == "sarif":
        raise UsageError("gpl2py run: --output-format sarif describes diagnostics, not a run; use "
                         "gpl2py check --output-format sarif, or run with text, json or github")
    if not hasattr(args, "no_config"):
        return  # dump-ast, explain: no project options
    config = discover(args.config, args.no_config)
    args.config_path = str(config.path) if config.path is not None else None
    _apply_config(args, config, command)
    try:
        select = parse_codes(args.select, "--select") if args.select is not None else None
        ignore = parse_codes(args.ignore, "--ignore") if args.ignore is not None else ()
    except ValueError as exc:
        raise UsageError(f"gpl2py {command.name}: {exc}") from None
    args.selection = Selection(select, ignore)  # also without options: the gpl2py: ignore comments


def _apply_config(args: argparse.Namespace, config: Config, command: Command) -> None:
    """Fill what the command line left out from ``config``, then the built-in defaults."""
    if hasattr(args, "paths") and not args.paths:
        if not config.paths:
            raise UsageError(f"gpl2py {command.name}: the following arguments are required: "
                             f"{'PATH' if command.name == 'check' else 'PROJECT'} (or paths in "
                             "[tool.gpl2py] of pyproject.toml)")
        args.paths = [_shown(p) for p in config.paths]
    if args.stubs is None and config.stubs is not None:
        args.stubs = _shown(config.stubs)
    if args.strict is None:
        args.strict = bool(config.strict)
    if args.max_source_mb is None:
        args.max_source_mb = config.max_source_mb
    if args.select is None and config.select is not None:
        args.select = list(config.select)
        _check_codes(args.select, "select", config)
    if args.ignore is None and config.ignore is not None:
        args.ignore = list(config.ignore)
        _check_codes(args.ignore, "ignore", config)
    if command.name == "run":
        if args.clock is None:
            args.clock = config.clock or "virtual"
        if args.robot is None:
            robot = (config.robot or "PF400SX").upper()
            from gplrt.controller.pdb import model_names

            if robot not in model_names():
                raise ConfigError(config.path or Path(FILE_NAME), f"[tool.gpl2py] robot = {config.robot!r}: "
                                  f"not a robot model; one of {', '.join(model_names())}")
            args.robot = robot


def _check_codes(values: list[str], key: str, config: Config) -> None:
    try:
        parse_codes(values, key)
    except ValueError as exc:
        raise ConfigError(config.path or Path(FILE_NAME), f"[tool.gpl2py] {exc}") from None


def _shown(path: str) -> str:
    """A path from the configuration as diagnostics should show it: relative to the current folder
    when it is below it (editors and CI annotations resolve it there)."""
    try:
        return str(Path(path).relative_to(Path.cwd().absolute()))
    except ValueError:
        return path


def _usage_failure(detail: str, parser: argparse.ArgumentParser, display: Display, stdout: TextIO,
                   stderr: TextIO, usage_line: bool = True) -> int:
    out = Outcome(usage_error=True)
    out.sink.report(msg.USAGE_ERROR, None, detail=detail)
    if display.format == "text" and usage_line:
        stderr.write(parser.format_usage())
    _emit(out, display, stdout, stderr)
    return EXIT_USAGE


if __name__ == "__main__":
    sys.exit(main())
