"""V+ programs translated and run end to end (issue 21, milestones 2, 4 and 5).

``gpl2py run`` (in a subprocess, as a user runs it) and ``Cell.load`` on V+ files: the corpus's
self-test prints what its ``[=> ...]`` notes say, the start program is ``--start`` or the first
program of the first file, data sections load before it runs, GOTO jumps between blocks, a read
before any assignment is V+'s *Undefined value* at its V+ line, and the generated Python keeps V+
names, comments and lines.
"""

from __future__ import annotations

import json
import os
import re
import subprocess
import sys
import warnings
from pathlib import Path

from gpl2py.diagnostics import DiagnosticSink
from gpl2py.notebook import Cell
from gpl2py.transpile import transpile
from gpltest import corpus_dir


def _run(path: Path | str, *options: str) -> subprocess.CompletedProcess[str]:
    env = {**os.environ, "GPL2PY_CACHE_DIR": str(Path(path).parent / ".cache")} \
        if Path(path).parent.is_dir() and os.access(Path(path).parent, os.W_OK) else dict(os.environ)
    return subprocess.run([sys.executable, "-m", "gpl2py", "run", str(path), "--quiet", *options],
                          capture_output=True, text=True, timeout=300, env=env)


def _write(tmp_path: Path, text: str, name: str = "main.v2") -> Path:
    path = tmp_path / name
    path.write_text(text)
    return path


def test_the_corpus_self_test_prints_what_its_notes_say(tmp_path: Path) -> None:
    src = corpus_dir() / "vplus" / "robot-sandbox" / "tests" / "vplustests.v2"
    r = _run(src, "--cache-dir", str(tmp_path / "cache"))
    assert r.returncode == 0, r.stderr
    lines = r.stdout.splitlines()
    checked = 0
    for i, line in enumerate(lines):
        m = re.search(r"\[=> ([^\]]*)\]", line)
        if m is None:
            continue
        expected = m.group(1).split()
        assert lines[i + 1:i + 1 + len(expected)] == expected, (line, lines[i + 1:i + 1 + len(expected)])
        checked += 1
    assert checked == 7  # array, do-until, for, while-next, if-else, if-elseif-else, for-exit


def test_the_start_program_is_the_first_of_the_first_file_or_start(tmp_path: Path) -> None:
    src = _write(tmp_path, ".PROGRAM first()\n  TYPE \"first\"\n.END\n.PROGRAM second()\n  TYPE \"second\"\n.END\n")
    assert _run(src).stdout == "first\n"
    assert _run(src, "--start", "SECOND").stdout == "second\n"
    r = _run(src, "--start", "third")
    assert r.returncode == 1 and "error GPL4311: --start third: no such program in this project" in r.stderr


def test_cell_load_runs_a_v_plus_project_through_the_same_door(tmp_path: Path) -> None:
    folder = tmp_path / "cell"
    folder.mkdir()
    _write(folder, ".PROGRAM main()\n  CALL helper(x)\n  TYPE \"x is \", x\n.END\n", "a.v2")
    _write(folder, ".PROGRAM helper(v)\n  v = 41 + 1\n.END\n.PROGRAM other()\n  TYPE \"other\"\n.END\n", "b.v2")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        cell = Cell.load(folder, echo=False, cache_dir=tmp_path / "cache")
        assert cell.run_main() == 0
        assert cell.sim.console.output == "x is 42\n"
        other = Cell.load(folder, echo=False, cache_dir=tmp_path / "cache", start="other")
        assert other.run_main() == 0
        assert other.sim.console.output == "other\n"


def test_data_sections_are_loaded_before_the_program_runs(tmp_path: Path) -> None:
    src = _write(tmp_path, ".PROGRAM main()\n  TYPE $name, \" \", dx * 2, \" \", DX(pick)\n.END\n"
                 ".REALS\ndx 12.5\n.END\n.STRINGS\n$name \"cell\"\n.END\n"
                 ".LOCATIONS\npick 100 200 300 0 180 0\n.END\n")
    r = _run(src)
    assert r.returncode == 0, r.stderr
    assert r.stdout == "cell 25 100\n"


def test_goto_leaves_and_reenters_blocks_forward_and_backward(tmp_path: Path) -> None:
    src = _write(tmp_path, (
        ".PROGRAM main()\n"
        "    n = 0\n"
        "10  n = n + 1\n"
        "    WHILE TRUE DO\n"
        "        IF n < 3 THEN\n"
        "            GOTO 10\n"
        "        END\n"
        "        GOTO 20\n"
        "    END\n"
        "    TYPE \"skipped\"\n"
        "20  TYPE \"n = \", n\n"
        ".END\n"))
    r = _run(src)
    assert r.returncode == 0, r.stderr
    assert r.stdout == "n = 3\n"


GOTO_INTO_BLOCKS = """\
.PROGRAM main()
; GOTO into IF, ELSE, CASE, WHILE and DO blocks
        n = 0
        GOTO 10
        TYPE "skipped"
        IF n > 100 THEN
            TYPE "never: n > 100"
10          TYPE "in the THEN block, n=", n
            n = n+1
        ELSE
            TYPE "else, n=", n
20          TYPE "in the ELSE block, n=", n
            n = n+1
        END
        IF n < 2 GOTO 20
        CASE n OF
        VALUE 1:
            TYPE "one"
        VALUE 2:
            TYPE "two"
30          TYPE "in VALUE 2, n=", n
        ANY
            TYPE "any"
        END
        IF n == 2 THEN
            n = 5
            GOTO 30
        END
        k = 10
        GOTO 40
        WHILE k < 3 DO
            TYPE "while k=", k
40          k = k-7
            TYPE "k=", k
        END
        m = 0
        again = 0
        DO
            m = m+1
50          TYPE "do m=", m
            m = m+1
        UNTIL m > 5
        IF again <> 1 THEN
            again = 1
            m = 3
            GOTO 50
        END
        TYPE "end n=", n, " k=", k, " m=", m
.END
"""


def test_goto_enters_if_else_case_while_and_do_blocks_as_the_controller_runs_them(tmp_path: Path) -> None:
    """V+ runs a program step by step: a GOTO to a label inside a block runs from there, and the
    block's END (or ELSE, VALUE, UNTIL) does what it always does -- an IF's goes on after the IF,
    a WHILE's tests the condition again, an UNTIL tests its own (L4376-4397)."""
    expected = ["in the THEN block, n=0", "in the ELSE block, n=1", "two", "in VALUE 2, n=2", "in VALUE 2, n=5",
                "k=3", "do m=1", "do m=3", "do m=5", "do m=3", "do m=5", "end n=5 k=3 m=6"]
    _prints_plain_and_under_reacte(tmp_path, GOTO_INTO_BLOCKS, "        n = 0\n", expected)


def _prints_plain_and_under_reacte(tmp_path: Path, src: str, first: str, expected: list[str]) -> None:
    """The program prints ``expected``, and the same with ``REACTE trap`` before its line
    ``first``: each statement, and each test of a block, is then a resumable step of its own."""
    r = _run(_write(tmp_path, src))
    assert r.returncode == 0, r.stderr
    assert r.stdout.splitlines() == expected
    trapped = src.replace(first, "        REACTE trap\n" + first, 1) + ".PROGRAM trap()\n        TYPE \"trapped\"\n.END\n"
    r = _run(_write(tmp_path, trapped, "trapped.v2"))
    assert r.returncode == 0, r.stderr
    assert r.stdout.splitlines() == expected


GUIDE_DISK_EXAMPLE = """\
.PROGRAM disk.example()
AUTO dlun, i
AUTO $file.name
$file.name = "data.tst"

; Attach to a disk logical unit
ATTACH (dlun, 4) "DISK"
IF IOSTAT(dlun) < 0 GOTO 100

; Open a new file and check status
FOPENW (dlun) $file.name
IF IOSTAT(dlun) < 0 GOTO 100

; Write the text
FOR i = 1 TO 10

WRITE (dlun) "Line "+$ENCODE(i)
IF IOSTAT(dlun) < 0 GOTO 100

END

; Close the file
FCLOSE (dlun)
IF IOSTAT(dlun) < 0 GOTO 100

; Reopen the file and read its contents
FOPENR (dlun) $file.name
IF IOSTAT(dlun) < 0 GOTO 100
READ (dlun) $txt
WHILE IOSTAT(dlun) > 0 DO

TYPE $txt
READ (dlun) $txt

END ;End of file or error
IF (IOSTAT(dlun) < 0) AND (IOSTAT(dlun) <> -504) THEN

100 TYPE $ERROR(IOSTAT(dlun)) ;Report any errors
END
FCLOSE (dlun) ;Close the file
IF IOSTAT(dlun) < 0 THEN

TYPE $ERROR(IOSTAT(dlun))
END
DETACH (dlun) ;Detach the LUN
.END
"""


def test_the_guides_disk_example_which_jumps_into_a_then_block_translates_and_runs(tmp_path: Path) -> None:
    """The User's Guide's disk I/O example (L7755-7798, spec Appendix B.2) as printed, inside a
    .PROGRAM: its ``GOTO 100`` lands in a THEN block."""
    r = _run(_write(tmp_path, GUIDE_DISK_EXAMPLE))
    assert r.returncode == 0, r.stderr
    assert r.stdout.splitlines() == [f"Line {i}" for i in range(1, 11)]


GOTO_IN_AND_OUT_OF_FOR = """\
.PROGRAM main()
; GOTO within one FOR body, forward and backward, and out of FOR loops
        last = 4
        FOR i = 1 TO last
            last = 1                    ; (the end was evaluated once, at the FOR)
            IF i == 2 GOTO 10           ; forward: skips the rest of the body's first part
            TYPE "body i=", i
10      tries = 0
20      tries = tries+1
            IF tries < i GOTO 20        ; backward: a retry loop inside the body
            TYPE "i=", i, " tries=", tries
        END
        TYPE "after i=", i
        FOR c = 1 TO 2
            IF c == 1 GOTO 60           ; into a THEN block inside the same FOR body
            IF c == 99 THEN
60              TYPE "in the THEN block, c=", c
            END
            TYPE "c=", c
        END
        FOR a = 1 TO 3
            FOR b = 1 TO 5
                IF b == a GOTO 50       ; out of the inner loop, on in the outer body
            END
            TYPE "never"
50      TYPE "a=", a, " b=", b
        END
        total = 0
        FOR i = 1 TO 3
            FOR j = 1 TO 3
                total = total+1
                IF (i == 2) AND (j == 2) GOTO 30    ; out of both loops
            END
        END
30      TYPE "out at i=", i, " j=", j, " total=", total
        FOR k = 1 TO 10 STEP 2
            IF k == 5 GOTO 40
        END
40      TYPE "k=", k
        FOR m = 1 TO 3
            m = 10                      ; past the end: the GOTO still goes on in the body
            GOTO 70
            TYPE "never"
70          TYPE "m=", m
        END
        TYPE "after m=", m
.END
"""


def test_goto_within_a_for_body_and_out_of_for_loops_runs_as_the_controller_runs_it(tmp_path: Path) -> None:
    """A GOTO whose label is in the same FOR body runs from that label on without going through
    the FOR statement again (so without a new test of the end, evaluated once at the FOR,
    L4889-4890); a GOTO out of one or more FOR loops leaves them with their index as it is."""
    expected = ["body i=1", "i=1 tries=1", "i=2 tries=2", "body i=3", "i=3 tries=3", "body i=4",
                "i=4 tries=4", "after i=5", "in the THEN block, c=1", "c=1", "c=2",
                "a=1 b=1", "a=2 b=2", "a=3 b=3", "out at i=2 j=2 total=5", "k=5", "m=10", "after m=11"]
    _prints_plain_and_under_reacte(tmp_path, GOTO_IN_AND_OUT_OF_FOR, "        last = 4\n", expected)


def test_a_goto_into_a_for_loop_from_outside_it_stays_refused_and_only_that_goto(tmp_path: Path) -> None:
    """Entering a FOR body other than through its FOR statement would skip the evaluation of its
    end and step (L4889-4890): GPL4700 at each GOTO that does it -- from the outer loop's body into
    an inner loop, from the top level -- and not at a GOTO to the same label within the body."""
    src = _write(tmp_path, """\
.PROGRAM main()
        FOR i = 1 TO 2
            IF i == 1 GOTO 10
            FOR j = 1 TO 2
10              TYPE "j"
            END
        END
        FOR k = 1 TO 2
20          TYPE "k=", k
            IF k == 1 GOTO 20
        END
        IF k == 3 GOTO 20
.END
""")
    r = _run(src)
    assert r.returncode != 0
    errors = [line for line in r.stderr.splitlines() if "error GPL" in line]
    assert [e.split(": error ")[0].rsplit(":", 2)[1:] for e in errors] == [["3", "13"], ["12", "9"]]
    assert all("GPL4700" in e and "from outside it" in e for e in errors)


EXIT_AND_NEXT_WITH_A_COUNT = """\
.PROGRAM main()
; EXIT n and NEXT n leave n nested loops
        FOR i = 1 TO 3
            FOR j = 1 TO 3
                k = 0
                WHILE k < 5 DO
                    k = k+1
                    IF (i == 2) AND (j == 2) AND (k == 2) THEN
                        EXIT 3          ; out of the FOR i
                    END
                    IF k == 3 THEN
                        NEXT 2          ; the next j
                    END
                END
                TYPE "never: NEXT 2 skips this"
            END
            TYPE "i ", i, " done"
        END
        TYPE "after: i=", i, " j=", j, " k=", k
        n = 0
        DO
            n = n+1
            FOR m = 1 TO 4
                IF m == 2 THEN
                    NEXT 2              ; the DO's next pass: its UNTIL is tested
                END
                TYPE "m ", m
            END
        UNTIL n >= 3
        TYPE "n=", n, " m=", m
.END
"""


def test_exit_n_and_next_n_leave_n_nested_loops(tmp_path: Path) -> None:
    r = _run(_write(tmp_path, EXIT_AND_NEXT_WITH_A_COUNT))
    assert r.returncode == 0, r.stderr
    assert r.stdout.splitlines() == ["i 1 done", "after: i=2 j=2 k=2", "m 1", "m 1", "m 1", "n=3 m=2"]


def _nested_loops(depth: int, reacte: bool) -> str:
    """A FOR, WHILE and DO nest of ``depth`` loops around a TYPE, each loop run once."""
    kinds = ["FOR", "WHILE", "DO"]
    head = [".PROGRAM main()"] + (["        REACTE trap"] if reacte else []) + ['        TYPE "start"']
    opened, closed = [], []
    for k in range(depth):
        kind = kinds[k % 3]
        if kind == "FOR":
            opened.append(f"        FOR i{k} = 1 TO 1")
            closed.append("        END")
        elif kind == "WHILE":
            opened += [f"        w{k} = 1", f"        WHILE w{k} DO", f"            w{k} = 0"]
            closed.append("        END")
        else:
            opened.append("        DO")
            closed.append("        UNTIL TRUE")
    tail = ['        TYPE "end"', ".END", ".PROGRAM trap()", '        TYPE "trapped ", ERROR(-1)', ".END"]
    return "\n".join(head + opened + ['        TYPE "inside"'] + closed[::-1] + tail) + "\n"


def _loop_line(text: str, nth: int) -> int:
    """The line of the ``nth`` loop statement (1-based) of ``_nested_loops``' text."""
    loops = [n for n, line in enumerate(text.splitlines(), 1) if line.split()[:1] in (["FOR"], ["WHILE"], ["DO"])]
    return loops[nth - 1]


def test_loops_nest_as_deep_as_python_compiles_and_one_more_is_an_error_that_raises_when_reached(
        tmp_path: Path) -> None:
    """V+ nests loops deeper than CPython compiles (20 loop and with blocks in one function); the
    deepest nest that fits runs, and one loop more is GPL4702 at the innermost loop Python would
    refuse (not an internal error), whose line raises *Not implemented* under --ignore (or
    --keep-going), where REACTE traps it.  Under REACTE every instruction that can fail is a
    ``with`` block of its own, so one loop fewer fits."""
    for reacte, deepest in ((False, 20), (True, 19)):
        r = _run(_write(tmp_path, _nested_loops(deepest, reacte), f"ok{reacte}.v2"))
        assert r.returncode == 0, r.stderr
        assert r.stdout.splitlines() == ["start", "inside", "end"]
        text = _nested_loops(deepest + 1, reacte)
        deep = _write(tmp_path, text, f"deep{reacte}.v2")
        sink = DiagnosticSink()
        transpile(deep, sink, keep_modules=False)
        assert [d.code for d in sink] == ["GPL4702"], [d.header() for d in sink]
        innermost = _loop_line(text, deepest + 1)
        assert sink.errors[0].span is not None and sink.errors[0].span.line == innermost
        r = _run(deep, "--ignore", "GPL4702")
        if reacte:
            assert r.returncode == 0, r.stderr
            assert r.stdout.splitlines() == ["start", "trapped -430", "end"]
        else:
            assert r.returncode == 3
            assert r.stdout.splitlines() == ["start"]
            assert f"{deep}:{innermost}: error -430 in thread task 0: *Not implemented* - GPL4702" in r.stderr


KEPT_ERRORS = """\
.PROGRAM main()
        REACTE trap
        TYPE "start"
        FROB 3
        TYPE "after frob"
        x = (1 +
        TYPE "after bad expression"
        CALL nothing()
        TYPE "after call"
        y = FROB(1)
        TYPE "after function"
        SET p = TRANS(1)
        p = 2
        TYPE "end"
.END
.PROGRAM trap()
        TYPE "trapped ", ERROR(-1), " ", $ERROR(ERROR(-1))
.END
"""
KEPT = "GPL4100,GPL4101,GPL4300,GPL4304,GPL4306"


def test_a_line_kept_with_its_error_raises_v_plus_error_there_which_reacte_traps(tmp_path: Path) -> None:
    """--keep-going, or the errors ignored: each line V+ would not have loaded raises *Program not
    executable* when reached, a CALL of no program *Undefined program or variable name*, a real
    stored into a location *Data type mismatch* -- and the rest of the program runs."""
    r = _run(_write(tmp_path, KEPT_ERRORS), "--ignore", KEPT)
    assert r.returncode == 0, r.stderr
    assert r.stdout.splitlines() == [
        "start", "trapped -311 *Program not executable*", "after frob",
        "trapped -311 *Program not executable*", "after bad expression",
        "trapped -402 *Undefined program or variable name*", "after call",
        "trapped -311 *Program not executable*", "after function",
        "trapped -407 *Data type mismatch*", "end"]
    untrapped = _write(tmp_path, KEPT_ERRORS.replace("        REACTE trap\n", "        TYPE \"no trap\"\n"), "plain.v2")
    r = _run(untrapped, "--ignore", KEPT)
    assert r.stdout == "no trap\nstart\n"
    assert r.returncode == 3
    assert (f"{untrapped}:4: error -311 in thread task 0: *Program not executable* - GPL4101: unknown V+ "
            "instruction FROB") in r.stderr


def test_a_read_before_any_assignment_is_the_undefined_value_error_at_its_line(tmp_path: Path) -> None:
    src = _write(tmp_path, ".PROGRAM main()\n  TYPE \"start\"\n  x = y + 1\n  TYPE \"never\"\n.END\n")
    r = _run(src)
    assert r.stdout == "start\n"
    assert r.returncode == 3
    assert f"{src}:3: error -401 in thread task 0: *Undefined value* - y" in r.stderr


def test_arguments_pass_by_reference_unless_an_expression_is_passed(tmp_path: Path) -> None:
    src = _write(tmp_path, (
        ".PROGRAM main()\n"
        "  a = 1\n  b = 1\n  $s = \"x\"\n"
        "  CALL inc(a, (b), $s, $s+\"\")\n"
        "  TYPE a, \" \", b, \" \", $s\n"
        ".END\n"
        ".PROGRAM inc(p, q, $r, $t)\n"
        "  p = p + 1\n  q = q + 1\n  $r = $r + \"y\"\n  $t = \"changed\"\n"
        ".END\n"))
    r = _run(src)
    assert r.returncode == 0, r.stderr
    assert r.stdout == "2 1 xy\n"


def test_generated_python_keeps_names_comments_and_lines(tmp_path: Path) -> None:
    src = corpus_dir() / "vplus" / "swri-ros" / "ros.v2"
    sink = DiagnosticSink()
    out = transpile(src, sink)
    assert out is not None, [d.header() for d in sink]
    module = out.files[f"{out.package}/ros.py"]
    assert '@vp.program("ros.rev.bytes")\ndef ros_rev_bytes(s_in, s_out) -> None:' in module
    assert "    str_len.v = vp.len_(s_in.v)" in module
    assert "cmd_port.v = 11000  # TCP port for joint commands" in module
    smap = json.loads(out.files[f"{out.package}/_sourcemap.json"])
    entry = smap["modules"]["ros.py"]
    assert entry["source"] == "ros.v2"
    source_lines = src.read_text().splitlines()
    runs = entry["runs"]
    py_lines = module.splitlines()

    def v_line(n: int) -> int:  # the V+ line of Python line n (1-based)
        found = 0
        for first, line in runs:
            if first <= n:
                found = line
        return found
    seen = 0
    for n, text in enumerate(py_lines, start=1):
        if text.strip() == "cmd_port.v = 11000  # TCP port for joint commands":
            assert source_lines[v_line(n) - 1].strip().startswith("cmd.port = 11000")
            seen += 1
        if text.strip().startswith("vp.write(lun.v, s_msg.v"):
            assert source_lines[v_line(n) - 1].strip() == "WRITE (lun) $msg, /S"
            seen += 1
    assert seen == 3  # (two servers write)


def test_a_tier_3_instruction_parses_and_raises_not_implemented_when_reached(tmp_path: Path) -> None:
    src = _write(tmp_path, ".PROGRAM main()\n  TYPE \"before\"\n  GCLEAR (20)\n  TYPE \"after\"\n.END\n")
    r = _run(src)
    assert "warning GPL4124: GCLEAR is not supported by gpl2py" not in r.stderr  # (--quiet: errors only)
    assert r.stdout == "before\n"
    assert r.returncode == 3
    assert f"{src}:3: error -430 in thread task 0: *Not implemented* - GCLEAR is not simulated" in r.stderr


def test_reacte_traps_an_error_and_returne_goes_on_after_the_failing_statement(tmp_path: Path) -> None:
    src = _write(tmp_path, (
        ".PROGRAM main()\n"
        "    REACTE trouble\n"
        "    TYPE \"before\"\n"
        "    x = 1 / 0\n"
        "    TYPE \"after, x defined: \", DEFINED(x)\n"
        ".END\n"
        ".PROGRAM trouble()\n"
        "    TYPE \"trapped \", ERROR(-1)\n"
        "    RETURNE\n"
        ".END\n"))
    r = _run(src)
    assert r.returncode == 0, r.stderr
    assert r.stdout == "before\ntrapped -406\nafter, x defined: 0\n"


def test_react_runs_its_program_when_the_signal_comes_on_during_a_loop(tmp_path: Path) -> None:
    folder = tmp_path / "react"
    folder.mkdir()
    _write(folder, (
        ".PROGRAM main()\n"
        "    REACT 1001, alarm\n"
        "    SIGNAL 1\n"
        "    FOR i = 1 TO 3\n"
        "        TYPE \"tick \", i\n"
        "        WAIT.EVENT , 1\n"
        "    END\n"
        ".END\n"
        ".PROGRAM alarm()\n"
        "    TYPE \"alarm at \", i\n"
        ".END\n"))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        cell = Cell.load(folder, echo=False, cache_dir=tmp_path / "cache")
    cell.io.when_output(1, True).set_input(10001, True, after=1.5)  # the input 1001 comes on at 1.5 s
    assert cell.run_main() == 0
    assert cell.sim.console.output == "tick 1\ntick 2\nalarm at 2\ntick 3\n"


def test_scopes_local_keeps_its_value_auto_is_new_per_call_global_is_shared(tmp_path: Path) -> None:
    src = _write(tmp_path, (
        ".PROGRAM main()\n"
        "    shared = 0\n"
        "    FOR k = 1 TO 3\n"
        "        CALL count()\n"
        "    END\n"
        "    TYPE \"shared \", shared\n"
        "    IF \"abc\" == \"ABC\" THEN\n"  # UPPER is on: strings compare ignoring case
        "        TYPE \"same\"\n"
        "    END\n"
        ".END\n"
        ".PROGRAM count()\n"
        "    LOCAL calls\n"
        "    AUTO fresh\n"
        "    IF NOT DEFINED(calls) THEN\n"
        "        calls = 0\n"
        "    END\n"
        "    calls = calls + 1\n"
        "    TYPE \"calls \", calls, \" fresh \", DEFINED(fresh)\n"
        "    fresh = 1\n"
        "    shared = shared + 10\n"
        ".END\n"))
    r = _run(src)
    assert r.returncode == 0, r.stderr
    assert r.stdout == "calls 1 fresh 0\ncalls 2 fresh 0\ncalls 3 fresh 0\nshared 30\nsame\n"


def test_running_a_file_without_a_program_is_a_usage_error_that_says_what_is_missing(tmp_path: Path) -> None:
    src = _write(tmp_path, ".REALS\nx 1\n.END\n")
    r = _run(src)
    assert r.returncode == 2
    assert f"error GPL9001: {src} has no start procedure: run needs a .PROGRAM" in r.stderr


def test_under_reacte_an_error_in_a_block_header_resumes_as_if_the_test_were_false(tmp_path: Path) -> None:
    src = _write(tmp_path, (
        ".PROGRAM main()\n"
        "    REACTE trouble\n"
        "    IF 1 / 0 THEN\n"
        "        TYPE \"then\"\n"
        "    ELSE\n"
        "        TYPE \"else\"\n"
        "    END\n"
        "    n = 0\n"
        "    WHILE n < 3 DO\n"
        "        n = n + 1\n"
        "    END\n"
        "    TYPE \"n \", n\n"
        ".END\n"
        ".PROGRAM trouble()\n"
        "    TYPE \"trapped \", ERROR(-1)\n"
        "    RETURNE\n"
        ".END\n"))
    r = _run(src)
    assert r.returncode == 0, r.stderr
    assert r.stdout == "trapped -406\nelse\nn 3\n"
