"""The ``gpl2py`` command: argument parsing, running one subcommand, printing diagnostics, exit codes.

Structure: every subcommand is a :class:`Command` (its name, help, how it adds its arguments, and the
function that runs it) in ``COMMANDS``.  The bare form ``gpl2py PROJECT -o OUT`` is handled by
:func:`_route`: when the first argument is not a known command, it is handed to the command marked
``default=True`` (``translate``).

Output contract:

* text mode: diagnostics (sorted by file, line, column, each with a caret excerpt) on **stderr**,
  a one-line summary on stderr unless ``--quiet``; stdout carries only the command's product (the
  AST dump), so it can be piped;
* ``--json``: stdout is exactly one JSON object with a ``"diagnostics"`` list (plus the command's
  product, e.g. ``"ast"``), nothing on stderr.  ``--quiet`` does not filter JSON: a program reading
  it can filter by ``severity`` itself.

Exit status: 0 no errors (warnings allowed), 1 errors in the input (or an internal error, GPL9000),
2 the command line itself is wrong (GPL9001/GPL9002).  No input produces a Python traceback: an
unexpected exception becomes GPL9000 (set ``GPL2PY_TRACEBACK=1`` to see the traceback instead).
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import textwrap
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import NoReturn, TextIO

from gpl2py import __version__
from gpl2py import messages as msg
from gpl2py.diagnostics import Diagnostic, DiagnosticSink, Severity
from gpl2py.project import (
    DEFAULT_MAX_SOURCE_MB,
    MAX_SOURCE_ENV,
    PROJECT_FACTOR,
    SOURCE_SUFFIXES,
    Limits,
    Project,
    load_project,
)
from gpl2py.run import plural as _plural
from gpl2py.source import SourceFile

EXIT_OK = 0
EXIT_ERRORS = 1
EXIT_USAGE = 2

_EPILOG = """\
exit status:
  0  no errors (warnings do not change the status)
  1  errors in the GPL input, or an internal gpl2py error (GPL9000)
  2  the command line is wrong (unknown command or option, missing argument)
  gpl2py run adds 3 (a GPL thread ended with an unhandled error), 4 (the program
  stalled) and 130 (Ctrl-C): see gpl2py run --help

Every diagnostic has a stable code, e.g. "Main.gpl:12:5: error GPL1101: ...";
docs/diagnostics.md explains each code.
"""


class UsageError(Exception):
    """The command line is wrong; carries the message for GPL9001."""


@dataclass
class Outcome:
    """What a command produced: the diagnostics, the files they point into, and stdout content."""

    sink: DiagnosticSink = field(default_factory=DiagnosticSink)
    files: dict[str, SourceFile] = field(default_factory=dict)
    product: str | None = None  # printed on stdout in text mode, under "ast" etc. in JSON mode
    product_key: str = "output"
    usage_error: bool = False
    checked: int = 0
    summary: str | None = None  # replaces the "checked N files: ..." line (transpile, run)
    summary_json: dict[str, object] | None = None  # replaces the JSON "summary" object
    emitted: bool = False  # the command printed everything itself (run)
    exit_status: int | None = None  # overrides the status derived from the diagnostics (run)


@dataclass(frozen=True)
class Command:
    """One subcommand: ``configure`` adds its arguments, ``run`` does the work."""

    name: str
    help: str
    description: str
    configure: Callable[[argparse.ArgumentParser], None]
    run: Callable[[argparse.Namespace], Outcome]
    default: bool = False  # receives the arguments when the first one is not a command name
    epilog: str | None = None  # replaces the common exit-status text in --help


# --- commands -----------------------------------------------------------------------------------


def _configure_check(parser: argparse.ArgumentParser) -> None:
    parser.add_argument(
        "path",
        metavar="PATH",
        help="a project folder (with or without Project.gpr), a Project.gpr file, "
        "or a single .gpl/.gpo file",
    )
    add_stub_options(parser)


def _run_check(args: argparse.Namespace) -> Outcome:
    """Load the project, parse every source and run the semantic pass (names, types, calls: what a
    porting engineer wants to know), collecting all diagnostics in one run.  Nothing is written.

    When those find no error, the translation's own checks run too (GoTo targets, nesting that
    Python cannot compile: lowering, in memory), so a project ``check`` passes translates.

    Names that only protected (.gpp) files define are reported as stub warnings, as the
    translation would (GPL3501); ``--strict`` makes them errors.  ``--stubs DIR`` is read as
    ``translate`` and ``run`` read it, so a folder or file they would refuse (GPL3503) is
    reported here too: the three commands take the same stub options."""
    from gpl2py.transpile import collector_paused

    out = Outcome()
    with collector_paused():  # translate's policy, from loading on (gpl2py.transpile)
        _check(args, out)  # its locals (trees, model) go before the collector comes back
    return out


def _check(args: argparse.Namespace, out: Outcome) -> None:
    from gpl2py.lower.user_stubs import load_user_stubs, with_shipped_standins
    from gpl2py.semantics.catalogue import load_catalogue
    from gpl2py.semantics.check import analyze
    from gpl2py.transpile import lower

    project = load_project(args.path, out.sink, limits_of(args))
    if project is None:
        return
    _remember(out, project)
    user = load_user_stubs(args.stubs, out.sink) if args.stubs is not None else None
    if args.stubs is None or user is not None:  # (a bad --stubs folder is already an error)
        user = with_shipped_standins(user, out.sink)
    incomplete = out.sink.has_errors()  # a source could not be loaded: it may declare the start
    units = []
    for source in project.sources:
        units.append(_parse(source, out.sink))
        out.checked += 1
    model = analyze(units, out.sink, load_catalogue(), project.name,  # type: ignore[arg-type]
                    None if incomplete else project.start, protected=bool(project.protected),
                    strict=args.strict, stub_provider=user.provider if user is not None else None,
                    start_span=project.start_span)
    if not out.sink.has_errors():
        lower(project, model, out.sink, user=user)


def _configure_dump_ast(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("file", metavar="FILE", help="one .gpl or .gpo source file")


def _run_dump_ast(args: argparse.Namespace) -> Outcome:
    """Parse one file and print its syntax tree (for debugging the front end)."""
    from gpl2py.syntax.ast import dump

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


def _configure_transpile(parser: argparse.ArgumentParser) -> None:
    parser.add_argument(
        "path",
        metavar="PROJECT",
        help="a project folder (with or without Project.gpr), a Project.gpr file, or one .gpl file",
    )
    parser.add_argument("-o", "--output", metavar="OUT", default=".",
                        help="folder that receives the package OUT/<project_name>/ (default: .)")
    parser.add_argument("--keep-going", action="store_true",
                        help="write the package even when there are errors (exit status stays 1)")
    add_stub_options(parser)


def add_stub_options(parser: argparse.ArgumentParser) -> None:
    """--stubs, --strict and --max-source-mb (check, translate and run): see README "Porting
    your own project" and docs/security.md."""
    parser.add_argument("--max-source-mb", metavar="MB", type=_megabytes, default=None,
                        help=f"read at most MB megabytes from one source file and {PROJECT_FACTOR} "
                        f"times that from all of them (default: ${MAX_SOURCE_ENV}, else "
                        f"{DEFAULT_MAX_SOURCE_MB})")
    parser.add_argument("--stubs", metavar="DIR", default=None,
                        help="folder of Python files implementing stubs for protected code or "
                        "missing built-in members (Module.Proc -> DIR/module.py, function Proc); "
                        "translate and run copy them into the package")
    parser.add_argument("--strict", action="store_true",
                        help="report every stub (GPL3501, GPL3502) as an error: nothing is written "
                        "or run, exit status 1")


def _megabytes(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a number: {text!r}") from None
    if not 0 < value < float("inf"):
        raise argparse.ArgumentTypeError(f"must be a positive number: {text!r}")
    return value


def limits_of(args: argparse.Namespace) -> Limits | None:
    """The input limits --max-source-mb asks for (``None``: the environment's or the defaults)."""
    mb = getattr(args, "max_source_mb", None)
    return Limits.of_mb(mb) if mb is not None else None


def _run_transpile(args: argparse.Namespace) -> Outcome:
    """Transpile a project into an importable Python package; nothing is written on errors."""
    import time

    from gpl2py.progress import ProgressBar, wants_progress
    from gpl2py.run import count_lines, transpile_summary
    from gpl2py.transpile import transpile, write_package

    out = Outcome()
    started = time.perf_counter()
    if not Path(args.path).exists() and not any(ch in args.path for ch in "./\\"):
        # `gpl2py frobnicate`: a mistyped command is more likely than a project called that
        names = ", ".join(c.name for c in COMMANDS)
        out.sink.report(msg.USAGE_ERROR, None,
                        detail=f"{args.path!r} is neither a command ({names}) nor a project path")
        out.usage_error = True
        return out
    bar = ProgressBar(sys.stderr, wants_progress(sys.stderr, args.quiet, args.json))
    loaded: list[Project] = []
    try:
        output = transpile(args.path, out.sink, keep_going=args.keep_going, progress=bar,
                           stubs_dir=args.stubs, strict=args.strict, loaded=loaded.append,
                           limits=limits_of(args))
    finally:
        bar.close()
    if output is None and loaded:
        # errors: nothing written, but the summary counts the files that were checked
        _remember(out, loaded[0])
        out.checked = len(loaded[0].sources)
    if output is not None and output.project is not None:
        _remember(out, output.project)
        out.checked = len(output.project.sources)
        write_package(output, args.output, out.sink)
        lines = count_lines(output.project)
        seconds = time.perf_counter() - started
        out.summary = transpile_summary(out.checked, lines, out.sink, seconds, False)
        out.summary_json = {**_counts(out.sink.sorted()), "files": out.checked, "lines": lines,
                            "seconds": round(seconds, 3)}
    return out


def _configure_run(parser: argparse.ArgumentParser) -> None:
    from gpl2py.run import configure

    configure(parser)


def _run_run(args: argparse.Namespace) -> Outcome:
    from gpl2py.run import run_command

    return run_command(args)


def _run_epilog() -> str:
    from gpl2py.run import RUN_EPILOG

    return RUN_EPILOG


COMMANDS: list[Command] = [
    Command(
        name="check",
        help="load a project and report every diagnostic, without translating",
        description="Load a GPL project (or one file), parse and analyse every source file (names, "
        "types, calls) and print all diagnostics, sorted by file and line, each with the "
        "offending source line. Nothing is written.",
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
        "every GPL thread and exits with status 130. Example: gpl2py run samples/pick_and_place "
        "--setup samples/notebook/cell_io.py --plot cell.png",
        configure=_configure_run,
        run=_run_run,
        epilog=_run_epilog(),
    ),
]


def _parse(source: SourceFile, sink: DiagnosticSink) -> object:
    from gpl2py.syntax.parser import parse

    return parse(source, sink)


def _remember(out: Outcome, project: Project) -> None:
    for f in project.files():
        out.files[f.path] = f


# --- argument parsing ---------------------------------------------------------------------------


class _Parser(argparse.ArgumentParser):
    """argparse, but a bad command line raises :class:`UsageError` instead of exiting."""

    def error(self, message: str) -> NoReturn:
        raise UsageError(f"{self.prog}: {message}")


def _output_options(parser: argparse.ArgumentParser, top: bool) -> None:
    """--json/--quiet, accepted before or after the command name.

    Subcommand copies default to SUPPRESS so that they do not overwrite a value given before the
    command name.
    """
    default: object = False if top else argparse.SUPPRESS
    parser.add_argument(
        "--json",
        action="store_true",
        default=default,
        help="print diagnostics as one JSON object on stdout (for editors and scripts)",
    )
    parser.add_argument(
        "-q",
        "--quiet",
        action="store_true",
        default=default,
        help="print errors only: no warnings and no summary line",
    )


def build_parser() -> argparse.ArgumentParser:
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
        child = sub.add_parser(
            command.name,
            help=command.help,
            description=textwrap.fill(command.description, width=78),
            epilog=command.epilog or _EPILOG,
            formatter_class=argparse.RawDescriptionHelpFormatter,
        )
        _output_options(child, top=False)
        command.configure(child)
        child.set_defaults(handler=command)
    return parser


def _route(argv: list[str]) -> list[str]:
    """Insert the default command's name when the first argument is not a command (see module doc)."""
    names = {c.name for c in COMMANDS}
    default = next((c for c in reversed(COMMANDS) if c.default), None)
    first = next((a for a in argv if not a.startswith("-")), None)
    if default is not None and first is not None and first not in names:
        return [default.name, *argv]
    return argv


# --- output -------------------------------------------------------------------------------------


def _emit(out: Outcome, as_json: bool, quiet: bool, stdout: TextIO, stderr: TextIO) -> None:
    diags = out.sink.sorted()
    if as_json:
        doc: dict[str, object] = {"diagnostics": [d.to_json() for d in diags]}
        if out.product is not None:
            doc[out.product_key] = out.product
        doc["summary"] = out.summary_json if out.summary_json is not None else _counts(diags)
        stdout.write(json.dumps(doc, indent=2) + "\n")
        return
    for d in diags:
        if quiet and d.severity is not Severity.ERROR:
            continue
        source = out.files.get(d.span.file) if d.span is not None else None
        stderr.write(d.render(source) + "\n")
    if out.product is not None:
        stdout.write(out.product.rstrip("\n") + "\n")
    if not quiet and not out.usage_error and out.summary is not None:
        stderr.write(out.summary + "\n")
    elif not quiet and not out.usage_error:
        counts = _counts(diags)
        files = "file" if out.checked == 1 else "files"
        stderr.write(
            f"checked {out.checked} {files}: {_plural(counts['errors'], 'error')}, "
            f"{_plural(counts['warnings'], 'warning')}\n"
        )


def _counts(diags: Sequence[Diagnostic]) -> dict[str, int]:
    return {
        "errors": sum(d.severity is Severity.ERROR for d in diags),
        "warnings": sum(d.severity is Severity.WARNING for d in diags),
    }


def _wants_json(argv: Sequence[str]) -> bool:
    """Whether --json was asked for, even on a command line too broken for argparse."""
    return "--json" in argv


# --- entry point --------------------------------------------------------------------------------


def main(argv: list[str] | None = None) -> int:
    """Run the gpl2py command line; returns the exit status (see ``gpl2py --help``)."""
    args_list = list(sys.argv[1:] if argv is None else argv)
    stdout, stderr = sys.stdout, sys.stderr
    parser = build_parser()
    try:
        args = parser.parse_args(_route(args_list))
    except UsageError as exc:
        return _usage_failure(str(exc), parser, _wants_json(args_list), stdout, stderr)
    except SystemExit as exc:  # --help and --version print and "exit" successfully
        return exc.code if isinstance(exc.code, int) else EXIT_OK
    command: Command | None = getattr(args, "handler", None)
    if command is None:
        names = ", ".join(c.name for c in COMMANDS)
        return _usage_failure(
            f"gpl2py: missing COMMAND (one of: {names})", parser, args.json, stdout, stderr
        )
    try:
        out = command.run(args)
    except KeyboardInterrupt:
        stderr.write("gpl2py: interrupted\n")
        return 130
    except Exception as exc:  # noqa: BLE001 - the promise is: never a traceback
        if os.environ.get("GPL2PY_TRACEBACK"):
            raise
        out = Outcome()
        out.sink.report(msg.INTERNAL_ERROR, None, detail=f"{type(exc).__name__}: {exc}")
    if not out.emitted:
        _emit(out, args.json, args.quiet, stdout, stderr)
    if out.exit_status is not None:
        return out.exit_status
    if out.usage_error:
        return EXIT_USAGE
    return EXIT_ERRORS if out.sink.has_errors() else EXIT_OK


def _usage_failure(
    detail: str, parser: argparse.ArgumentParser, as_json: bool, stdout: TextIO, stderr: TextIO
) -> int:
    out = Outcome(usage_error=True)
    out.sink.report(msg.USAGE_ERROR, None, detail=detail)
    if not as_json:
        stderr.write(parser.format_usage())
    _emit(out, as_json, False, stdout, stderr)
    return EXIT_USAGE


if __name__ == "__main__":
    sys.exit(main())
