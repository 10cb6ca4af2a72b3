"""Signal.DIO / Signal.AIO on the simulated I/O map: ranges, rules on the clock, output trace."""

from __future__ import annotations

import numpy as np
import pytest

from gplrt.controller.services import Controller
from gplrt.controller.signals import Signal, SignalChange, SignalMap
from gplrt.lang.errors import GplException
from gplrt.sim import Simulation
from gplrt.threads import Thread, checkpoint


def test_ex12_read_the_first_digital_signal(vsim: Simulation) -> None:
    signal_state = Signal.DIO(1)  # EX-12
    assert signal_state is False
    Signal.set_DIO(1, True)
    assert Signal.DIO(1) is True


def test_writing_an_input_is_refused_with_1519(vsim: Simulation) -> None:
    with pytest.raises(GplException) as info:
        Signal.set_DIO(10001, True)
    assert info.value.ErrorCode == -1519
    with pytest.raises(GplException) as info:
        Signal.set_AIO(10001, 2.5)
    assert info.value.ErrorCode == -1519
    assert vsim.io.trace == []


@pytest.mark.parametrize(("signal", "code"), [(0, -1517), (65, -1518), (10065, -1518), (30000, -1518)])
def test_undefined_and_invalid_signal_numbers(vsim: Simulation, signal: int, code: int) -> None:
    with pytest.raises(GplException) as info:
        Signal.DIO(signal)
    assert info.value.ErrorCode == code


def test_soft_signals_are_read_write_and_negative_numbers_invert(vsim: Simulation) -> None:
    Signal.set_DIO(20001, True)
    assert Signal.DIO(20001) is True
    assert Signal.DIO(-20001) is False
    Signal.set_DIO(-2, False)  # inverted write: output 2 goes on
    assert Signal.DIO(2) is True
    assert Signal.DIO(-10003) is True  # input 10003 is off


def test_analog_channels(vsim: Simulation) -> None:
    Signal.set_AIO(3, 4.25)
    assert Signal.AIO(3) == 4.25
    vsim.io.set_analog_input(10002, -1.5)
    assert Signal.AIO(10002) == -1.5
    assert [(c.kind, c.signal, c.value, c.source) for c in vsim.io.trace] == [
        ("AIO", 3, 4.25, "gpl"),
        ("AIO", 10002, -1.5, "sim"),
    ]


def test_rule_fires_at_the_right_virtual_time_and_trace_is_stamped(vsim: Simulation) -> None:
    """'DIO 10001 goes high 2 s after output 1 goes high'; the program waits for it by polling."""
    vsim.io.when_output(1, True).set_input(10001, True, after=2.0)
    vsim.io.when_output(1, False).set_input(10001, False, after=0.5)
    seen: list[float] = []

    def main() -> None:
        Thread.Sleep(1000)
        Signal.set_DIO(1, True)  # at 1.0
        t0 = Controller.Timer(1)
        while not Signal.DIO(10001):
            Thread.Sleep(10)
        seen.append(Controller.Timer(1) - t0)
        Signal.set_DIO(1, False)
        while Signal.DIO(10001):
            Thread.Sleep(0)
            checkpoint()
        seen.append(Controller.Timer(1))

    vsim.run_main(main)
    assert seen[0] == 2.0
    assert 3.5 <= seen[1] < 3.5 + 0.001 * 2  # the off edge, observed by a Sleep(0) spin
    assert vsim.io.trace == [
        SignalChange(1.0, "DIO", 1, True, "gpl"),
        SignalChange(3.0, "DIO", 10001, True, "sim"),
        SignalChange(3.0, "DIO", 1, False, "gpl"),
        SignalChange(3.5, "DIO", 10001, False, "sim"),
    ]
    assert [c.signal for c in vsim.io.output_trace()] == [1, 1]


def test_rules_wake_a_sleeping_program_in_time_order(vsim: Simulation) -> None:
    """Several pending actions: time jumps from one to the next, firing in deadline order."""
    vsim.io.when_output(5).set_input(10005, True, after=3.0).set_input(10004, True, after=1.0)
    log: list[tuple[float, bool, bool]] = []

    def main() -> None:
        Signal.set_DIO(5, True)
        for _ in range(4):
            Thread.Sleep(1000)
            log.append((Controller.Timer(1), Signal.DIO(10004), Signal.DIO(10005)))

    vsim.run_main(main)
    assert log == [(1.0, True, False), (2.0, True, False), (3.0, True, True), (4.0, True, True)]


def test_scheduled_inputs_and_listener(vsim: Simulation) -> None:
    changes: list[SignalChange] = []
    vsim.io.on_change(changes.append)
    vsim.io.schedule_input(10010, True, at=0.75)
    seen: list[float] = []

    def main() -> None:
        while not Signal.DIO(10010):
            Thread.Sleep(50)
        seen.append(Controller.Timer(1))

    vsim.run_main(main)
    assert seen == [0.75]
    assert changes == [SignalChange(0.75, "DIO", 10010, True, "sim")]


def test_custom_signal_map() -> None:
    from gplrt.controller.signals import IoMap

    sim = Simulation(capture=True, io=IoMap(SignalMap(digital_outputs=range(97, 105), digital_inputs=range(1, 9))))
    with sim:
        Signal.set_DIO(97, True)
        with pytest.raises(GplException) as info:
            Signal.set_DIO(1, True)
        assert info.value.ErrorCode == -1519


def test_latch_results_queue_per_robot_with_timestamps_and_event(vsim: Simulation) -> None:
    from gplrt.controller.signals import Latch

    class FakeRobot:
        def latch_angles(self) -> list[float]:
            return [10.0 * vsim.now(), 5.0]

    vsim.robots[1] = FakeRobot()
    vsim.io.configure_latch(10007, robot=1)
    vsim.io.schedule_input(10007, True, at=0.5)
    vsim.io.schedule_input(10007, False, at=0.6)  # falling edge: no latch
    vsim.io.schedule_input(10007, True, at=0.8)
    got: list[tuple[int, float, float, float, int]] = []

    def main() -> None:
        Latch.set_ThreadEvent(1, 3)
        while len(got) < 2:
            ev = Thread.WaitEvent(0b100, 5000)
            while Latch.Count(1) > 0:
                lt = Latch.Result(1)
                got.append((ev, lt.Timestamp(1), lt.Angle(1), lt.Location().Angle(2), lt.Signal))

    vsim.run_main(main)
    assert got == [(4, 0.5, 5.0, 5.0, 10007), (4, 0.8, 8.0, 5.0, 10007)]
    assert Latch.Result(1) is None and Latch.ThreadEvent(1) == 3


def test_latch_overrun_raises_526_once(vsim: Simulation) -> None:
    from gplrt.controller.signals import LATCH_QUEUE_SIZE, Latch

    vsim.io.configure_latch(10008, robot=2)
    for _ in range(LATCH_QUEUE_SIZE + 1):
        vsim.io.set_input(10008, True)
        vsim.io.set_input(10008, False)
    assert Latch.Count(2) == LATCH_QUEUE_SIZE
    with pytest.raises(GplException) as info:
        Latch.Result(2)
    assert info.value.ErrorCode == -526
    assert Latch.Result(2) is not None
    Latch.Flush(2)
    assert Latch.Count(2) == 0


def test_cartesian_latch_location_is_the_tool_pose_when_the_latch_fired(vsim: Simulation) -> None:
    from gplrt.controller.signals import Latch
    from gplrt.geometry.location import Location
    from gplrt.motion.move import Move
    from gplrt.motion.profile import Profile
    from gplrt.motion.robot_class import Robot

    vsim.io.configure_latch(10003, robot=1)
    got: dict[str, object] = {}

    def main() -> None:
        Robot.Attached = 1
        Controller.PowerEnabled = True
        Robot.Home()
        t0 = vsim.now()
        vsim.io.schedule_input(10003, True, at=t0 + 0.4)  # while the arm is moving
        Move.Loc(Location.from_angles([300.0, 40.0, 100.0, 30.0, 90.0]), Profile())
        Move.WaitForEOM()
        robot = vsim.robots[1]
        got["expected"] = robot.forward(robot.joints_at(t0 + 0.4))
        got["config"] = robot.model.config_of(list(robot.joints_at(t0 + 0.4)))
        lt = Latch.Result(1)
        got["cart"], got["angles"] = lt.Location(0), lt.Location()
        got["joints"] = list(robot.joints_at(t0 + 0.4))
        try:
            lt.Location(2)
        except GplException as exc:
            got["bad"] = exc.ErrorCode

    vsim.run_main(main)
    assert vsim.console.log_text == ""
    cart = got["cart"]
    assert isinstance(cart, Location) and cart.Type == 0
    assert np.allclose(cart.matrix(), got["expected"], atol=1e-9, rtol=0.0)
    assert cart.Config == got["config"]
    assert list(got["angles"].axis_values()) == pytest.approx(got["joints"], abs=1e-9)  # type: ignore[union-attr]
    assert got["bad"] == -707


def test_cartesian_latch_location_without_kinematics_raises_1036(vsim: Simulation) -> None:
    from gplrt.controller.signals import Latch

    vsim.io.configure_latch(10004, robot=3)  # no robot 3: the latch has no axes
    vsim.io.set_input(10004, True)
    lt = Latch.Result(3)
    with pytest.raises(GplException) as info:
        lt.Location(0)
    assert info.value.ErrorCode == -1036
