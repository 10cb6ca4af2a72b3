"""How diagnostics are printed: ``--output-format text|json|sarif|github``, and colour.

* ``text``: ``file:line:col: severity GPLnnnn: message``, the source line and a caret
  (``Diagnostic.render``), coloured on a terminal (:func:`wants_colour`).
* ``json``: one object, ``{"schema_version": 1, "gpl2py_version": ..., "diagnostics": [...],
  "summary": {...}}`` (:func:`json_document`); ``schema_version`` changes only when a field
  changes meaning or goes away (new fields may appear in any version).
* ``sarif``: SARIF 2.1.0 (:func:`sarif_log`), for code-scanning services: one run, the rules of
  every code reported, file locations relative to the current folder (``%SRCROOT%``) where they
  are below it.
* ``github``: GitHub Actions workflow commands, ``::error file=F,line=L,col=C,...::message``
  (:func:`github_annotations`), which annotate the lines of a pull request.
"""

from __future__ import annotations

import os
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import TextIO
from urllib.parse import quote

from gpl2py import __version__
from gpl2py import messages as msg
from gpl2py.diagnostics import Diagnostic, Severity, one_line

FORMATS = ("text", "json", "sarif", "github")
#: The version of the JSON document's shape (docs/cli.md, "JSON output").
JSON_SCHEMA_VERSION = 1
SARIF_SCHEMA = "https://json.schemastore.org/sarif-2.1.0.json"


# --- colour ---------------------------------------------------------------------------------------


def wants_colour(stream: TextIO, choice: str = "auto", env: Mapping[str, str] | None = None) -> bool:
    """Whether to colour what goes to ``stream``: ``--color always|never`` decides; with ``auto``,
    a non-empty ``NO_COLOR`` turns colour off (no-color.org), else a non-empty ``FORCE_COLOR`` turns
    it on, else colour is used on a terminal whose ``TERM`` is not ``dumb``."""
    if choice != "auto":
        return choice == "always"
    env = os.environ if env is None else env
    if env.get("NO_COLOR"):
        return False
    if env.get("FORCE_COLOR"):
        return True
    if env.get("TERM") == "dumb":
        return False
    return is_terminal(stream)


def is_terminal(stream: TextIO) -> bool:
    """Whether ``stream`` is a terminal: a closed stream, or one without ``isatty``, is not."""
    isatty = getattr(stream, "isatty", None)
    try:
        return bool(isatty and isatty())
    except (OSError, ValueError):
        return False


# --- JSON -----------------------------------------------------------------------------------------


def json_document(diags: Sequence[Diagnostic], summary: Mapping[str, object], **extra: object) -> dict[str, object]:
    """The one JSON object of ``--output-format json`` (check, translate, run, dump-ast, explain)."""
    doc: dict[str, object] = {"schema_version": JSON_SCHEMA_VERSION, "gpl2py_version": __version__,
                              "diagnostics": [d.to_json() for d in diags]}
    doc.update(extra)
    doc["summary"] = dict(summary)
    return doc


# --- SARIF ----------------------------------------------------------------------------------------

_SARIF_LEVEL = {Severity.ERROR: "error", Severity.WARNING: "warning", Severity.NOTE: "note"}


def sarif_log(diags: Sequence[Diagnostic], cwd: Path | None = None, *, succeeded: bool = True) -> dict[str, object]:
    """A SARIF 2.1.0 log of ``diags``: one run of gpl2py, a rule per code reported (its message
    template and notes from ``gpl2py.messages``), a result per diagnostic."""
    root = (cwd or Path.cwd()).absolute()
    known = {m.code: m for m in msg.all_messages()}
    codes = sorted({d.code for d in diags})
    rules = []
    for code in codes:
        m = known.get(code)
        rule: dict[str, object] = {"id": code}
        if m is not None:
            rule["shortDescription"] = {"text": m.template}
            if m.notes:
                rule["fullDescription"] = {"text": m.notes}
            rule["defaultConfiguration"] = {"level": "error" if m.severity_name == "error" else "warning"}
        rules.append(rule)
    index = {code: i for i, code in enumerate(codes)}
    results = []
    for d in diags:
        result: dict[str, object] = {
            "ruleId": d.code,
            "ruleIndex": index[d.code],
            "level": _SARIF_LEVEL[d.severity],
            "message": {"text": d.message},
        }
        if d.span is not None:
            region: dict[str, int] = {"startLine": max(d.span.line, 1), "startColumn": max(d.span.col, 1)}
            if d.span.end_line >= d.span.line and (d.span.end_line, d.span.end_col) > (d.span.line, d.span.col):
                region["endLine"] = d.span.end_line
                region["endColumn"] = max(d.span.end_col, 1)
            result["locations"] = [{"physicalLocation": {"artifactLocation": _artifact(d.span.file, root),
                                                         "region": region}}]
        results.append(result)
    run: dict[str, object] = {
        "tool": {"driver": {"name": "gpl2py", "version": __version__, "semanticVersion": __version__,
                            "rules": rules}},
        "originalUriBaseIds": {"%SRCROOT%": {"uri": root.as_uri() + "/"}},
        "columnKind": "unicodeCodePoints",  # gpl2py counts characters, a tab as one
        "invocations": [{"executionSuccessful": succeeded}],
        "results": results,
    }
    return {"$schema": SARIF_SCHEMA, "version": "2.1.0", "runs": [run]}


def _artifact(file: str, root: Path) -> dict[str, str]:
    path = Path(file)
    absolute = path if path.is_absolute() else root / path
    try:
        relative = absolute.relative_to(root)
    except ValueError:
        return {"uri": absolute.as_uri()}
    return {"uri": quote(relative.as_posix()), "uriBaseId": "%SRCROOT%"}


# --- GitHub Actions -------------------------------------------------------------------------------

_GITHUB_COMMAND = {Severity.ERROR: "error", Severity.WARNING: "warning", Severity.NOTE: "notice"}


def github_annotations(diags: Sequence[Diagnostic], cwd: Path | None = None) -> str:
    """One workflow command per diagnostic: ``::error file=F,line=L,col=C,endLine=..,endColumn=..,
    title=GPLnnnn::message``; the file relative to the current folder (the checkout) when below it."""
    root = (cwd or Path.cwd()).absolute()
    lines = []
    for d in diags:
        props = []
        if d.span is not None:
            props += [f"file={_property(_relative(d.span.file, root))}", f"line={d.span.line}",
                      f"col={d.span.col}"]
            if d.span.end_line == d.span.line and d.span.end_col > d.span.col:
                props += [f"endLine={d.span.end_line}", f"endColumn={d.span.end_col}"]
        props.append(f"title={_property(d.code)}")
        lines.append(f"::{_GITHUB_COMMAND[d.severity]} {','.join(props)}::{_data(f'{d.code}: {one_line(d.message)}')}")
    return "".join(line + "\n" for line in lines)


def github_annotation(severity: Severity, message: str, file: str | None = None, line: int | None = None,
                      title: str | None = None) -> str:
    """One workflow command (``gpl2py run``'s unhandled GPL errors)."""
    props = []
    if file:
        props.append(f"file={_property(_relative(file, Path.cwd().absolute()))}")
        if line:
            props.append(f"line={line}")
    if title:
        props.append(f"title={_property(title)}")
    head = f"::{_GITHUB_COMMAND[severity]}" + (f" {','.join(props)}" if props else "")
    return f"{head}::{_data(one_line(message))}\n"


def _relative(file: str, root: Path) -> str:
    file = one_line(file)
    path = Path(file)
    if not path.is_absolute():
        return path.as_posix()
    try:
        return path.relative_to(root).as_posix()
    except ValueError:
        return path.as_posix()


def _data(text: str) -> str:
    """The message part of a workflow command: %, CR and LF escaped (GitHub's own rules)."""
    return text.replace("%", "%25").replace("\r", "%0D").replace("\n", "%0A")


def _property(text: str) -> str:
    """A property value: also ':' and ',' escaped, which would end it."""
    return _data(text).replace(":", "%3A").replace(",", "%2C")


__all__ = ["FORMATS", "JSON_SCHEMA_VERSION", "github_annotation", "github_annotations", "json_document",
           "sarif_log", "wants_colour"]
