"""samples/tcp_command_server serves concurrent clients, each in its own uniquely named thread.

Thread names identify threads (-749 *Thread already exists* for a second live thread of the same
name), so the sample names each client thread after its connection number, as cell_server does.
The server has no shutdown command: the test ends it with ``Simulation.stop()``.
"""

from __future__ import annotations

import threading
from pathlib import Path

from gpltest import SAMPLES, LineClient, copy_project, free_port, transpile
from gplrt.sim import Simulation

TIMEOUT = 15.0


def test_two_concurrent_clients_are_both_served(tmp_path: Path) -> None:
    port = free_port()
    src = copy_project(SAMPLES / "tcp_command_server", tmp_path / "src" / "tcp_command_server",
                       {"SERVER_PORT As Integer = 10100": f"SERVER_PORT As Integer = {port}"})
    sample = transpile(src, tmp_path / "out")
    sim = Simulation(clock="real", speed=10.0, capture=True)
    runner = threading.Thread(target=sample.package.main, args=(sim,), daemon=True)
    runner.start()
    try:
        for _ in range(400):
            if "listening" in sim.console.output:
                break
            runner.join(0.025)
        assert "listening" in sim.console.output, sim.console.output + sim.console.log_text
        first, second = LineClient(port, newline="\n"), LineClient(port, newline="\n")
        try:
            # both connections open at once, requests interleaved
            assert first.ask("version") == "0 TCS sample 1.2"
            assert second.ask("version") == "0 TCS sample 1.2"
            assert first.ask("echo one") == "0 one"
            assert second.ask("echo two") == "0 two"
            names = sorted(t.Name for t in sim.threads if t.StartProcedure.lower() == "startup.serveclient")
            assert len(names) == 2 and len(set(names)) == 2
            assert second.ask("quit") == "0 bye"
            assert first.ask("echo still here") == "0 still here"
        finally:
            first.close()
            second.close()
        third = LineClient(port, newline="\n")  # a later client after one has left
        try:
            assert third.ask("echo three") == "0 three"
        finally:
            third.close()
        assert sim.console.log_text == ""
        assert [t.Name for t in sim.threads if t.unhandled_error is not None] == []
    finally:
        report = sim.stop(grace=TIMEOUT)
        runner.join(TIMEOUT)
    assert report.still_alive == []
    assert not runner.is_alive()
