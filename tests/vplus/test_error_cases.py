"""Every error code of the V+ front end (GPL4000-GPL4999) has a case here: a V+ source that gives
it, at the place it names, with no internal error, and which translates with ``--keep-going`` to
Python that compiles (the V+ counterpart of tests/frontend/test_no_internal_error.py's cases)."""

from __future__ import annotations

from pathlib import Path

import pytest

from gpl2py import messages as M
from gpl2py.diagnostics import DiagnosticSink, Severity
from gpl2py.transpile import transpile

P = ".PROGRAM main()\n"
CASES: dict[str, tuple[str, int]] = {  # code -> (source, line of the diagnostic)
    "GPL4001": (P + "  x = 1 @ 2\n.END\n", 2),
    "GPL4002": (P + "  TYPE \"abc\n.END\n", 2),
    "GPL4003": (P + "  x = 1e999\n.END\n", 2),
    "GPL4004": (P + "  x = '\n.END\n", 2),
    "GPL4100": (P + "  x = (1 +\n.END\n", 2),
    "GPL4101": (P + "  FROB 3\n.END\n", 2),
    "GPL4102": ("x = 1\n" + P + ".END\n", 1),
    "GPL4103": (P + "  x = 1\n", 1),
    "GPL4104": (P + "  WHILE x DO\n.END\n", 2),
    "GPL4105": (P + "  UNTIL x\n.END\n", 2),
    "GPL4106": (P + "  x = 1\n  LOCAL y\n.END\n", 3),
    "GPL4107": (P + "  99999 x = 1\n.END\n", 2),
    "GPL4108": (P + "  10 x = 1\n  10 y = 2\n.END\n", 3),
    "GPL4109": (P + ".END\n.REALS\nx 1 2\n.END\n", 4),
    "GPL4110": (P + ".END\n.NOTES\n.END\n", 3),
    "GPL4113": (P + "  IF x THEN\n" * 51 + "  TYPE 1\n" + "  END\n" * 51 + ".END\n", 52),
    "GPL4111": (P + "  x = " + "(" * 150 + "1" + ")" * 150 + "\n.END\n", 2),
    "GPL4300": (P + "  CALL nothing()\n.END\n", 2),
    "GPL4303": (P + "  CALL sub(1, 2)\n.END\n.PROGRAM sub(a)\n.END\n", 2),
    "GPL4304": (P + "  SET p = TRANS(1)\n  p = 2\n.END\n", 3),
    "GPL4306": (P + "  x = FROB(1)\n.END\n", 2),
    "GPL4308": (P + "  GOTO 5\n.END\n", 2),
    "GPL4309": (P + "  NEXT\n.END\n", 2),
    "GPL4311": None,  # type: ignore[dict-item]
    "GPL4700": (P + "  GOTO 5\n  FOR i = 1 TO 3\n5   x = 1\n  END\n.END\n", 2),
    "GPL4701": (P + "  WHILE x DO\n    EXIT 2\n  END\n.END\n", 3),
    "GPL4702": (P + "".join(f"  FOR i{k} = 1 TO 1\n" for k in range(21)) + "  TYPE 1\n" + "  END\n" * 21
                + ".END\n", 22),
}
#: (GPL4311 is about --start: tests/vplus/test_run.py; GPL4112 about a folder: below.)


def test_every_v_plus_error_code_has_a_case() -> None:
    errors = {m.code for m in M.all_messages() if m.severity is Severity.ERROR and "GPL4000" <= m.code < "GPL5000"}
    assert errors == set(CASES) | {"GPL4112"}


@pytest.mark.parametrize("code", sorted(c for c, case in CASES.items() if case is not None))
def test_the_case_gives_its_code_where_it_says_and_translates_with_keep_going(code: str, tmp_path: Path) -> None:
    text, line = CASES[code]
    src = tmp_path / "m.v2"
    src.write_text(text)
    sink = DiagnosticSink()
    transpile(src, sink, keep_modules=False)
    assert not any(d.code == "GPL9000" for d in sink), [d.header() for d in sink]
    found = [d for d in sink if d.code == code]
    assert found, [d.header() for d in sink]
    assert found[0].span is not None and found[0].span.line == line, found[0].header()
    kept = DiagnosticSink()
    out = transpile(src, kept, keep_going=True)
    assert not any(d.code == "GPL9000" for d in kept)
    for name, code_text in (out.files.items() if out is not None else ()):
        if name.endswith(".py"):
            compile(code_text, name, "exec")


def test_an_empty_folder_is_no_v_plus_sources(tmp_path: Path) -> None:
    sink = DiagnosticSink()
    transpile(tmp_path, sink, language="vplus")
    assert [d.header() for d in sink] == [f"error GPL4112: no V+ source files (.v2, .pg) in {tmp_path}"]
