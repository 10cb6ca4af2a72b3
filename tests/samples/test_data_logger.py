"""samples/data_logger: XML configuration in, CSV log and XML summary out, in virtual time.

The signals are scripted on the controller clock; the expected rows are computed here from
that script and the configured period (samples at k * 0.25 s), never copied from a run.
"""

from __future__ import annotations

import xml.dom.minidom
from pathlib import Path

import pytest

from gpltest import SAMPLES, Transpiled, transpile
from gplrt.controller.signals import IoMap
from gplrt.sim import Simulation

CONFIG = """<?xml version="1.0"?>
<logger station="Line3">
  <!-- four samples a second -->
  <sample period_ms="250" count="8"/>
  <channel signal="10001" name="door"/>
  <channel signal="10002" name="vacuum"/>
  <analog channel="10001" name="pressure"/>
</logger>
"""
PERIOD = 0.25
COUNT = 8
DOOR_OPEN = (0.6, 1.1)  # input 10001 high in this interval
VACUUM_ON = 0.1  # input 10002 high from here on
PRESSURE = [(0.1, 1.5), (0.9, 2.25), (1.4, 0.75)]  # analog input 10001 steps (time, value)


def pressure_at(t: float) -> float:
    value = 0.0
    for when, v in PRESSURE:
        if when <= t:
            value = v
    return value


def expected_rows() -> list[str]:
    rows = ["time,door,vacuum,pressure"]
    for k in range(COUNT):
        t = k * PERIOD
        door = int(DOOR_OPEN[0] <= t < DOOR_OPEN[1])
        vacuum = int(t >= VACUUM_ON)
        p = pressure_at(t)
        rows.append(f"{t:.3f},{door},{vacuum},{p:g}")
    return rows


@pytest.fixture(scope="module")
def sample(tmp_path_factory: pytest.TempPathFactory) -> Transpiled:
    return transpile(SAMPLES / "data_logger", tmp_path_factory.mktemp("data_logger"))


def scripted(sim: Simulation) -> None:
    io = sim.io
    io.schedule_input(10001, True, DOOR_OPEN[0])
    io.schedule_input(10001, False, DOOR_OPEN[1])
    io.schedule_input(10002, True, VACUUM_ON)
    for when, v in PRESSURE:
        sim.scheduler.call_at(when, lambda v=v: io.set_analog_input(10001, v))


def test_logs_every_sample_on_the_period_grid_and_summarises(sample: Transpiled, tmp_path: Path) -> None:
    folder = tmp_path / "flash" / "logger"
    folder.mkdir(parents=True)
    (folder / "config.xml").write_text(CONFIG)
    sim = Simulation(capture=True, flash_root=tmp_path, io=IoMap())
    scripted(sim)
    assert sample.package.main(sim) == 0

    rows = expected_rows()
    assert (folder / "log.csv").read_bytes() == ("\r\n".join(rows) + "\r\n").encode()

    data = [r.split(",") for r in rows[1:]]
    door_on = sum(int(d[1]) for d in data)
    vacuum_on = sum(int(d[2]) for d in data)
    pressures = [float(d[3]) for d in data]
    mean = sum(pressures) / len(pressures)
    assert sim.console.output.splitlines() == [
        "station Line3: 2 digital, 1 analog, 8 samples every 250 ms",
        f"door on in {door_on} of {COUNT}",
        f"vacuum on in {vacuum_on} of {COUNT}",
        f"pressure {min(pressures):g} .. {max(pressures):g}, mean {mean:g}",
        "summary written to /flash/logger/summary.xml",
    ]
    root = xml.dom.minidom.parse(str(folder / "summary.xml")).documentElement
    assert root.tagName == "summary"
    assert (root.getAttribute("station"), root.getAttribute("samples")) == ("Line3", str(COUNT))
    channels = {c.getAttribute("name"): c.getAttribute("on") for c in root.getElementsByTagName("channel")}
    assert channels == {"door": str(door_on), "vacuum": str(vacuum_on)}
    (analog,) = root.getElementsByTagName("analog")
    assert float(analog.getAttribute("min")) == min(pressures)
    assert float(analog.getAttribute("max")) == max(pressures)
    assert float(analog.getAttribute("mean")) == mean
    # the sampling took (COUNT - 1) periods of controller time, not wall time
    assert abs(sim.now() - (COUNT - 1) * PERIOD) < 1e-6


def test_missing_configuration_is_reported_with_the_file_error(sample: Transpiled, tmp_path: Path) -> None:
    (tmp_path / "flash" / "logger").mkdir(parents=True)
    sim = Simulation(capture=True, flash_root=tmp_path)
    assert sample.package.main(sim) == 0
    assert sim.console.output == "no configuration: error -508\n"
    assert not (tmp_path / "flash" / "logger" / "log.csv").exists()


def test_malformed_configuration_is_reported_with_the_xml_error(sample: Transpiled, tmp_path: Path) -> None:
    folder = tmp_path / "flash" / "logger"
    folder.mkdir(parents=True)
    (folder / "config.xml").write_text("<logger><sample></logger>")
    sim = Simulation(capture=True, flash_root=tmp_path)
    sample.package.main(sim)
    lines = sim.console.output.splitlines()
    assert lines[0].startswith("config error -799, ")
    assert lines[-1] == "no configuration: error -799"
