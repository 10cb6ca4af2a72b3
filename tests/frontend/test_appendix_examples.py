"""Every example from the manuals (spec appendices) parses; the lines that are not GPL are reported.

The examples were extracted once by ``tools/extract_examples.py`` into ``examples/*.gpl`` (verbatim,
one file per fragment; ``manifest.json`` says where each came from), so this test does not read
``/work/shared``.

Wrapping.  Most examples are fragments.  The test wraps each one the way the spec's Appendix A
suggests, choosing by content:

* a fragment that contains a ``Module`` line is already a file;
* one that declares procedures, classes or delegates is wrapped in ``Module Test … End Module``;
* anything else is a statement list, wrapped in ``Module Test / Public Sub Main … End Sub / End Module``;
* the E39 ``Case`` fragments are wrapped in a ``Select x … End Select`` inside ``Main``.

Line numbers below are the fragment's own lines (the wrapper's offset is subtracted).

Expectations.  A line must produce an error if and only if it is listed.  Reasons:

* ``invalid`` — the manual marks the line invalid for a syntactic reason (a declaration without a
  type).  Lines the manual marks invalid for *semantic* reasons (assignment to a Const in E11,
  incomplete/Private paths in E16 and E24, the illegal GoTo in E47, duplicate declarations in
  alternatives) must parse cleanly and are not listed; nor is the Dim inside a For of E05, which
  the manual calls "Not allowed" but which real code writes and the controller compiles
  (docs/design/real-code.md).
* ``doc`` — documentation text inside a listing, not GPL: the ``-or-`` / ``or`` separators between
  alternatives, prose (``is equivalent to``), the operator table of §7.2, template meta-syntax
  (``While | Until``, ``test_expression,...``, ``New class_name`` used as a statement) and lines
  holding only ``:`` (the manual's "code omitted" ellipsis; gpl2py treats a stray ``:`` as an error,
  as GPL has no ``:`` statement separator).
* ``artifact`` — PDF line-wrap damage kept in the ``…_verbatim`` files and in EX-21 (the spec gives
  the repaired versions, which must parse cleanly).

No example may produce a warning.
"""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest

from gpl2py.diagnostics import DiagnosticSink, Severity
from gpl2py.source import SourceFile
from gpl2py.gpl.syntax.parser import parse

EXAMPLES = Path(__file__).parent / "examples"

# file stem -> {fragment line: reason}
EXPECTED_ERRORS: dict[str, dict[int, str]] = {
    "lang_E07": {1: "invalid: declaration without a type"},
    "lang_E18_2": {1: "doc: template 'New class_name' as a statement"},
    "lang_E18_3": {2: "doc: -or-", 4: "doc: -or-"},
    "lang_E23_verbatim": {3: "artifact: wrapped comment text 'obj' at class level"},
    "lang_E29": {1: "doc: prose"},
    "lang_E30": {2: "doc: or"},
    "lang_E31_verbatim": {5: "artifact: wrapped comment text 'as 8'"},
    "lang_E32_1": {1: "doc: prose"},
    "lang_E32_2": {n: "doc: operator table" for n in (1, 2, 3, 4, 5, 6, 7, 9, 10, 11)},
    "lang_E37": {1: "doc: While | Until", 4: "doc: -or-", 7: "doc: While | Until"},
    "lang_E38": {2: "doc: test_expression,...,test_expression"},
    "lang_E42_2": {2: "doc: ':' ellipsis", 6: "doc: ':' ellipsis"},
    "lang_E42_3": {5: "doc: or"},
    "lang_E43_2": {2: "doc: or"},
    "lang_E43_3": {2: "doc: ':' ellipsis", 4: "doc: ':' ellipsis"},
    "lang_X04_2": {2: "doc: ':' ellipsis"},
    "lang_X08_verbatim": {35: "artifact: continuation without ' _'"},
    "classes_EX-03": {4: "doc: -or-", 6: "doc: -or-"},
    "classes_EX-16": {4: "doc: ':' ellipsis"},
    "classes_EX-21": {35: "artifact: continuation without ' _'"},
}

SELECT_WRAPPED = {"lang_E39"}

_MODULE_LINE = re.compile(r"^\s*Module\b", re.IGNORECASE)
_MEMBER_LINE = re.compile(
    r"^\s*((Public|Private|Shared)\s+)*(Sub|Function|Class|Delegate)\b", re.IGNORECASE
)


def wrap(stem: str, text: str) -> tuple[str, int]:
    """The text to parse and the number of wrapper lines before the fragment's first line."""
    lines = text.splitlines()
    if stem in SELECT_WRAPPED:
        head = ["Module Test", "Public Sub Main", "Select x"]
        tail = ["End Select", "End Sub", "End Module"]
    elif any(_MODULE_LINE.match(line) for line in lines):
        return text, 0
    elif any(_MEMBER_LINE.match(line) for line in lines):
        head, tail = ["Module Test"], ["End Module"]
    else:
        head, tail = ["Module Test", "Public Sub Main"], ["End Sub", "End Module"]
    return "\n".join(head + lines + tail) + "\n", len(head)


FILES = sorted(p.stem for p in EXAMPLES.glob("*.gpl"))


def test_examples_are_present_and_listed_in_the_manifest() -> None:
    manifest = json.loads((EXAMPLES / "manifest.json").read_text())
    assert sorted(Path(e["file"]).stem for e in manifest) == FILES
    assert len(FILES) >= 120
    assert set(EXPECTED_ERRORS) <= set(FILES)


@pytest.mark.parametrize("stem", FILES)
def test_example(stem: str) -> None:
    text = (EXAMPLES / f"{stem}.gpl").read_text(encoding="utf-8")
    wrapped, offset = wrap(stem, text)
    sink = DiagnosticSink()
    unit = parse(SourceFile(f"{stem}.gpl", wrapped), sink)
    assert unit.members, "nothing parsed"
    error_lines = {d.span.line - offset for d in sink if d.severity is Severity.ERROR}
    expected = set(EXPECTED_ERRORS.get(stem, {}))
    report = "\n".join(d.render(SourceFile(stem, wrapped)) for d in sink)
    assert error_lines == expected, report
    assert not [d for d in sink if d.severity is not Severity.ERROR], report


DOC_LINES = {stem: {n for n, why in lines.items() if why.startswith("doc")} for stem, lines in EXPECTED_ERRORS.items()}

# Template lines carry structure, so they are instantiated rather than blanked.
TEMPLATE_INSTANCES: dict[str, dict[int, str]] = {
    "lang_E37": {1: "Do While condition", 7: "Loop Until condition"},
    "lang_E38": {2: "    Case test_expression, test_expression"},
}


@pytest.mark.parametrize("stem", sorted(stem for stem, lines in DOC_LINES.items() if lines))
def test_example_without_its_documentation_lines_is_clean(stem: str) -> None:
    """The documentation lines are the only problem: blank them (keeping line numbers; template
    lines such as ``Do While | Until condition`` are instantiated instead) and the example has no
    diagnostic at all, except on the lines the manual marks invalid.  This also
    shows that the errors on documentation lines did not hide anything around them."""
    lines = (EXAMPLES / f"{stem}.gpl").read_text(encoding="utf-8").splitlines()
    for n in DOC_LINES[stem]:
        lines[n - 1] = TEMPLATE_INSTANCES.get(stem, {}).get(n, "")
    wrapped, offset = wrap(stem, "\n".join(lines) + "\n")
    sink = DiagnosticSink()
    unit = parse(SourceFile(f"{stem}.gpl", wrapped), sink)
    assert unit.members
    left = {n: why for n, why in EXPECTED_ERRORS[stem].items() if not why.startswith("doc")}
    report = "\n".join(d.render(SourceFile(stem, wrapped)) for d in sink)
    assert {d.span.line - offset for d in sink} == set(left), report
