"""Speed of GPL file I/O on the sandboxed controller disks vs plain Python file I/O.

Run::

    python benchmarks/file_speed.py [--n 2000] [--runs 7]

A file-heavy GPL workload, in five kernels a cell program really has (a log appended one line per
event, a location table read at every cycle, files written, copied, listed and deleted, an NVRAM
record log, an XML configuration saved and loaded), is transpiled here with the real pipeline and
run against a temporary flash root.  The same work written with Python's own ``open``/``shutil``/
``os`` on a plain temporary folder runs in turns with it, both from the same files at each turn,
with the collector on; printed are the medians of ``--runs`` runs of each with their spread, and
the median of the per-turn ratios ``transpiled / python``.  Both sides must produce the same result
(checked).  The reference workload R (``_reference``) runs in every turn too, and each median is
printed once more in R (the time divided by R of its turn): the figures to compare between
machines.

The ratio is what the sandbox costs on top of the host's file system: every GPL file operation
walks the path from the root's descriptor without following links and checks the file before and
after opening it (``gplrt.io.sandbox``).  To compare two versions of the runtime, run the script
under each (``PYTHONPATH=<other checkout>/runtime``) and compare the ratios.
"""

from __future__ import annotations

import argparse
import importlib
import os
import shutil
import sys
import tempfile
import xml.dom.minidom as minidom
from collections.abc import Callable
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
sys.path.insert(0, str(Path(__file__).resolve().parent))

from _reference import HOW_TO_COMPARE, Reference  # noqa: E402
from _sidebyside import Pair, Samples, collector, timed  # noqa: E402

from gpl2py.diagnostics import DiagnosticSink  # noqa: E402
from gpl2py.transpile import transpile, write_package  # noqa: E402

TABLE_LINES = 20

GPL_KERNELS = """Module FileKernels
    ' 1. an event log: open for append, one line, close - per event
    Public Function LogLines(ByVal n As Integer) As Integer
        Dim i As Integer
        Dim w As StreamWriter
        For i = 1 To n
            w = New StreamWriter("/flash/bench/log.txt", True)
            w.WriteLine("event " & CStr(i) & " part ok")
            w.Close()
        Next
        Return File.Length("/flash/bench/log.txt")
    End Function

    ' 2. a location table read line by line at every cycle
    Public Function ReadTable(ByVal n As Integer) As Integer
        Dim i, total As Integer
        Dim r As StreamReader
        For i = 1 To n
            r = New StreamReader("/flash/bench/table.txt")
            While r.Peek() >= 0
                total = total + Len(r.ReadLine())
            End While
            r.Close()
        Next
        Return total
    End Function

    ' 3. result files written, backed up, listed and the backup deleted
    Public Function FileChurn(ByVal n As Integer) As Integer
        Dim i, total As Integer
        Dim name As String
        Dim w As StreamWriter
        Dim names() As String
        For i = 1 To n
            name = "/flash/bench/tmp/r" & CStr(i Mod 10)
            w = New StreamWriter(name)
            w.WriteLine("result " & CStr(i))
            w.Close()
            File.Copy(name, name & ".bak", True)
            names = File.GetFiles("/flash/bench/tmp")
            total = total + names.GetUpperBound(0) + 1
            File.DeleteFile(name & ".bak")
        Next
        Return total
    End Function

    ' 4. an NVRAM record log (AutoFlush: one atomic record per WriteLine)
    Public Function NvramLog(ByVal n As Integer) As Integer
        Dim i As Integer
        Dim w As New StreamWriter("/NVRAM/file1 -size 2048 -wrap", True)
        For i = 1 To n
            w.WriteLine("cycle " & CStr(i))
        Next
        w.Close()
        Return File.Length("/NVRAM/file1")
    End Function

    ' 5. an XML configuration saved and read back
    Public Function XmlRoundTrip(ByVal n As Integer) As Integer
        Dim i, total As Integer
        Dim doc, back As XmlDoc
        For i = 1 To n
            doc = New XmlDoc("config")
            doc.DocumentElement.AddAttribute("cycle", CStr(i))
            doc.SaveFile("/flash/bench/config.xml")
            back = XmlDoc.LoadFile("/flash/bench/config.xml")
            total = total + CInt(back.DocumentElement.GetAttribute("cycle"))
        Next
        Return total
    End Function
End Module
"""


# -- the same work with Python's own file functions, on a plain folder --------------------------


class PlainFiles:
    def __init__(self, root: Path) -> None:
        self.root = root

    def log_lines(self, n: int) -> int:
        path = self.root / "log.txt"
        for i in range(1, n + 1):
            with open(path, "ab") as f:
                f.write(f"event {i} part ok\r\n".encode("latin-1"))
        return os.stat(path).st_size

    def read_table(self, n: int) -> int:
        total = 0
        for _ in range(n):
            with open(self.root / "table.txt", "rb") as f:
                total += sum(len(line.rstrip(b"\r\n")) for line in f)
        return total

    def file_churn(self, n: int) -> int:
        total = 0
        folder = self.root / "tmp"
        for i in range(1, n + 1):
            name = folder / f"r{i % 10}"
            with open(name, "wb") as f:
                f.write(f"result {i}\r\n".encode("latin-1"))
            shutil.copyfile(name, f"{name}.bak")
            total += len(os.listdir(folder))
            os.unlink(f"{name}.bak")
        return total

    def nvram_log(self, n: int) -> int:
        records: list[bytes] = []
        path = self.root / "file1"
        for i in range(1, n + 1):
            records.append(f"cycle {i}\r\n".encode("latin-1"))
            while 1 + sum(len(r) + 1 for r in records) > 2048:
                records.pop(0)
            temp = self.root / ".file1.new"
            with open(temp, "wb") as f:
                f.write(b"".join(bytes([len(r)]) + r for r in records))
            os.replace(temp, path)
        return sum(len(r) for r in records)

    def xml_round_trip(self, n: int) -> int:
        total = 0
        path = self.root / "config.xml"
        for i in range(1, n + 1):
            doc = minidom.getDOMImplementation().createDocument(None, "config", None)
            doc.documentElement.setAttribute("cycle", str(i))
            with open(path, "wb") as f:
                f.write(doc.toxml().encode("utf-8"))
            with open(path, "rb") as f:
                back = minidom.parseString(f.read())
            total += int(back.documentElement.getAttribute("cycle"))
        return total


def table_text() -> bytes:
    return b"".join(b"Station%02d, %d.5, %d.25, 100, 0, 180, 0\r\n" % (i, i * 10, i * 20) for i in range(TABLE_LINES))


def build(tmp: Path):  # type: ignore[no-untyped-def]
    proj = tmp / "FileKernels"
    proj.mkdir()
    (proj / "FileKernels.gpl").write_text(GPL_KERNELS)
    (proj / "Project.gpr").write_text(
        'ProjectBegin\nProjectName="Bench Files"\nProjectSource="FileKernels.gpl"\nProjectEnd\n')
    sink = DiagnosticSink()
    out = transpile(str(proj), sink)
    if out is None:
        raise SystemExit("\n".join(d.render() for d in sink.sorted()))
    write_package(out, tmp / "out", sink)
    sys.path.insert(0, str(tmp / "out"))
    return importlib.import_module(f"{out.package}.file_kernels")


def fresh(flash: Path, plain: Path) -> None:
    """Both sides start each run from the same files."""
    for folder in (flash / "flash" / "bench", flash / "NVRAM", plain):
        shutil.rmtree(folder, ignore_errors=True)
    for folder in (flash / "flash" / "bench" / "tmp", flash / "NVRAM", plain / "tmp"):
        folder.mkdir(parents=True)
    (flash / "flash" / "bench" / "table.txt").write_bytes(table_text())
    (plain / "table.txt").write_bytes(table_text())


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=2000)
    ap.add_argument("--runs", "--repeat", type=int, default=7, help="samples per side (default 7)")
    args = ap.parse_args()
    from gplrt.io.flashroot import set_flash_root

    with tempfile.TemporaryDirectory() as tmp:
        kernels = build(Path(tmp))
        flash, plain_root = Path(tmp) / "disks", Path(tmp) / "plain"
        set_flash_root(flash)
        plain = PlainFiles(plain_root)
        cases = [
            ("event log, open/append/close", kernels.LogLines, plain.log_lines),
            ("table read line by line", kernels.ReadTable, plain.read_table),
            ("write, copy, list, delete", kernels.FileChurn, plain.file_churn),
            ("NVRAM record log", kernels.NvramLog, plain.nvram_log),
            ("XML save and load", kernels.XmlRoundTrip, plain.xml_round_trip),
        ]
        ref = Reference()
        print(f"{'kernel':30} {'transpiled (median, spread)':>28} {'python (median, spread)':>28}  ratio (spread)")
        pairs: list[Pair] = []
        for label, gpl, py in cases:
            pair = turns(gpl, py, args.n, args.runs, lambda: fresh(flash, plain_root), ref)
            pairs.append(pair)
            print(f"{label:30} {pair.a.text()} {pair.b.text()}  {pair.ratio_text()}")
            print(f"{'  in R':30} {pair.a_in_r.text(1, 'R', 3)} {pair.b_in_r.text(1, 'R', 3)}")
        gpl_ms, py_ms = (sum(getattr(p, s).median for p in pairs) * 1e3 for s in "ab")
        gpl_r, py_r = (sum(getattr(p, s).median for p in pairs) for s in ("a_in_r", "b_in_r"))
        print(f"{'all five (sum of medians)':30} {gpl_ms:9.1f} ms {py_ms:9.1f} ms  {gpl_ms / py_ms:.2f}x   "
              f"in R: {gpl_r:.3f} R, {py_r:.3f} R")
        print(ref.line())
        print(HOW_TO_COMPARE)
    return 0


def turns(gpl: Callable[[int], object], py: Callable[[int], object], n: int, runs: int,
          reset: Callable[[], None], ref: Reference) -> Pair:
    """``runs`` turns of (reset, GPL side, reset, Python side, R) after an untimed one, with the
    collector on; both sides' results are checked equal at every turn."""
    ta: list[float] = []
    tb: list[float] = []
    with collector(True):
        for turn in range(runs + 1):
            out: list[object] = []
            reset()
            a = timed(lambda: out.append(gpl(n)))
            reset()
            b = timed(lambda: out.append(py(n)))
            assert out[0] == out[1], out
            ref.run(record=turn > 0, match=a + b)
            if turn:
                ta.append(a)
                tb.append(b)
    return Pair(Samples(ta), Samples(tb), Samples(ref.wall[-runs:]))


if __name__ == "__main__":
    raise SystemExit(main())
