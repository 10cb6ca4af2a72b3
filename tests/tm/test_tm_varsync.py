"""Variables found by a name given at run time (issue 22, item 3): ``GetVarValue`` (L6650) in script
projects as in Listen-node packets, and ``VarSync`` (L7626), which sends variables to the robot's
simulated TMmanager (``Robot.manager``, ``gplrt.tm.manager``): what it received is read back
here as a notebook would; a manager switched off answers -1, bad parameters -9, a manager that
fails is retried every interval of controller time."""

from __future__ import annotations

from pathlib import Path

import pytest
from tmpacket import run_packet, run_project

from gplrt.tm import context


def run_source(source: str, tmp_path: Path) -> tuple[int, list[str], object]:
    """Translate and run a script project: (status, Display lines, the robot)."""
    src = tmp_path / "proj.tms"
    src.write_text(source)
    status, lines = run_project(src, tmp_path / "out")
    return status, lines, context.robot()


def test_get_var_value_in_a_script_project_l6650(tmp_path: Path, capsys) -> None:  # type: ignore[no-untyped-def]
    status, lines, _ = run_source("""define
{
    string var_s1 = "Hello World"
    string var_s2 = "Hi TM Robot"
}
main
{
    string var_h = "var_s1"
    string var_t = "var_s"
    string var_re = GetVarValue("var_h")
    Display(var_re)
    var_re = GetVarValue(var_h)
    Display(var_re)
    var_re = GetVarValue(var_t + "2")
    Display(var_re)
    int[] n = {1, 2, 3}
    int[] m = GetVarValue("n")
    Display("" + m[2])
    var_re = GetVarValue(var_t)
    Display("not reached")
}
""", tmp_path)
    assert lines == ["var_s1", "Hello World", "Hi TM Robot", "3"]
    assert status == 1  # var_s does not exist: an error that stops the project
    assert "error: GetVarValue: the variable 'var_s' does not exist" in capsys.readouterr().err


SYNC = """define
{
    string var_s = "ABC"
    string var_s1 = "var_s"
    string[] var_ss = {"ABC", "var_s", "var_s1"}
    int ABC = 7
}
main
{
    int t0 = GetNowStamp()
    Display("" + VarSync(1, 1000, "var_s"))
    Display("" + VarSync(2, 2000, var_s))
    Display("" + VarSync(3, 2000, var_ss))
    Display("" + VarSync(4, 2000, "var_ss", "var_s1", "ABC", "no_such_var"))
    Display("" + VarSync("var_s1"))
    float local_f = 1.5
    Display("" + VarSync(1, "local_f"))
    Display("" + VarSync(1, 1000, "no_such_var"))
    Display("" + VarSync(1, 1000))
    Display("" + VarSync(1, 1000, 5))
    Display("" + GetNowStamp(t0))
}
"""


def test_var_sync_sends_the_named_variables_to_the_tmmanager_l7626(tmp_path: Path) -> None:
    status, lines, robot = run_source(SYNC, tmp_path)
    assert status == 0
    assert lines[:9] == ["1", "1", "1", "1", "1", "1", "0", "-9", "-9"]
    sent = [sync.values for sync in robot.manager.received]  # type: ignore[attr-defined]
    assert sent == [
        {"var_s": "ABC"},
        {"ABC": 7},  # by the value of var_s (L7670)
        {"ABC": 7, "var_s": "ABC", "var_s1": "var_s"},  # the names in var_ss
        {"var_ss": ["ABC", "var_s", "var_s1"], "var_s1": "var_s", "ABC": 7},  # no_such_var is not sent
        {"var_s1": "var_s"},
        {"local_f": 1.5},  # a main's local, by name
    ]
    assert int(lines[9]) < 100  # every send took: no retry waited


def test_var_sync_disabled_retried_and_failing(tmp_path: Path) -> None:
    robot = context.use_robot("TM5-900")
    robot.manager.enabled = False
    v = run_packet('string var_s = "ABC"\r\nint r = VarSync(1, 1000, "var_s")')
    assert v.r == -1 and robot.manager.received == []  # the TMmanager function is not enabled

    robot.manager.enabled = True
    robot.manager.fail_next = 2
    v = run_packet('string var_a = "x"\r\nint t0 = GetNowStamp()\r\nint r = VarSync(3, 500, "var_a")\r\n'
                   "int dt = GetNowStamp(t0)")
    assert v.r == 3  # the third send went through
    assert v.dt >= 1000  # two waits of 500 ms of controller time between the sends
    assert [s.values for s in robot.manager.received] == [{"var_a": "x"}]

    robot.manager.fail_next = 5
    v = run_packet('string var_b = "y"\r\nint r = VarSync(2, -1, "var_b")')  # (a negative interval: 1000 ms)
    assert v.r == 0 and robot.manager.fail_next == 3  # two tries, both failed: nothing sent
    assert robot.manager.variables == {"var_a": "x"}


def test_get_var_value_and_var_sync_in_listen_node_packets() -> None:
    robot = context.use_robot("TM5-900")
    v = run_packet('int var_i = 5\r\nstring name = "var_i"\r\nint got = GetVarValue(name)\r\n'
                   'int r = VarSync(name, "got")')
    assert v.got == 5 and v.r == 1
    assert robot.manager.variables == {"var_i": 5, "got": 5}
    with pytest.raises(Exception, match="does not exist"):
        run_packet('int x = GetVarValue("nothing")')



def test_the_variables_passed_by_name_keep_pep8_lines_and_take_python_keywords() -> None:
    from gpl2py.tmscript.pipeline import translate_packet

    names = [f"var_long_name_number_{i}" for i in range(12)]
    script = "\r\n".join(f"int {n} = {i}" for i, n in enumerate(names)) + "\r\nint got = GetVarValue(\"var_long_name_number_7\")"
    packet = translate_packet(script)
    assert not packet.errors
    assert max(len(line) for line in packet.python.splitlines()) <= 99
    v = run_packet(script + '\r\nint pass = 3\r\nint k = GetVarValue("pass")')
    assert (v.got, v.k) == (7, 3)
