"""What a gpl2py command produced and how it is printed: shared by the CLI and ``gpl2py run``.

``gpl2py.cli`` parses the command line and dispatches; each command fills an :class:`Outcome`
(diagnostics, product, summary) that :func:`emit` prints in the chosen :class:`Display`.  ``run``
(``gpl2py.run``) prints its own run report but uses the same pieces.  They live here, below both,
so that the CLI and ``run`` do not import each other (issue 13, item 2: an acyclic import graph;
``tests/controller/test_import_graph.py``).  ``gpl2py.cli``'s module docstring has the output
contract.
"""

from __future__ import annotations

import argparse
import json
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import TextIO

from gpl2py import messages as msg
from gpl2py.diagnostics import Diagnostic, DiagnosticSink, Severity, plural
from gpl2py.formats import github_annotations, json_document, sarif_log
from gpl2py.project import DEFAULT_MAX_SOURCE_MB, MAX_SOURCE_ENV, PROJECT_FACTOR, Limits, Project
from gpl2py.source import SourceFile


@dataclass(frozen=True)
class Display:
    """How a command prints: ``format`` (text, json, sarif, github), ``quiet``, ``colour`` (text
    diagnostics on stderr)."""

    format: str = "text"
    quiet: bool = False
    colour: bool = False

    @property
    def json(self) -> bool:
        return self.format == "json"

    @property
    def text(self) -> bool:
        """Human-readable diagnostics on stderr (text, and github's summary)."""
        return self.format in ("text", "github")


@dataclass
class Outcome:
    """What a command produced: the diagnostics, the files they point into, and stdout content."""

    sink: DiagnosticSink = field(default_factory=DiagnosticSink)
    files: dict[str, SourceFile] = field(default_factory=dict)
    product: str | None = None  # printed on stdout in text mode, under "ast" etc. in JSON mode
    product_key: str = "output"
    product_json: object = None  # the product in JSON mode, when it is not the text
    usage_error: bool = False
    checked: int = 0
    summary: str | None = None  # replaces the "checked N files: ..." line (transpile, run)
    summary_json: dict[str, object] | None = None  # replaces the JSON "summary" object
    emitted: bool = False  # the command printed everything itself (run)
    written: int = 0  # translate: packages written
    counts: bool = True  # the command checks files: print the "checked N files" summary line
    exit_status: int | None = None  # overrides the status derived from the diagnostics (run)
    failed: bool = False  # gpl2py could not do its job (GPL9000): SARIF's executionSuccessful


def add_project_options(parser: argparse.ArgumentParser) -> None:
    """The options of every command that reads a project (check, translate, run): the language, stubs,
    strictness, input limits, the diagnostics selection and the configuration file.  Each one
    that ``[tool.gpl2py]`` can set defaults to None here, so that :func:`_settle` can tell
    "not given" from a value."""
    from gpl2py.languages import names

    parser.add_argument("--language", metavar="NAME", default=None, type=str.lower, choices=names(),
                        help=f"the source language ({', '.join(names())}; default: recognised "
                        "from the files)")
    parser.add_argument("--start", metavar="PROGRAM", default=None,
                        help="the program to run (V+: default the first program of the first file, "
                        "as EXECUTE of the main program; GPL: replaces Project.gpr's ProjectStart)")
    parser.add_argument("--max-source-mb", metavar="MB", type=_megabytes, default=None,
                        help=f"read at most MB megabytes from one source file and {PROJECT_FACTOR} "
                        f"times that from all of them (default: ${MAX_SOURCE_ENV}, else "
                        f"{DEFAULT_MAX_SOURCE_MB})")
    parser.add_argument("--stubs", metavar="DIR", default=None,
                        help="folder of Python files implementing stubs for protected code or "
                        "missing built-in members (Module.Proc -> DIR/module.py, function Proc); "
                        "translate and run copy them into the package")
    parser.add_argument("--strict", action=argparse.BooleanOptionalAction, default=None,
                        help="report every stub (GPL3501, GPL3502) as an error: nothing is written "
                        "or run, exit status 1 (--no-strict: not even when [tool.gpl2py] says so)")
    parser.add_argument("--select", metavar="CODES", action="append", default=None,
                        help="report only these codes or prefixes (GPL2014, GPL20; comma-separated "
                        "or repeated); the more specific of --select and --ignore wins")
    parser.add_argument("--ignore", metavar="CODES", action="append", default=None,
                        help="do not report these codes or prefixes; an ignored error no longer "
                        "stops the translation (see also ' gpl2py: ignore[CODE] comments)")
    parser.add_argument("--config", metavar="FILE", default=None,
                        help="read [tool.gpl2py] from this pyproject.toml (default: the first one "
                        "with that table in the current folder or above)")
    parser.add_argument("--no-config", action="store_true",
                        help="read no configuration file")


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


def new_sink(args: argparse.Namespace) -> DiagnosticSink:
    """The command's sink, filtered by its selection (:func:`_settle` made it)."""
    return DiagnosticSink(getattr(args, "selection", None))


def remember(out: Outcome, project: Project) -> None:
    """Keep the project's files, so that its diagnostics show their source lines."""
    for f in project.files():
        out.files[f.path] = f


def emit(out: Outcome, display: Display, stdout: TextIO, stderr: TextIO) -> None:
    """Print the outcome as ``display`` says (module docstring, "Output contract")."""
    diags = out.sink.sorted()
    if display.format == "json":
        extra: dict[str, object] = {}
        if out.product is not None:
            extra[out.product_key] = out.product_json if out.product_json is not None else out.product
        doc = json_document(diags, out.summary_json if out.summary_json is not None else counts(diags), **extra)
        stdout.write(json.dumps(doc, indent=2) + "\n")
        return
    if display.format == "sarif":
        failed = out.failed or any(d.code == msg.INTERNAL_ERROR.code for d in diags) or out.usage_error
        stdout.write(json.dumps(sarif_log(diags, succeeded=not failed), indent=2) + "\n")
        return
    shown = [d for d in diags if not display.quiet or d.severity is Severity.ERROR]
    if display.format == "github":
        stdout.write(github_annotations(shown))
    else:
        for d in shown:
            source = out.files.get(d.span.file) if d.span is not None else None
            stderr.write(d.render(source, display.colour) + "\n")
    if out.product is not None:
        stdout.write(out.product.rstrip("\n") + "\n")
    if not out.counts or display.quiet or out.usage_error:
        return
    if out.summary is not None:
        stderr.write(out.summary + "\n")
    else:
        found = counts(diags)
        files = "file" if out.checked == 1 else "files"
        stderr.write(
            f"checked {out.checked} {files}: {plural(found['errors'], 'error')}, "
            f"{plural(found['warnings'], 'warning')}\n"
        )


def counts(diags: Sequence[Diagnostic]) -> dict[str, int]:
    """The errors and warnings among ``diags`` (the summary line, the JSON "summary")."""
    return {
        "errors": sum(d.severity is Severity.ERROR for d in diags),
        "warnings": sum(d.severity is Severity.WARNING for d in diags),
    }
