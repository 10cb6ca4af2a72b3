"""Every TMscript error code (GPL5000-GPL5999) has a case that produces it, at the line and column
the message is about, and none of them is an internal error."""

from __future__ import annotations

from pathlib import Path

import pytest

from gpl2py import messages as M
from gpl2py.diagnostics import DiagnosticSink, Severity
from gpl2py.tmscript.pipeline import translate_packet
from gpl2py.transpile import transpile

# code -> (script project or None, packet text or None, line, col)
CASES: dict[str, tuple[str | None, str | None, int, int]] = {
    "GPL5001": (None, "int a = 1 @ 2", 1, 11),
    "GPL5002": (None, 'string s = "abc', 1, 12),
    "GPL5003": (None, "int a = 1\n/* open", 2, 1),
    "GPL5004": (None, "int a = 0x", 1, 9),
    "GPL5100": (None, "if (1 Display(1)", 1, 7),
    "GPL5101": (None, "int a = *", 1, 9),
    "GPL5102": (None, "int a = 1 2", 1, 11),
    "GPL5103": (None, "else", 1, 1),
    "GPL5104": (None, "1 = 2", 1, 3),
    "GPL5105": (None, "int s = 2\nStopAndClearBuffer(s)", 2, 20),
    "GPL5300": (None, "int a = 1\nfloat a = 2", 2, 7),
    "GPL5302": (None, "Nope(1)", 1, 1),
    "GPL5303": (None, "Sleep()", 1, 1),
    "GPL5304": (None, "int a = (int)true", 1, 9),
    "GPL5305": (None, "int a = 4 / 0", 1, 13),
    "GPL5306": ("main\n{\n}\nint F()\n{\n  return\n}\n", None, 6, 3),
    "GPL5307": (None, "break", 1, 1),
    "GPL5308": (None, "byte b = -100", 1, 10),
    "GPL5309": (None, "float f = 1\nf++", 2, 1),
    "GPL5310": ("define\n{\n  int a = 1\n}\n", None, 1, 1),
    "GPL5311": ("main\n{\n}\nmain\n{\n}\n", None, 4, 1),
    "GPL5314": (None, "int x = 1\nswitch (x)\n{\ncase 1\n  if (x > 0) break\n  Display(1)\n}", 5, 14),
    "GPL5317": (None, "int i = 1\nint k = i.Value", 2, 11),
    "GPL5700": ("", None, 0, 0),
    # 21 nested loops: the 21st is the innermost Python would not compile
    "GPL5316": (None, 'Nope["ControlBox"].DO[0] = 1', 1, 1),
    "GPL5701": (None, "int i = 0\n" + "while (i < 1) {\n" * 21 + "i = 1\n" + "}\n" * 21, 22, 1),
}


def test_every_tmscript_error_code_has_a_case() -> None:
    codes = {m.code for m in M.all_messages() if m.severity is Severity.ERROR and "GPL5000" <= m.code < "GPL6000"}
    assert codes == set(CASES)


@pytest.mark.parametrize("code", sorted(CASES))
def test_each_case_gives_its_code_where_it_is(code: str, tmp_path: Path) -> None:
    project, packet, line, col = CASES[code]
    if packet is not None:
        found = translate_packet(packet).errors
    else:
        if code == "GPL5700":
            path = tmp_path  # a folder with no script
        else:
            path = tmp_path / "p.tms"
            path.write_text(project or "")
        sink = DiagnosticSink()
        transpile(path, sink, language="tmscript")
        found = sink.errors
    hits = [d for d in found if d.code == code]
    assert hits, [d.header() for d in found]
    if line:
        assert (hits[0].span.line, hits[0].span.col) == (line, col), hits[0].header()
    assert not any(d.code == "GPL9000" for d in found)


@pytest.mark.parametrize("packet, header", [
    ('mbus1.Preset("a", 1, "DO", 1, "bool")',
     "packet:1:1: error GPL5302: 'mbus1.Preset' is not a function of TMscript or of this project"),
    ('TBase b1 = 0,0,0,0,0,0\nfloat[] f = b1.GetValue(1)', "packet:2:13: error GPL5314: TBase.GetValue() is not supported yet by gpl2py"),
    ("TTCP t = 0,0,0,0,0,0\nt.Frob()", "packet:2:1: error GPL5302: 'TTCP.Frob' is not a function of TMscript or of this project"),
])
def test_a_method_the_variable_does_not_have_is_reported_not_a_python_error(packet: str, header: str) -> None:
    """``var.Method()`` on a bare word or a class without that method was an AttributeError at run
    time (E81's ``b1.GetValue(1)``, a packet naming a device of an earlier node it never declared)."""
    assert [d.header() for d in translate_packet(packet).errors] == [header]
    assert translate_packet('ModbusTCP m = "127.0.0.1"\nm.Preset("a", 1, "DO", 1, "bool")').errors == []


def _loops(depth: int, kinds: tuple[str, ...] = ("while", "for", "do")) -> str:
    """Statements of a packet: ``depth`` nested loops (while, for, do...while in turn), each run
    once, around a Display."""
    opened, closed = [], []
    for k in range(depth):
        kind = kinds[k % len(kinds)]
        if kind == "while":
            opened += [f"int w{k} = 1", f"while (w{k} == 1) {{", f"w{k} = 0"]
            closed.append("}")
        elif kind == "for":
            opened.append(f"for (int f{k} = 0; f{k} < 1; f{k}++) {{")
            closed.append("}")
        else:
            opened.append("do {")
            closed.append("} while (false)")
    return "\n".join(opened + ['Display("inside")'] + closed[::-1])


def test_loops_nest_as_deep_as_python_compiles_and_one_more_is_one_error_at_the_innermost() -> None:
    """TMscript nests loops deeper than CPython compiles (20 loops in one function): 20 translate
    to Python that compiles, 21 are GPL5701 once, at the 21st loop, and never an internal error."""
    ok = translate_packet(_loops(20))
    assert not ok.errors, [d.header() for d in ok.errors]
    compile(ok.python, "packet", "exec")
    deep = translate_packet(_loops(21))
    assert [d.code for d in deep.errors] == ["GPL5701"], [d.header() for d in deep.errors]
    line = [n for n, text in enumerate(_loops(21).splitlines(), 1)
            if text.startswith(("while", "for", "do"))][20]
    assert deep.errors[0].span.line == line


def test_blocks_nested_past_the_parsers_limit_are_one_error_and_the_rest_of_the_script_is_read(
        tmp_path: Path) -> None:
    """Braces nested 200 deep: one GPL5103 at the first brace past the limit, the block skipped to
    its closing brace, and the script after it read as usual (an error there is still found)."""
    body = "if (i == 0) {\n" * 200 + 'Display("x")\n' + "}\n" * 200
    path = tmp_path / "deep.tms"
    path.write_text("main\n{\nint i = 0\n" + body + "Nope(1)\n}\n")
    sink = DiagnosticSink()
    transpile(path, sink, language="tmscript")
    assert [(d.code, d.span.line) for d in sink.errors] == [("GPL5103", 53), ("GPL5302", 405)], \
        [d.header() for d in sink.errors]


def test_a_device_declared_inside_twenty_loops_is_one_error_at_its_declaration(tmp_path: Path) -> None:
    """The ``with`` block that closes a function's device at the end of its block counts as
    CPython counts it: inside 19 loops it translates, inside 20 it is GPL5701 at the declaration,
    the statement that opens the 21st block (unmeasured, the error fell on the loop around it)."""
    def errors(depth: int) -> list[tuple[str, int]]:
        opened = [f"for (int f{k} = 0; f{k} < 1; f{k}++) {{" for k in range(depth)]
        path = tmp_path / f"deep{depth}.tms"
        path.write_text("\n".join(["void F()", "{"] + opened + ['Socket s = "127.0.0.1", 1']
                                  + ["}"] * depth + ["}", "main", "{", "F()", "}"]))
        sink = DiagnosticSink()
        transpile(path, sink, language="tmscript")
        return [(d.code, d.span.line) for d in sink.errors]

    assert errors(19) == []
    assert errors(20) == [("GPL5701", 23)]


# what the TMscript fuzz (tests/tm/test_tm_fuzz.py) found


@pytest.mark.parametrize("text, code", [
    ("main\n{\n  num = 10\n  3 = 4\n}\n", "GPL5104"),  # kept-going Python was '"num" = 10': no module
    ("define\n{\n  {\n    int x = 1\n  }\n}\nmain\n{\n}\n", "GPL5103"),  # a block in define: KeyError (GPL9000)
    ("main\n{\n  if (true)\n  {\n    continue\n  }\n  break\n}\n", "GPL5307"),  # 'continue' Python refuses
    ("main\n{\n  lambda(1)\n}\n", "GPL5302"),  # 'tm.lambda(1)'
])
def test_keep_going_output_of_an_erroneous_script_compiles(tmp_path: Path, text: str, code: str) -> None:
    src = tmp_path / "bad.tms"
    src.write_text(text)
    sink = DiagnosticSink()
    out = transpile(src, sink, keep_going=True)
    assert code in [d.code for d in sink.errors] and "GPL9000" not in [d.code for d in sink], \
        [d.header() for d in sink]
    assert out is not None
    for name, py in out.files.items():
        if name.endswith(".py"):
            compile(py, name, "exec")


def test_a_chain_past_the_limit_is_one_error_and_one_within_it_is_python_that_compiles() -> None:
    """Each binary operator is a call in the Python (``tm.add(a, b)``): a chain of 200 ``&&``
    gave a packet without errors whose Python does not compile (too many nested parentheses)."""
    ok = translate_packet("bool fz = " + " && ".join(["1"] * 100))
    assert not ok.errors, [d.header() for d in ok.errors]
    compile(ok.python, "packet", "exec")
    long = translate_packet("bool fz = " + " && ".join(["1"] * 200))
    assert [d.code for d in long.errors] == ["GPL5103"], [d.header() for d in long.errors]


@pytest.mark.parametrize("text", [
    "int x = 1\n" + "switch (x)\n{\ncase 1\n" * 300 + "Display(1)\n" + "}\n" * 300,  # RecursionError
    "int x = " + "1 ? 2 : " * 2000 + "3",  # RecursionError
])
def test_switches_and_conditionals_past_the_limits_are_an_error_not_a_recursion_error(text: str) -> None:
    found = translate_packet(text).errors
    assert [d.code for d in found] and all(d.code == "GPL5103" for d in found), [d.header() for d in found]


def test_names_that_python_reserves_and_the_same_with_an_underscore_stay_two_names() -> None:
    """``v`` is ``v_`` in the Python (the node's variables are ``v``), and ``v_`` was ``v_`` too: two
    TMscript variables were one Python name (in parameters, a function Python refuses)."""
    p = translate_packet("int v = 1\r\nint v_ = 2\r\nint list = 3\r\nint list_ = 4\r\nDisplay(v + \" \" + v_ + list + list_)")
    assert not p.errors, [d.header() for d in p.errors]
    compile(p.python, "packet", "exec")
    assert {"v_", "v__", "list_", "list__"} <= {var.pyname for var in p.declared.values()}


def test_numbers_past_a_double_are_the_scripts_error_not_python_s() -> None:
    """A literal past the double's range (1e400; an integer of 200 digits into a double) gave
    Python a bare ``inf`` or an OverflowError from inside the runtime; they are the script's error
    now, in the runtime's words, and the packet's Python compiles."""
    from gplrt.tm.values import TMError, to_double, to_float

    for text in ("double d = 1e400", "double d = " + "9" * 200, "float f = " + "9" * 60):
        p = translate_packet(text)
        assert not p.errors, [d.header() for d in p.errors]
        compile(p.python, "packet", "exec")
    with pytest.raises(TMError, match="out of the range of a double"):
        to_double(10 ** 400)
    with pytest.raises(TMError, match="out of the range of a float"):
        to_float(10 ** 39)
    with pytest.raises(TMError, match="cannot be converted to double"):
        to_double(float("inf"))

