"""The TMscript front end through gpl2py's commands: diagnostics in the project's form, a
translated script project that runs with the output the manual shows, packets translated at run
time, and no traceback on input that is not TMscript."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from gpl2py.diagnostics import DiagnosticSink
from gpl2py.tmscript.pipeline import translate_packet
from gpl2py.transpile import transpile


def gpl2py(*args: str, cwd: Path | None = None) -> subprocess.CompletedProcess[str]:
    return subprocess.run([sys.executable, "-m", "gpl2py", *args], capture_output=True, text=True, cwd=cwd, timeout=120)


def test_check_reports_errors_in_the_project_form(tmp_path: Path) -> None:
    src = tmp_path / "bad.tms"
    src.write_text("main\n{\n  int i = 1\n  int i = 2\n  i = i +\n  Nope(3)\n}\n")
    r = gpl2py("check", str(src))
    assert r.returncode == 1
    assert "Traceback" not in r.stderr + r.stdout
    text = r.stdout + r.stderr
    assert f"{src}:4:7: error GPL5300: 'i' is already declared" in text
    assert f"{src}:5:10: error GPL5101: expected an expression, found the end of the line" in text
    assert f"{src}:6:3: error GPL5302: 'Nope' is not a function of TMscript or of this project" in text


# E17 and E12 of the spec's appendix (manual L1150-L1194, L994-L1043), with the output they show
PROJECT = """\
define
{
  int g_count = 2
}
main
{
  int a = Add(5, 6)
  Display("Add:" + a)
  Display("Div:" + 10 / 3 + " " + 10 / 3.0)
  string s = "Hi"
  for (int i = 0; i < g_count; i++)
  {
    s = s + i
  }
  Display(s)
  byte b = 255
  b = b + 1
  int big = 2147483647
  big = big + 1
  Display(b + " " + big + " " + (int)1.99 + " " + (byte)1000)
  switch (s)
  {
    case "Hi01"
      Display("matched")
      break
    default
      Display("no")
      break
  }
  Tally()
  Display("count " + g_count)
}
closestop
{
  Display("closed")
}
int Add(int x, int y)
{
  return x + y
}
void Tally()
{
  g_count++
}
"""


def test_translate_and_run_a_script_project(tmp_path: Path) -> None:
    src = tmp_path / "demo.tms"
    src.write_text(PROJECT)
    out = tmp_path / "out"
    r = gpl2py("translate", str(src), "-o", str(out))
    assert r.returncode == 0, r.stdout + r.stderr
    module = (out / "demo" / "demo.py").read_text()
    compile(module, "demo.py", "exec")
    run = subprocess.run([sys.executable, "-m", "demo"], capture_output=True, text=True, cwd=out, timeout=120,
                         env={**__import__("os").environ, "PYTHONPATH": str(Path(__file__).resolve().parents[2] / "runtime")})
    assert run.returncode == 0, run.stderr
    assert run.stdout.splitlines() == [
        "Add:11", "Div:3 3.3333333", "Hi01", "0 -2147483648 1 232", "matched", "count 3", "closed"]


def test_language_option_and_recognition(tmp_path: Path) -> None:
    src = tmp_path / "script.txt"
    src.write_text("main\n{\n  Display(1)\n}\n")
    assert gpl2py("check", "--language", "tmscript", str(src)).returncode == 0
    sink = DiagnosticSink()
    tms = tmp_path / "s.tms"
    tms.write_text("main\n{\n  Display(1)\n}\n")
    assert transpile(tms, sink) is not None and not sink.has_errors()


@pytest.mark.parametrize("text", [
    "", "\x00\x01", "{{{{", ")))", "int", "int[", "(int)", "a = = b", "for(;;", "switch (x) { case", "\\",
    "/* never closed", '"never closed', "x" * 5000, "(" * 3000, "-" * 3000 + "1", "do {", "}", "0x", "1e",
    "int a = {1,,2}", "x = " + "1+" * 5000 + "1", "x = " + "a[" * 400 + "0" + "]" * 400, "if (1) else", "Robot[0].Joint = 1", "case 1", "main { }", "byte b = -100", "int é = 1", "達明 = 2",
])
def test_any_packet_text_gives_diagnostics_never_an_exception(text: str) -> None:
    p = translate_packet(text)
    assert not any(d.message.startswith("internal error") for d in p.errors), [d.message for d in p.errors]
    if not p.errors:
        compile(p.python, "<packet>", "exec")


def test_a_run_time_error_names_the_script_line_never_a_traceback(tmp_path: Path) -> None:
    src = tmp_path / "demo.tms"
    src.write_text('main\n{\n  PTP("JPP",0,0,90,0,90,0,50,200,0,false)\n  QueueTag(1, 1)\n  Display("J " + Robot[0].Joint)\n'
                   '  int z = 0\n  Display(1 / z)\n}\nerrorstop\n{\n  Display("errorstop ran")\n}\n')
    r = gpl2py("run", str(src), "--robot", "TM5-900", cwd=tmp_path)
    assert r.returncode == 1
    assert r.stdout.splitlines()[:2] == ["J {0,0,90,0,90,0}", "errorstop ran"]
    assert "demo.tms:7: error: division by zero" in r.stderr
    assert "Traceback" not in r.stderr
