"""The rest of the V+ library, one behaviour each: signals in groups, events, LOCALs, packing of
transformations, HERE a:b:x, DRIVE/DELAY/READY/DEPART, SPEED MONITOR, CPOFF, append and delete."""

from __future__ import annotations

from pathlib import Path

import pytest

from gplrt import vplus as vp
from gplrt.sim import Simulation
from gplrt.vplus.transforms import components

TOL = 1e-6


def test_signal_groups(sim: Simulation) -> None:
    vp.bits_set(1, 4, 0b1010)
    assert [vp.sig(i) for i in (1, 2, 3, 4)] == [0.0, -1.0, 0.0, -1.0]
    assert vp.bits(1, 4) == 10.0
    vp.signal(2001)  # a soft signal
    assert vp.sig(2001) == -1.0 and vp.sig(-2001) == 0.0
    vp.reset()
    assert vp.bits(1, 4) == 0.0
    assert vp.sig_ins(1) == -1.0 and vp.sig_ins(9999) == 0.0
    with pytest.raises(vp.VError):
        vp.signal(1001)  # an input cannot be set


def test_local_variables_are_shared_by_calls(sim: Simulation) -> None:
    @vp.program("counter")
    def counter() -> float:
        n = vp.local_store("counter")["n"]
        n.v = vp.add(n.v, 1) if n.defined else 1
        return n.v

    assert [counter(), counter(), counter()] == [1.0, 2.0, 3.0]
    assert not vp.G["n"].defined  # a LOCAL hides nothing global


def test_cas_and_events(sim: Simulation) -> None:
    flag = vp.G["flag"]
    flag.v = 0
    assert vp.cas(flag, 0, 5) == 0.0 and flag.v == 5.0
    assert vp.cas(flag, 0, 7) == 5.0 and flag.v == 5.0

    def main() -> None:
        vp.set_event(0)
        vp.type_(vp.get_event())
        vp.clear_event()
        vp.type_(vp.get_event(), " ", vp.wait_event(None, 0.05))

    assert sim.run_main(main) == []
    assert sim.console.output.splitlines() == ["1", "0 0"]


def test_transformation_packing_and_other_functions() -> None:
    t = vp.trans(1.5, -2, 3, 10, 20, 30)
    packed = vp.s_transb(t)
    assert len(packed) == 24
    assert components(vp.transb(packed)) == pytest.approx(components(t), abs=1e-5)
    assert vp.s_truncate("ab\0cd") == "ab"
    assert vp.outside(0, 5, 10) == 0.0 and vp.outside(0, 11, 10) == -1.0
    assert vp.max_(1, 5, 3) == 5.0 and vp.min_(1, 5, 3) == 1.0 and vp.cubrt(-27) == pytest.approx(-3.0)
    assert 0.0 <= vp.random() < 1.0
    assert vp.tps() == 62.5


def test_append_and_delete_a_file(tmp_path: Path) -> None:
    sim = Simulation(capture=True, flash_root=tmp_path)

    def main() -> None:
        lun, line = vp.Cell("lun"), vp.Cell("$line")
        vp.attach(lun, 4, "DISK")
        vp.fopenw(lun, "log.txt")
        vp.write(lun, "one")
        vp.fclose(lun)
        vp.fopena(lun, "log.txt")
        vp.write(lun, "two")
        vp.fclose(lun)
        vp.fopenr(lun, "log.txt")
        vp.read(lun, line)
        vp.read(lun, line)
        vp.type_(line.v)
        vp.fclose(lun)
        vp.fdelete(lun, "log.txt")
        vp.fopenr(lun, "log.txt")
        vp.type_(vp.s_error(vp.iostat(lun)))

    with sim:
        assert sim.run_main(main) == []
    assert sim.console.output.splitlines() == ["two", "*Nonexistent file*"]
    sim.close()


def test_here_compound_drive_delay_ready_depart_and_monitor_speed() -> None:
    sim = Simulation(robot="VIPER-S650", capture=True)
    got: dict[str, object] = {}

    def main() -> None:
        vp.move(vp.p_ppoint(10, -20, 40, 5, 50, -10))
        vp.break_()
        frame = vp.trans(100, 50, 0, 30)
        x = vp.Cell("x")
        vp.here_into(x, frame)  # HERE frame:x
        got["here"], got["frame:x"] = vp.here(), vp.compose(frame, x.v)
        vp.drive(1, 15, 50)
        vp.break_()
        got["drive"] = vp.p_phere()
        t0 = sim.now()
        vp.delay(0.5)
        vp.break_()
        got["delay"] = sim.now() - t0
        vp.depart(20)
        vp.break_()
        got["depart"] = vp.here()
        vp.speed(50, unit="MONITOR")
        got["monitor"] = vp.speed_value(1)
        vp.cp(False, always=True)
        vp.ready()
        vp.break_()
        got["ready"] = vp.p_phere()

    with sim:
        assert sim.run_main(main) == [], sim.console.log_text
    sim.close()
    assert components(got["frame:x"]) == pytest.approx(components(got["here"]), abs=TOL)
    assert components(got["drive"])[0] == pytest.approx(25.0, abs=TOL)
    assert got["delay"] == pytest.approx(0.5, abs=1e-6)
    assert got["monitor"] == 50.0
    assert components(got["ready"]) == pytest.approx((0, 0, 0, 0, 0, 0), abs=TOL)


def test_functions_that_share_an_instruction_name() -> None:
    sim = Simulation(robot="VIPER-S650", capture=True)
    got: list[float] = []

    def main() -> None:
        vp.speed(30, always=True)
        vp.speed(40, unit="MONITOR")
        vp.accel(80, 60)
        vp.duration(1.5, always=True)
        vp.move(vp.p_ppoint(10, -20, 40, 5, 50, -10))
        vp.break_()
        got.extend([vp.speed_value(1), vp.speed_value(2), vp.accel_value(1), vp.accel_value(2),
                    vp.duration_value(), vp.select_value("ROBOT"), vp.config_value()])

    with sim:
        assert sim.run_main(main) == [], sim.console.log_text
    sim.close()
    assert got[:6] == [40.0, 30.0, 80.0, 60.0, 1.5, 1.0]
    assert got[6] > 0  # some configuration bits


def test_fopend_reads_directory_records(tmp_path: Path) -> None:
    """FOPEND then READ: one DOS-layout record per entry (L7936-7993), -504 after the last."""
    (tmp_path / "flash" / "sub").mkdir(parents=True)
    (tmp_path / "flash" / "data.tst").write_bytes(b"x" * 1000)
    (tmp_path / "flash" / "a.v2").write_bytes(b"")
    sim = Simulation(capture=True, flash_root=tmp_path)

    def main() -> None:
        lun, rec = vp.Cell("lun"), vp.Cell("$rec")
        vp.attach(lun, 4, "DISK")
        vp.fopend(lun, "D:\\*.*")
        vp.read(lun, rec)
        while vp.iostat(lun) > 0:
            vp.type_("[", rec.v, "]")
            vp.read(lun, rec)
        vp.type_(vp.iostat(lun))

    with sim:
        assert sim.run_main(main) == [], sim.console.log_text
    sim.close()
    def record(name: str, ext: str, sectors: int, attributes: str) -> str:
        # bytes 1-8 name, 9 '.', 10-12 extension, 13-20 size, 21 ' ', 22-28 attributes, 29-37 date,
        # 38 ' ', 39-46 time (blank: the simulated system date was never set)
        return f"[{name:<8}.{ext:<3}{sectors:>8} {attributes:<7}{'':9} {'':8}]"

    lines = sim.console.output.splitlines()
    assert lines == [record("a", "v2", 0, ""), record("data", "tst", 2, ""), record("sub", "", 0, "D"), "-504"]
    assert all(len(line) == 46 + 2 for line in lines[:3])
