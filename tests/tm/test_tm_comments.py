"""TMscript comments reach the generated Python (the project's standard: "source comments carried
along"), as GPL's and V+'s do: ``//`` and ``/* */`` (manual L1196-L1224) on lines of their own
above the statement they precede, a comment at the end of a line at the end of its statement's
line, a ``/* */`` over several lines one ``#`` line per line, the comments that end a block or the
file after its last statement.  The Python still compiles, parses with libcst, is PEP 8 and runs
as before; every line keeps its script line in the source map.
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import libcst
import pycodestyle
from tmpacket import load_project, run_loaded, run_packet

from gpl2py.diagnostics import DiagnosticSink
from gpl2py.tmscript.pipeline import translate_packet
from gpl2py.transpile import transpile
from gplrt.tm import context

SCRIPT = """\
// The counting project
/* Written for the tests:
   two lines of block comment */
define
{   // the globals
  int count = 0   // how many
  /* the limit */ int limit = 3
}

// the entry point
main
{
  // count up
  while (count < limit) {  // loop
    count++  // one more
    if (count == 2) { /* two */
      Display("two")   // say it
    } else {
      // not two
      Display("n " + count)
    }  // end if
  }
  for (int i = 0; i < 2; i++) { // twice
    Display("i " + i)
  }
  switch (count) {  // which one
    // the three
    case 3   // three
      Display("three")
      break  // done
    default
      Display("other")
  }  // end switch
  do {  // once
    count--
  } while (count > 5)  // until
  Display(twice(count) /* inline */)
  /* the end
       of main */
}

int twice(int x)  // doubles
{
  return 2 * x  // the answer
  // after the return
}
// end of the script
/* the very end */
"""


def translated(tmp_path: Path, text: str, name: str = "project") -> tuple[str, list[int]]:
    """The module ``text`` becomes (checked: no diagnostics, compiles, libcst, PEP 8) and, per
    Python line, its script line (from the package's source map)."""
    src = tmp_path / f"{name}.tms"
    src.write_text(text)
    sink = DiagnosticSink()
    out = transpile(src, sink)
    assert out is not None and not list(sink), [d.header() for d in sink]
    py = out.files[f"{out.package}/{name}.py"]
    compile(py, "generated", "exec")
    libcst.parse_module(py)
    path = tmp_path / "generated.py"
    path.write_text(py)
    assert pycodestyle.StyleGuide(max_line_length=99, quiet=True).check_files([str(path)]).total_errors == 0
    runs = json.loads(out.files[f"{out.package}/_sourcemap.json"])["modules"][f"{name}.py"]["runs"]
    lines = py.splitlines()
    line_map = []
    for i in range(1, len(lines) + 1):
        line_map.append(next(t for start, t in reversed(runs) if start <= i))
    return py, line_map


def at(py: str, line_map: list[int], text: str) -> int:
    """The script line of the one generated line that is ``text`` (indentation included)."""
    found = [i for i, ln in enumerate(py.splitlines()) if ln == text]
    assert len(found) == 1, (text, py)
    return line_map[found[0]]


def test_comments_are_carried_where_a_reader_expects_them(tmp_path: Path) -> None:
    py, _ = translated(tmp_path, SCRIPT)
    expected = """\
# The counting project
# Written for the tests:
#   two lines of block comment
def define():  # the globals
    \"\"\"The define section: run() sets the globals anew each time the project runs.\"\"\"
    global count, limit
    count = 0  # how many
    # the limit
    limit = 3


# the entry point
def main():
    global count
    # count up
    while (count < limit):  # loop
        tm.tick()
        count = tm.to_int(tm.add(count, 1))  # one more
        if tm.eq(count, 2):  # two
            tm.Display("two")  # say it
        else:
            # not two
            tm.Display(tm.add("n ", count))
            # end if
    i = 0
    while (i < 2):  # twice
        tm.tick()
        tm.Display(tm.add("i ", i))
        i = tm.to_int(tm.add(i, 1))
    _switch1 = count  # which one
    # the three
    if tm.eq(_switch1, 3):  # three
        tm.Display("three")
        # done
    else:
        tm.Display("other")
    # end switch
    _first2 = True
    while _first2 or (count > 5):  # once  # until
        _first2 = False
        tm.tick()
        count = tm.to_int(tm.sub(count, 1))
    tm.Display(twice(count))  # inline
    # the end
    #     of main


def twice(x):  # doubles
    x = tm.to_int(x)
    return tm.to_int(tm.mul(2, x))  # the answer
    # after the return


# end of the script
# the very end


def run():
"""
    assert expected in py


def test_a_script_with_comments_runs_as_before(tmp_path: Path) -> None:
    src = tmp_path / "project.tms"
    src.write_text(SCRIPT)
    module = load_project(src, tmp_path / "out")
    context.use_robot("TM5-900")
    assert run_loaded(module) == (0, ["n 1", "two", "n 3", "i 0", "i 1", "three", "4"])


def test_each_comment_line_and_statement_keeps_its_script_line(tmp_path: Path) -> None:
    py, line_map = translated(tmp_path, SCRIPT)
    script = SCRIPT.splitlines()
    for text, needle in [("    count = 0  # how many", "int count = 0"), ("    limit = 3", "int limit = 3"),
                         ("            tm.Display(\"two\")  # say it", 'Display("two")'),
                         ("    tm.Display(twice(count))  # inline", "Display(twice(count)"),
                         ("    return tm.to_int(tm.mul(2, x))  # the answer", "return 2 * x")]:
        assert needle in script[at(py, line_map, text) - 1], text
    for text, needle in [("# Written for the tests:", "/* Written for the tests:"),
                         ("#   two lines of block comment", "two lines of block comment */"),
                         ("    # the end", "/* the end"), ("    #     of main", "of main */"),
                         ("    # after the return", "// after the return"), ("# the very end", "/* the very end */"),
                         ("            # not two", "// not two"), ("    # the three", "// the three")]:
        assert script[at(py, line_map, text) - 1].strip() == needle, text


def test_a_run_time_error_below_comments_names_its_own_line(tmp_path: Path) -> None:
    src = tmp_path / "demo.tms"
    src.write_text("main\n{\n  /* a comment\n     over\n     three lines */\n  int z = 0  // zero\n"
                   "  // what follows fails\n  Display(1 / z)  // here\n}\n")
    r = subprocess.run([sys.executable, "-m", "gpl2py", "run", str(src), "--robot", "TM5-900"],
                       capture_output=True, text=True, cwd=tmp_path, timeout=600)
    assert r.returncode == 1
    assert "demo.tms:8: error: division by zero" in r.stderr
    assert "Traceback" not in r.stderr


def test_comments_in_a_packet(tmp_path: Path) -> None:
    script = "// a packet\r\nint total = 0  // start\r\n/* add\r\n   two */\r\ntotal = total + 2\r\n// the end"
    p = translate_packet(script)
    assert not p.errors
    assert p.python == ("def script(v):\n    # a packet\n    v.total = 0  # start\n    # add\n    #   two\n"
                        "    v.total = tm.to_int(tm.add(v.total, 2))\n    # the end\n")
    assert p.lines == [0, 1, 2, 3, 4, 5, 6]
    context.use_robot("TM5-900")
    assert run_packet(script).total == 2


def test_a_trailing_block_comment_over_lines_keeps_one_line_per_line(tmp_path: Path) -> None:
    py, line_map = translated(tmp_path, "main\n{\n  int a = 1  /* first\n  second\n   third */\n"
                              "  Display(a)\n}\n")
    assert "    a = 1  # first\n    # second\n    # third\n    tm.Display(a)\n" in py
    assert [at(py, line_map, t) for t in ("    a = 1  # first", "    # second", "    # third")] == [3, 4, 5]


def test_a_block_of_comments_only_is_a_block(tmp_path: Path) -> None:
    py, _ = translated(tmp_path, "main\n{\n  if (true) {\n    // nothing yet\n  }\n"
                       "  while (false) { /* later */ }\n}\nvoid later()\n{\n  // to do\n}\n")
    assert "    if True:\n        # nothing yet\n        pass\n" in py
    assert "    while False:  # later\n        tm.tick()\n" in py
    assert "def later():\n    # to do\n    pass\n" in py


def test_hostile_comment_text_stays_a_comment(tmp_path: Path) -> None:
    """What could end a line for Python or an editor is shown escaped, as in GPL's comments; a long
    comment is re-flowed or moved above its statement to keep PEP 8's line length."""
    long = " ".join(["word"] * 40)
    text = ("main\n{\n  int a = 1  // x\x0bimport os\x0c\u2028y = 2\x85z\n"
            f"  int b = 2  // {long}\n  // {long}\n"
            "  int c = 3  /* \x1c\x1d\x1e */\n  Display(a + b + c)\n}\n")
    py, _ = translated(tmp_path, text)
    assert "    a = 1  # x\\x0bimport os\\x0c\\u2028y = 2\\x85z\n" in py
    assert "import os" not in [ln.strip() for ln in py.splitlines()]
    assert all(len(ln) <= 99 for ln in py.splitlines())
    assert py.count("word") == 80
    module = load_project(tmp_path / "project.tms", tmp_path / "out")
    context.use_robot("TM5-900")
    assert run_loaded(module) == (0, ["6"])


def test_comments_of_heads_without_braces_and_else_parts(tmp_path: Path) -> None:
    """A comment after ``if (...)``, ``while (...)``, ``for (...)`` whose statement is on the next
    line ends the ``if``/``while`` line; an ``else if``'s ends its ``elif`` line; comments between a
    block's ``}`` and its ``else`` and after a one-line block stay in order."""
    text = """main
{
  int a = 1
  if (a > 0)  // positive
    a = 2     // now two
  else        // not positive
    a = 3
  if (a == 1) {
    a = 4
  }
  // otherwise
  else if (a == 2)  // two
    a = 5
  else { a = 6 }  // six
  int n = 0
  while (n < 2)  // twice
    n++
  for (int i = 0; i < 2; i++)  // two more
    n++
  Display("a=" + a + // the value
          " n=" + n) // and the count
}
"""
    py, line_map = translated(tmp_path, text)
    assert """    if (a > 0):  # positive
        a = 2  # now two
    else:
        # not positive
        a = 3
    if tm.eq(a, 1):
        a = 4
    # otherwise
    elif tm.eq(a, 2):  # two
        a = 5
    else:
        a = 6
        # six
    n = 0
    while (n < 2):  # twice
        tm.tick()
        n = tm.to_int(tm.add(n, 1))
    i = 0
    while (i < 2):  # two more
""" in py
    assert '    tm.Display(tm.add(tm.add(tm.add("a=", a), " n="), n))  # the value  # and the count\n' in py
    assert at(py, line_map, "    # otherwise") == 11 and at(py, line_map, "    elif tm.eq(a, 2):  # two") == 12
    module = load_project(tmp_path / "project.tms", tmp_path / "out")
    context.use_robot("TM5-900")
    assert run_loaded(module) == (0, ["a=5 n=4"])


def test_comments_of_a_device_a_deferred_argument_and_an_empty_define(tmp_path: Path) -> None:
    """A device declaration's comment ends its ``with`` line; a statement whose deferred argument
    puts a ``def`` above it keeps its comment on its own line, not the ``def``'s; a ``define``
    section of comments only keeps them."""
    py, line_map = translated(tmp_path, """define
{
  // nothing declared yet
}
main
{
  int st = 0
  // the server
  Socket s = "127.0.0.1", 5890  // not opened here
  bool ok = WaitFor((st = ThreadState(0)) == 0, 10)  // waits
  Display("done")
}
""")
    assert "\n# nothing declared yet\n\n\ndef main():\n" in py
    assert ('    # the server\n    with tm.Socket("s", "127.0.0.1", 5890):  # not opened here\n\n'
            '        def _deferred1():\n') in py
    assert "        ok = tm.to_bool(tm.WaitFor(_deferred1, 10))  # waits\n" in py
    assert at(py, line_map, "        ok = tm.to_bool(tm.WaitFor(_deferred1, 10))  # waits") == 10
    module = load_project(tmp_path / "project.tms", tmp_path / "out")
    context.use_robot("TM5-900")
    assert run_loaded(module) == (0, ["done"])
