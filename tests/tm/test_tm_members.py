"""Members of TMscript's built-in classes and parameterized objects (``tcp1.MCF``,
``Robot[0].CameraLight``): a member the manual documents and the runtime does not implement is
GPL5314 at the member's name, a member the manual does not document is GPL5317, both at compile
time; what only the run can tell (``Base[name]`` naming the read-only ``RobotBase``) is the
script's error or the manual's "invalid operation", never a Python AttributeError.

The front end's table of implemented members is generated from the runtime's classes
(``gpl2py/tmscript/semantics/members_data.py``); these tests keep the two, and the manual's
tables (``library.DOCUMENTED_MEMBERS``), in step."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest
from tmpacket import run_project

import gplrt.tm as tm
from gpl2py.diagnostics import DiagnosticSink
from gpl2py.tmscript.pipeline import translate_packet
from gpl2py.tmscript.semantics import members_gen
from gpl2py.tmscript.semantics.library import DOCUMENTED_MEMBERS, DOCUMENTED_METHODS
from gpl2py.tmscript.semantics.members_data import MEMBERS
from gpl2py.transpile import transpile
from gplrt.tm import context
from gplrt.tm.values import TMError

# E82 (manual L15486-L15511) in a main: MOI and MCF are the manual's, not simulated
E82 = """\
main
{
TTCP tcp1 = {0,0,90,0,0,0},3
TTCP tcp9 = "D",{0,0,90,0,0,0},2,{2,0.5,0.5},{0,0,-80,0,0,0}
float mass = tcp1.Mass
float[] mcf = tcp1.MCF
float[] moi9 = tcp9.MOI
tcp1.Mass = 2.4
tcp1.MOI = {0, 0, 0, 1, 2}
tcp1.MCF = {0, -20, 0, 0, 0, 0}
}
"""


def errors(source: str, tmp_path: Path) -> list[str]:
    """``file:line:col: error GPLnnnn: message`` of a script project, without the file."""
    src = tmp_path / "members.tms"
    src.write_text(source)
    sink = DiagnosticSink()
    transpile(src, sink)
    return [d.header().split(":", 1)[1] for d in sink if d.severity.name == "ERROR"]


def packet_errors(script: str) -> list[str]:
    return [d.header().split(":", 1)[1] for d in translate_packet(script).errors]


def test_e82_moi_and_mcf_are_not_supported_at_their_names(tmp_path: Path) -> None:
    assert errors(E82, tmp_path) == [
        "6:20: error GPL5314: the member TTCP.MCF is not supported yet by gpl2py",
        "7:21: error GPL5314: the member TTCP.MOI is not supported yet by gpl2py",
        "9:6: error GPL5314: the member TTCP.MOI is not supported yet by gpl2py",
        "10:6: error GPL5314: the member TTCP.MCF is not supported yet by gpl2py",
    ]


def test_documented_members_not_simulated_read_and_written() -> None:
    assert packet_errors('float s = Robot[0].TCPSpeed3D\nRobot[0].CameraLight = 1\n'
                         'float[] f = Point["P1"].Flange\nbyte si = IO["Safety"].SI[0]') == [
        "1:20: error GPL5314: the member Robot[...].TCPSpeed3D is not supported yet by gpl2py",
        "2:10: error GPL5314: the member Robot[...].CameraLight is not supported yet by gpl2py",
        "3:25: error GPL5314: the member Point[...].Flange is not supported yet by gpl2py",
        "4:24: error GPL5314: the member IO[...].SI is not supported yet by gpl2py",
    ]


def test_undocumented_members_read_and_written() -> None:
    assert packet_errors('TPoint p = 1,2,3,4,5,6\nfloat[] f = p.Coord\np.Speed = 3\n'
                         'float[] j = Robot[0].Joints\nint i = 1\nint k = i.Value\nx.Value = 1') == [
        "2:15: error GPL5317: 'Coord' is not a member of TPoint",
        "3:3: error GPL5317: 'Speed' is not a member of TPoint",
        "4:22: error GPL5317: 'Joints' is not a member of Robot[...]",
        "6:11: error GPL5317: 'Value' is not a member of the int variable i",
        "7:3: error GPL5317: 'Value' is not a member of the string \"x\"",
    ]


def test_implemented_members_still_check_clean() -> None:
    assert packet_errors('TTCP t = 0,0,10,0,0,0,2\nt.Mass = 2.5\nfloat m = t.Mass\nTBase b = 0,0,0,0,0,0\n'
                         'string s = b.Type\nfloat[] j = Robot[0].Joint\nIO["ControlBox"].DO[0] = 1\n'
                         'float[] v = Point["p"].Value\nfloat[] vp = VPoint["job"].Value') == []


def test_writing_a_read_only_member_is_a_warning() -> None:
    """L14433: ``Robot[0].CoordRobot = {...}`` "Read only, invalid operation"."""
    p = translate_packet('Robot[0].Joint = {0, 0, 90, 0, 90, 0}\nTBase b = 0,0,0,0,0,0\nb.Type = "C"')
    assert not p.errors
    assert [d.header().split(":", 1)[1] for d in p.warnings if d.code == "GPL5318"] == [
        "1:10: warning GPL5318: Robot[...].Joint is read only: assigning it is an invalid operation and changes "
        "nothing",
        "3:3: warning GPL5318: TBase.Type is read only: assigning it is an invalid operation and changes nothing",
    ]


def gpl2py(*args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run([sys.executable, "-m", "gpl2py", *args], capture_output=True, text=True, timeout=120)


@pytest.mark.parametrize("command", ["check", "run"])
def test_check_and_run_stop_with_the_diagnostic(command: str, tmp_path: Path) -> None:
    src = tmp_path / "e82.tms"
    src.write_text(E82)
    r = gpl2py(command, str(src))
    text = r.stdout + r.stderr
    assert r.returncode != 0
    assert "Traceback" not in text and "AttributeError" not in text
    assert f"{src}:6:20: error GPL5314: the member TTCP.MCF is not supported yet by gpl2py" in text


def test_writing_a_read_only_base_or_tcp_by_name_is_an_invalid_operation(tmp_path: Path) -> None:
    """L14481, L14535: ``Base["RobotBase"].Value = ...`` and ``TCP["NOTOOL"].Value = ...`` are the
    manual's "Read only, invalid operation": the checks cannot know the name, the run ignores it."""
    src = tmp_path / "fixed.tms"
    src.write_text('main\n{\nstring b = "RobotBase"\nBase[b].Value = {0, 0, 90, 0, 90, 0}\n'
                   'TCP["NOTOOL"].Value = {0, -10, 0, 0, 0, 0}\nDisplay(Base[b].Value)\n'
                   'Display(TCP["NOTOOL"].Value)\n}\n')
    assert run_project(src, tmp_path / "out") == (0, ["{0,0,0,0,0,0}", "{0,0,0,0,0,0}"])


def test_a_member_the_run_cannot_find_is_the_scripts_error() -> None:
    """Python code (a notebook, the generated code of another name) reaching a member that is not
    there: a TMError a script's errorstop sees, never AttributeError."""
    context.use_robot("TM5-900")
    with pytest.raises(TMError, match="MOI"):
        tm.TCP["NOTOOL"].MOI  # noqa: B018
    t = tm.TTCP("t_members", 0, 0, 10, 0, 0, 0, 2)
    with pytest.raises(TMError, match="MCF"):
        tm.assign(t, "MCF", [0, 0, 0, 0, 0, 0])
    with pytest.raises(TMError, match="Foo"):
        t.Foo = 1
    tm.Robot[0].Joint = [1, 2, 3, 4, 5, 6]  # read only: an invalid operation, ignored (L14433)
    assert list(tm.Robot[0].Joint) != [1, 2, 3, 4, 5, 6]


# --- the tables stay in step ---------------------------------------------------------------------

def test_the_data_module_is_what_the_runtime_declares_now() -> None:
    assert members_gen.data_path().read_text(encoding="utf-8") == members_gen.generate(), \
        f"members_data.py is out of date with the runtime: run `{members_gen.REGENERATE}`"


def test_every_member_the_checker_accepts_is_on_the_runtime_class() -> None:
    for owner, members in MEMBERS.items():
        cls = members_gen.runtime_class(owner)
        for name, mode in members.items():
            assert hasattr(cls, name), f"{owner}.{name}"
            documented = DOCUMENTED_MEMBERS.get(owner, {}).get(name) or (
                "method" if name in DOCUMENTED_METHODS.get(owner, ()) else None)
            assert documented == mode, f"{owner}.{name}: the manual says {documented}, the runtime {mode}"


def test_every_documented_member_the_runtime_lacks_is_gpl5314() -> None:
    for owner, members in DOCUMENTED_MEMBERS.items():
        missing = [n for n in members if n not in MEMBERS.get(owner, {})]
        for name in missing:
            if owner in ("TPoint", "TBase", "TTCP"):
                script = f'{owner} o = 0,0,0,0,0,0\nDisplay(o.{name})'
            else:
                script = f'Display({owner}["x"].{name})'
            got = packet_errors(script)
            assert len(got) == 1 and "GPL5314" in got[0] and f".{name} " in got[0], (owner, name, got)


def test_the_fixed_base_and_tcp_have_their_classes_members() -> None:
    """``Base["RobotBase"]`` and ``TCP["NOTOOL"]`` are checked as a TBase and a TTCP."""
    from gplrt.tm.members import surface
    from gplrt.tm.teach import TCP, Base

    assert set(surface(type(Base["RobotBase"]))) == set(MEMBERS["Base"])
    assert set(surface(type(TCP["NOTOOL"]))) == set(MEMBERS["TCP"])
