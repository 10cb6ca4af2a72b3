"""The V+ front end's syntax (issue 21, milestone 1): the corpus checks clean, bad input is a
positioned diagnostic, never a traceback.

The corpus (``../shared/corpus/vplus``, or ``$GPL_CORPUS``; read in place) is real V+: Adept's ROS
server and the robot-sandbox teaching programs, whose simulator accepted a looser dialect (IF
without THEN, WHILE without DO, ELSEIF) that is read with a warning naming it.
"""

from __future__ import annotations

import random
from pathlib import Path

import pytest

from gpl2py.diagnostics import DiagnosticSink
from gpl2py.source import SourceFile
from gpl2py.transpile import transpile
from gpl2py.vplus.syntax import ast as A
from gpl2py.vplus.syntax.parser import parse
from gpltest import corpus_dir


def _vplus_folders() -> list[Path]:
    root = corpus_dir() / "vplus"
    return sorted({p.parent for p in root.rglob("*.v2")})


def _check(path: Path | str, language: str | None = None) -> DiagnosticSink:
    sink = DiagnosticSink()
    transpile(path, sink, keep_modules=False, language=language)
    return sink


def _parse(text: str, path: str = "t.v2") -> tuple[A.Module, list[str]]:
    sink = DiagnosticSink()
    module = parse(SourceFile(path, text), sink)
    return module, [d.header() for d in sink.sorted()]


def test_every_folder_of_the_vplus_corpus_checks_with_no_error() -> None:
    folders = _vplus_folders()
    assert len(folders) >= 7, folders  # swri-ros, tests and the five robot-programs folders
    for folder in folders:
        sink = _check(folder)
        assert [d.header() for d in sink.errors] == [], folder
        for d in sink.warnings:  # each warning has a reason: a V+ front-end code
            assert d.code.startswith("GPL4"), d.header()


def test_the_robot_sandbox_dialect_is_read_with_a_warning_naming_it() -> None:
    sink = _check(corpus_dir() / "vplus" / "robot-sandbox" / "tests" / "vplustests.v2")
    codes = {d.code for d in sink}
    assert {"GPL4120", "GPL4121", "GPL4122"} <= codes
    assert all("robot-sandbox" in d.message for d in sink if d.code in ("GPL4120", "GPL4121", "GPL4122"))
    assert not sink.errors


def test_ros_server_parses_into_its_eight_programs() -> None:
    path = corpus_dir() / "vplus" / "swri-ros" / "ros.v2"
    module, diags = _parse(path.read_text(), str(path))
    assert diags == []
    assert [p.name for p in module.programs] == [
        "a.ros", "ros.msg.create", "ros.read.4bytes", "ros.read.joints", "ros.rev.bytes",
        "ros.srv.cmd", "ros.srv.fdb", "ros.stop"]
    cmd = module.programs[5]
    labels = {s.label: s for s in cmd.body if s.label is not None}
    assert set(labels) == {99, 100}
    assert isinstance(labels[99], A.Instr) and labels[99].word == "FCLOSE"
    assert isinstance(labels[100], A.Return)


def test_keywords_are_case_insensitive_and_dotted_names_are_names() -> None:
    module, diags = _parse(".program Main()\n  type \"x\"\n  wait.location = 3\n  If a Then\n  eNd\n.end\n")
    assert diags == []
    body = module.programs[0].body
    assert isinstance(body[0], A.Instr) and body[0].word == "TYPE"
    assert isinstance(body[1], A.Assign) and body[1].target.name == "wait.location"
    assert isinstance(body[2], A.If)


def test_operator_precedence_is_the_users_guide_table() -> None:
    # AND is evaluated with *, OR with +, relations last (User's Guide, Order of Operator Evaluation)
    module, diags = _parse(".PROGRAM p()\n  x = a OR b > c\n  y = 1 + 2 * 3 AND 4\n  z = -2 * 3\n.END\n")
    x, y, z = (s.value for s in module.programs[0].body)  # type: ignore[attr-defined]
    assert isinstance(x, A.Binary) and x.op == ">" and isinstance(x.left, A.Binary) and x.left.op == "OR"
    assert isinstance(y, A.Binary) and y.op == "+" and isinstance(y.right, A.Binary) and y.right.op == "AND"
    assert isinstance(y.right.left, A.Binary) and y.right.left.op == "*"
    assert isinstance(z, A.Binary) and isinstance(z.left, A.Unary)
    assert diags == ["t.v2:2:7: warning GPL4123: OR binds tighter than > in V+: this reads (a OR ...) > ...; "
                     "add parentheses to say which is meant"]


def test_sigils_compose_numbers_and_formats() -> None:
    text = (".PROGRAM p($s, #pp, jts[])\n"
            "  SET x = a:b:SHIFT(c BY 1, 2, 3)\n"
            "  WRITE (lun) $msg, /S\n"
            "  y = ^HFF + ^B101 + ^17 + 'A + 1.5E2\n"
            "  WAIT.EVENT , 7.25\n"
            ".END\n")
    module, diags = _parse(text)
    assert diags == []
    prog = module.programs[0]
    assert [p.var.sigil + p.var.name + ("[]" if p.var.whole else "") for p in prog.params] == ["$s", "#pp", "jts[]"]
    set_, write, assign, wait = prog.body
    assert isinstance(set_, A.SetLoc) and isinstance(set_.value, A.Binary) and set_.value.op == ":"
    shift = set_.value.right
    assert isinstance(shift, A.Call) and shift.by is not None and len(shift.by) == 3
    assert isinstance(write, A.Instr) and isinstance(write.args[1], A.Format) and write.args[1].letter == "S"
    values = []

    def walk(e: A.Expr) -> None:
        if isinstance(e, A.Binary):
            walk(e.left)
            walk(e.right)
        elif isinstance(e, A.Num):
            values.append(e.value)
    walk(assign.value)  # type: ignore[attr-defined]
    assert values == [255, 5, 15, 65, 150]
    assert isinstance(wait, A.Instr) and wait.args[0] is None and isinstance(wait.args[1], A.Num)


def test_data_sections_are_read_as_v_plus_stores_them() -> None:
    text = (".PROGRAM p()\n.END\n"
            ".LOCATIONS\n"
            "pick    100 200 300 0 180 0\n"
            "#safe   0 -90 180 0 0 0\n"
            ".END\n"
            ".REALS\n"
            "dx      12.5\n"
            ".END\n"
            ".STRINGS\n"
            "$name   \"cell 1\"\n"
            ".END\n")
    module, diags = _parse(text)
    assert diags == []
    kinds = [(s.kind, [(d.var.shown, d.values, d.text) for d in s.data]) for s in module.data]
    assert kinds == [("LOCATIONS", [("pick", [100, 200, 300, 0, 180, 0], None), ("#safe", [0, -90, 180, 0, 0, 0], None)]),
                     ("REALS", [("dx", [12.5], None)]),
                     ("STRINGS", [("$name", [], "cell 1")])]


@pytest.mark.parametrize(("text", "expected"), [
    (".PROGRAM p()\n  x = (1 +\n.END\n", "t.v2:2:11: error GPL4100: expected a value, found end of line"),
    (".PROGRAM p()\n  x = 1 2\n.END\n", "t.v2:2:9: error GPL4100: expected end of line, found '2'"),
    (".PROGRAM p()\n  TYPE \"abc\n.END\n", "t.v2:2:8: error GPL4002: string not closed before the end of the line"),
    (".PROGRAM p()\n  x = 1 @ 2\n.END\n", "t.v2:2:9: error GPL4001: unexpected character '@' in V+ source"),
    (".PROGRAM p()\n  FROB 3\n.END\n", "t.v2:2:3: error GPL4101: unknown V+ instruction FROB"),
    (".PROGRAM p()\n  IF x THEN\n    TYPE 1\n.END\n", "t.v2:2:3: error GPL4104: IF is not closed: END expected before .END"),
    (".PROGRAM p()\n  END\n.END\n", "t.v2:2:3: error GPL4105: END without a matching IF, CASE, WHILE or FOR"),
    (".PROGRAM p()\n  x = 1\n", "t.v2:1:10: error GPL4103: .PROGRAM p has no .END"),
    ("x = 1\n", "t.v2:1:1: error GPL4102: statement outside a program: a V+ file holds .PROGRAM ... .END "
     "blocks and data sections"),
    (".PROGRAM p()\n  x = 1\n  AUTO y\n.END\n",
     "t.v2:3:3: error GPL4106: AUTO must come before the first executable instruction"),
    (".PROGRAM p()\n  x = ^H\n.END\n", "t.v2:2:7: error GPL4003: invalid number ^H"),
    (".PROGRAM p()\n  70000 x = 1\n.END\n", "t.v2:2:3: error GPL4107: step label 70000 is not an integer from 0 to 65535"),
])
def test_syntax_errors_are_positioned(text: str, expected: str) -> None:
    _, diags = _parse(text)
    assert expected in diags, diags


def test_semantic_errors_name_the_program_and_label(tmp_path: Path) -> None:
    src = tmp_path / "m.v2"
    src.write_text(".PROGRAM main()\n  GOTO 10\n  CALL nothere()\n  EXIT\n.END\n")
    sink = _check(src)
    assert [d.header() for d in sink.errors] == [
        f"{src}:2:8: error GPL4308: no step label 10 in program main",
        f"{src}:3:8: error GPL4300: program nothere is not defined in this project",
        f"{src}:4:3: error GPL4309: EXIT outside a FOR, DO or WHILE loop",
    ]


def test_a_file_is_v_plus_by_its_first_line_whatever_its_extension(tmp_path: Path) -> None:
    src = tmp_path / "prog.txt"
    src.write_text("; a V+ program\n\n.PROGRAM main()\n  FROB\n.END\n")
    sink = _check(src)
    assert [d.code for d in sink] == ["GPL4101"]


def test_language_vplus_forces_the_front_end(tmp_path: Path) -> None:
    src = tmp_path / "prog.gpl"
    src.write_text(".PROGRAM main()\n  x = 1\n.END\n")
    assert _check(src, "vplus").errors == []
    assert _check(src).errors  # as GPL it is not a program


def test_random_mutations_of_the_corpus_never_give_an_internal_error(tmp_path: Path) -> None:
    files = sorted((corpus_dir() / "vplus").rglob("*.v2"))
    texts = [f.read_text(encoding="utf-8", errors="replace") for f in files]
    rng = random.Random(21)
    pieces = [".PROGRAM", ".END", "IF", "THEN", "END", "CASE", "VALUE", ":", "(", ")", "[", "]", ",", "\"",
              "=", "==", "SET", "HERE", ";", "^H", "'", "#", "$", "%", "DO", "UNTIL", "FOR", "TO", "GOTO 5",
              "5 ", "\x00", "\u00e9", "\t", "\n", "BY", "SHIFT(", "CALL x(", "..", "1e999", "-", "NOT"]
    inputs = 0
    for n in range(150):
        text = rng.choice(texts)
        for _ in range(rng.randint(1, 6)):
            i = rng.randrange(len(text) + 1)
            op = rng.random()
            if op < 0.4:
                text = text[:i] + rng.choice(pieces) + text[i:]
            elif op < 0.7:
                text = text[:i] + text[i + rng.randint(1, 20):]
            else:
                j = rng.randrange(len(text) + 1)
                text = text[:i] + text[j:j + 30] + text[i:]
        path = tmp_path / f"m{n}.v2"
        path.write_text(text, encoding="utf-8", errors="replace")
        sink = DiagnosticSink()
        output = transpile(path, sink, keep_going=True)  # every phase, lowering included
        inputs += 1
        for d in sink:
            assert d.code != "GPL9000", (n, d.header(), text)
            assert d.span is not None and d.span.line >= 1, d.header()
        for name, code in (output.files.items() if output is not None else ()):
            if name.endswith(".py"):
                compile(code, name, "exec")  # the translation, even with errors kept, is Python
    assert inputs == 150


def test_the_users_guide_programs_in_the_spec_parse() -> None:
    """Appendix B of the spec (bodies copied verbatim from the User's Guide) parses without an
    error; of the complete programs of Appendix A, those the PDF extraction left whole do too (the
    others have comments and strings wrapped onto the next line: spec §0)."""
    import re

    from gpltest import spec_dir

    text = (spec_dir() / "vplus-language.md").read_text()
    appendix = text[text.index("## Appendix: example programs"):]
    part_b = appendix[appendix.index("### Appendix B"):appendix.index("### Appendix C")]
    bodies = re.findall(r"```[a-z]*\n(.*?)```", part_b, re.S)
    assert len(bodies) >= 6
    for body in bodies:
        if ".PROGRAM" not in body.upper():
            body = ".PROGRAM body()\n" + body + ("" if ".END" in body.upper() else "\n.END\n")
        _, diags = _parse(body)
        assert [d for d in diags if " error " in d] == [], diags
    programs = [b for b in re.findall(r"```[a-z]*\n(.*?)```", appendix[:appendix.index("### Appendix B")], re.S)
                if ".PROGRAM" in b.upper()]
    clean = [i for i, b in enumerate(programs) if not [d for d in _parse(b)[1] if " error " in d]]
    assert clean == [0, 1, 2, 4, 5], clean


def test_a_v_plus_comment_ignores_a_diagnostic_on_its_line(tmp_path: Path) -> None:
    from gpl2py.selection import Selection

    src = tmp_path / "m.v2"
    src.write_text(".PROGRAM main()\n  x = 'A + 1\n  FROB 3 ; gpl2py: ignore[GPL4101]\n  FROB 4\n.END\n")
    sink = DiagnosticSink(Selection(None, ()))
    transpile(src, sink, keep_modules=False, loaded=lambda p: sink.filter.add_sources(p.sources, sink))
    assert [d.header() for d in sink.errors] == [f"{src}:4:3: error GPL4101: unknown V+ instruction FROB"]


def test_a_case_with_a_bad_value_list_and_an_arm_after_any_is_an_error_and_still_python(tmp_path: Path) -> None:
    src = tmp_path / "m.v2"
    src.write_text(".PROGRAM main()\n  CASE x OF\n  VALUE ]2:\n    TYPE 1\n  ANY\n    TYPE 2\n  ANY\n    TYPE 3\n  END\n.END\n")
    sink = DiagnosticSink()
    out = transpile(src, sink, keep_going=True)
    assert [d.header() for d in sink.errors] == [
        f"{src}:3:9: error GPL4100: expected a value, found ']'",
        f"{src}:7:3: error GPL4100: expected END after ANY, found 'ANY'",
    ]
    assert out is not None
    for name, code in out.files.items():
        if name.endswith(".py"):
            compile(code, name, "exec")  # (two ANY arms gave 'else:' twice: a SyntaxError)


def test_check_reports_what_translate_reports_and_every_corpus_translation_compiles() -> None:
    for folder in _vplus_folders():
        checked = _check(folder)
        sink = DiagnosticSink()
        out = transpile(folder, sink)
        assert [d.header() for d in checked] == [d.header() for d in sink], folder
        assert out is not None, folder
        for name, code in out.files.items():
            if name.endswith(".py"):
                compile(code, name, "exec")


def test_names_spelled_like_block_words_are_variables_where_an_assignment_is() -> None:
    text = (".PROGRAM p()\n  CASE x OF\n  VALUE 1:\n    value = 3\n    any = 4\n    end = 5\n  END\n"
            "  DO\n    until = 1\n  UNTIL until\n.END\n")
    module, diags = _parse(text)
    assert diags == []
    case, do = module.programs[0].body
    assert isinstance(case, A.Case) and [type(s).__name__ for s in case.arms[0].body] == ["Assign"] * 3
    assert isinstance(do, A.DoUntil) and isinstance(do.body[0], A.Assign)
