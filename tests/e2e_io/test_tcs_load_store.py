"""TCS's loadFile/storeFile commands round-trip a station file the real TCS wrote.

``docs/Tcs-taught-stations-2022.gpo`` in the corpus is the ``Tcs.gpo`` TCS generated on a working
PF400 cell.  The corpus's TCS 3.0C1 with the PARobot plug-in is copied unchanged, with that file
as its ``Tcs.gpo`` (data the user changes, not a ``.gpl`` line), served on a simulated PF400 (the
fixed port 10100 in a network namespace of its own, ``gpltest.private_network``), and asked to
``loadFile`` it and ``storeFile`` what it read: the file written must be the real TCS's, byte for
byte, but for the date on its second line.  So the whole GpoFile reader and writer
(``Class_gpofile.gpl``) behaves as on the controller.

It needs two things the controller does (docs/design/real-code.md): a class's ``Shared Sub Init``
runs at start-up (GpoFile's type tables), and ``CInt``/``CDbl`` of text with trailing characters
take the number it starts with -- ``CInt("20)")`` for the bound of ``tcs_sta_flags_1(20)`` split at
its parenthesis (``Class_gpofile.gpl:188-190``) and ``CDbl("180)")`` for the last argument of
``.XYZ(...,180)``.  Without either, ``loadFile`` fails (-519, then -717).
"""

from __future__ import annotations

import socket
from pathlib import Path
from typing import Any

from gpltest import copy_project, corpus_dir, private_network
from gpl2py.notebook import Cell

ROBOT_PORT = 10100  # Startup.gpl: Robot1Port
PROJECT_FOLDER = "flash/projects/Tcp_cmd_server_pa"  # ProjectName of the PARobot Project.gpr


def _lines(data: bytes) -> list[bytes]:
    return data.split(b"\r\n")


def test_load_file_and_store_file_round_trip_the_real_tcs_file(tmp_path: Path, request: Any) -> None:
    corpus = corpus_dir()
    taught = (corpus / "docs" / "Tcs-taught-stations-2022.gpo").read_bytes()
    if not private_network(request):
        return  # ran, and passed, in a network namespace of its own
    project = copy_project(corpus / "tcs-3.0C1-pa", tmp_path / "tcs")
    (project / "Tcs.gpo").chmod(0o644)
    (project / "Tcs.gpo").write_bytes(taught)
    flash = tmp_path / "disks"
    cell = Cell.load(project, robot="PF400SX", clock="fast", echo=False, flash=flash,
                     cache_dir=tmp_path / "cache")
    replies = []
    with cell.serve(ports=[ROBOT_PORT], timeout=60.0):
        with socket.create_connection(("127.0.0.1", ROBOT_PORT), timeout=30) as s:
            f = s.makefile("rwb")
            for command in ("loadFile", "locXyz 1", "storeFile Out.gpo"):
                f.write(command.encode() + b"\n")
                f.flush()
                replies.append(f.readline().decode().strip())
    # station 1 is the Cartesian location of the file's first XYZ, printed with three decimals
    assert replies == ["0", "0 0 1 -493.564 -82.63 1157.13 -83.037 90 180", "0"], replies
    written = _lines((flash / PROJECT_FOLDER / "Out.gpo").read_bytes())
    expected = _lines(taught)
    assert written[1].startswith(b"'Updated: ") and expected[1].startswith(b"'Updated: ")
    assert written[:1] + written[2:] == expected[:1] + expected[2:]
