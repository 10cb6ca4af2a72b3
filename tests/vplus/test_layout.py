"""Nothing of V+ is loaded on the GPL path (docs/design/frontends.md): checking and translating a
GPL project imports neither the V+ front end nor the V+ runtime layer, and the one registry of
diagnostics still lists the V+ codes when asked for all of them."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

_PROBE = """
import sys
from gpl2py.cli import main
status = main(["check", sys.argv[1], "--quiet"])
status2 = main(["translate", sys.argv[1], "-o", sys.argv[2], "--quiet"])
loaded = sorted(m for m in sys.modules if m.startswith(("gpl2py.vplus", "gplrt.vplus")))
print(status, status2, loaded)
"""


def test_a_gpl_check_and_translation_import_nothing_of_v_plus(tmp_path: Path) -> None:
    src = tmp_path / "Main.gpl"
    src.write_text('Module Main\n    Public Sub Main()\n        Console.WriteLine("hi")\n    End Sub\nEnd Module\n')
    r = subprocess.run([sys.executable, "-c", _PROBE, str(src), str(tmp_path / "out")],
                       capture_output=True, text=True, timeout=120)
    assert r.stdout.strip() == "0 0 []", r.stdout + r.stderr


def test_the_registry_lists_the_v_plus_messages() -> None:
    from gpl2py import messages

    codes = {m.code for m in messages.all_messages()}
    assert {"GPL4001", "GPL4100", "GPL4120", "GPL4302", "GPL4700"} <= codes
    assert messages.message("GPL4123").severity_name == "warning"


_V_PROBE = """
import sys
from gpl2py.cli import main
status = main(["check", sys.argv[1], "--quiet"])
status2 = main(["translate", sys.argv[1], "-o", sys.argv[2], "--quiet"])
loaded = sorted(m for m in sys.modules if m.startswith(("gplrt", "numpy", "pinocchio", "gpl2py.gpl.")))
print(status, status2, loaded)
"""


def test_a_v_plus_check_and_translation_import_neither_the_runtime_nor_the_gpl_front_end(tmp_path: Path) -> None:
    src = tmp_path / "main.v2"
    src.write_text('.PROGRAM main()\n    SET p = TRANS(1, 2, 3)\n    MOVE p\n    TYPE "hi"\n.END\n')
    r = subprocess.run([sys.executable, "-c", _V_PROBE, str(src), str(tmp_path / "out")],
                       capture_output=True, text=True, timeout=120)
    assert r.stdout.strip() == "0 0 []", r.stdout + r.stderr
