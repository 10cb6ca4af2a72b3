"""V+ motion on the shared planner (the ARM6 model, and the Cobra s600 SCARA): forward processing,
APPRO/DEPART along tool Z, one-shot vs ALWAYS speed, BREAK, OPENI/CLOSE, HERE/DEST, LEFTY/RIGHTY."""

from __future__ import annotations

import pytest

from gplrt import vplus as vp
from gplrt.motion.kinematics.config import GPL_LEFTY, GPL_RIGHTY
from gplrt.motion.robot_class import Robot
from gplrt.sim import Simulation
from gplrt.vplus.transforms import components

TOL = 1e-6


@pytest.fixture
def arm() -> Simulation:
    s = Simulation(robot="ARM6", capture=True)
    yield s
    s.close()


def _start_pose() -> object:
    return vp.p_ppoint(0, -30, 60, 0, 60, 0)


def test_move_break_here_matches_target(arm: Simulation) -> None:
    got: dict[str, object] = {}

    def main() -> None:
        vp.move(_start_pose())
        vp.break_()
        p = vp.here()
        target = vp.shift(p, 50, 20, -30)
        vp.moves(target)
        vp.break_()
        got["target"], got["here"], got["dest"] = target, vp.here(), vp.dest()

    with arm:
        assert arm.run_main(main) == []
    for key in ("here", "dest"):
        assert components(got[key]) == pytest.approx(components(got["target"]), abs=TOL)


def test_appro_and_depart_work_along_tool_z(arm: Simulation) -> None:
    got: dict[str, object] = {}

    def main() -> None:
        vp.move(_start_pose())
        vp.break_()
        place = vp.here()
        vp.appro(place, 50)
        vp.break_()
        got["appro"] = vp.here()
        vp.moves(place)
        vp.departs(30)
        vp.break_()
        got["depart"] = vp.here()
        got["place"] = place

    with arm:
        assert arm.run_main(main) == []
    place = got["place"]
    assert components(got["appro"]) == pytest.approx(components(vp.compose(place, vp.trans(0, 0, -50))), abs=TOL)
    assert components(got["depart"]) == pytest.approx(components(vp.compose(place, vp.trans(0, 0, -30))), abs=TOL)


def test_forward_processing_signal_after_move_fires_at_motion_start(arm: Simulation) -> None:
    """L6309-6325: MOVE a; SIGNAL 1; MOVE b; SIGNAL 2."""
    times: dict[str, float] = {}

    def main() -> None:
        vp.move(_start_pose())
        vp.break_()
        t0 = arm.now()
        vp.move(vp.p_ppoint(30, -20, 50, 0, 60, 0))
        vp.signal(1)
        times["sig1"] = arm.now() - t0
        vp.move(vp.p_ppoint(-30, -20, 50, 0, 60, 0))
        vp.signal(2)
        times["sig2"] = arm.now() - t0
        vp.break_()
        times["end"] = arm.now() - t0

    with arm:
        assert arm.run_main(main) == []
    assert times["sig1"] == 0.0  # at once: the robot was still
    assert 0.0 < times["sig2"] < times["end"]  # when the second motion began, before the end
    assert arm.io.read_dio(1) and arm.io.read_dio(2)


def test_one_shot_speed_applies_to_the_next_motion_only(arm: Simulation) -> None:
    durations: list[float] = []

    def timed(target: object) -> None:
        t0 = arm.now()
        vp.move(target)
        vp.break_()
        durations.append(arm.now() - t0)

    a, b = vp.p_ppoint(0, -30, 60, 0, 60, 0), vp.p_ppoint(40, -30, 60, 0, 60, 0)

    def main() -> None:
        vp.move(a)
        vp.break_()
        timed(b)           # program speed 100
        vp.speed(25)       # one shot
        timed(a)
        timed(b)           # back to 100
        vp.speed(25, always=True)
        timed(a)
        timed(b)

    with arm:
        assert arm.run_main(main) == []
    fast, slow_once, fast_again, slow1, slow2 = durations
    assert fast_again == pytest.approx(fast, rel=1e-6)
    assert slow_once > 1.5 * fast and slow1 == pytest.approx(slow_once, rel=1e-6)
    assert slow2 == pytest.approx(slow1, rel=1e-6)


def test_closei_waits_hand_time_and_close_waits_for_the_next_motion(arm: Simulation) -> None:
    seen: dict[str, object] = {}

    def main() -> None:
        vp.move(_start_pose())
        vp.parameter_set("HAND.TIME", 0.16)
        t0 = arm.now()
        vp.closei()
        seen["closei"] = arm.now() - t0
        seen["closed"] = (arm.io.read_dio(1), arm.io.read_dio(2))
        vp.open_()
        seen["before"] = (arm.io.read_dio(1), arm.io.read_dio(2))
        vp.move(vp.p_ppoint(10, -30, 60, 0, 60, 0))
        seen["after"] = (arm.io.read_dio(1), arm.io.read_dio(2))

    with arm:
        assert arm.run_main(main) == []
    assert seen["closed"] == (False, True) and seen["before"] == (False, True) and seen["after"] == (True, False)
    assert seen["closei"] > 0.16  # the motion ended first (CLOSEI breaks CP), then HAND.TIME


def test_unreachable_target_is_a_vplus_error_reacte_can_trap(arm: Simulation) -> None:
    @vp.program("m.trouble")
    def trouble() -> None:
        vp.type_("trapped ", vp.error(-1))

    def main() -> None:
        vp.reacte(trouble)
        with vp.step(1):
            vp.move(vp.trans(5000, 0, 0))
        with vp.step(2):
            vp.type_("went on")

    with arm:
        assert arm.run_main(main) == []
    lines = arm.console.output.splitlines()
    assert lines[0].startswith("trapped -") and lines[1] == "went on"


@pytest.fixture
def cobra() -> Simulation:
    s = Simulation(robot="COBRA-S600", capture=True)
    yield s
    s.close()


def test_scara_appro_is_straight_up_and_lefty_righty_choose_the_arm(cobra: Simulation) -> None:
    """On a SCARA the tool points down (pitch 180, L6033-6046), so APPRO's tool -Z is world up;
    RIGHTY/LEFTY ask for the elbow's side during the next motion."""
    got: dict[str, object] = {}

    def main() -> None:
        vp.move(vp.p_ppoint(10, 40, -50, 30))
        vp.break_()
        place = vp.here()
        got["place"] = place
        vp.righty()
        vp.move(place)
        vp.break_()
        got["righty"] = vp.p_phere()
        got["righty_config"] = vp.here().Config
        vp.lefty()
        vp.move(place)
        vp.break_()
        got["lefty"] = vp.p_phere()
        got["lefty_config"] = vp.here().Config
        got["lefty_here"] = vp.here()
        vp.appro(place, 50)
        vp.break_()
        got["appro"] = vp.here()

    with cobra:
        assert cobra.run_main(main) == [], cobra.console.log_text
    x, y, z, yaw, pitch, roll = components(got["place"])
    assert (yaw, pitch) == (0.0, 180.0)
    assert components(got["appro"]) == pytest.approx((x, y, z + 50, yaw, pitch, roll), abs=TOL)
    assert components(got["lefty_here"]) == pytest.approx(components(got["place"]), abs=TOL)
    j_right, j_left = components(got["righty"]), components(got["lefty"])
    assert j_right[1] * j_left[1] < 0  # the elbow on either side
    assert got["righty_config"] & GPL_RIGHTY and got["lefty_config"] & GPL_LEFTY


def test_viper_unreachable_and_out_of_range_goals_are_vplus_errors() -> None:
    sim = Simulation(robot="VIPER-S650", capture=True)

    def main() -> None:
        vp.move(vp.p_ppoint(10, -20, 40, 5, 50, -10))
        vp.break_()
        vp.type_(vp.inrange(vp.here()), " ", vp.inrange(vp.trans(5000, 0, 0)))
        for target in (vp.trans(5000, 0, 0), vp.p_ppoint(500, 0, 0, 0, 0, 0)):
            try:
                vp.move(target)
            except vp.VError as e:
                vp.type_(e.ErrorCode, " ", e.Message())

    with sim:
        assert sim.run_main(main) == []
    assert sim.console.output.splitlines() == ["0 -1005", "-1005 *Location too far*", "-1002 *Joint out of range*"]
    sim.close()


def test_reacti_stops_the_robot_and_brake_likewise(arm: Simulation) -> None:
    """REACTI also brakes (L4498-4500): the arm stops short of the goal when the input comes."""
    seen: dict[str, object] = {}

    @vp.program("m.stopper")
    def stopper() -> None:
        seen["reacted"] = arm.now()

    def main() -> None:
        vp.move(_start_pose())
        vp.break_()
        vp.reacti(1001, "m.stopper")
        vp.move(vp.p_ppoint(90, -30, 60, 0, 60, 0))
        vp.wait_for(lambda: vp.sig(1001))
        vp.break_()
        seen["joints"] = components(vp.p_phere())

    arm.io.schedule_input(10001, True, 1.3)
    with arm:
        assert arm.run_main(main) == []
    assert "reacted" in seen
    j1 = seen["joints"][0]  # type: ignore[index]
    assert 0.0 < j1 < 89.0  # stopped on the way


def test_tool_moves_the_point_here_reports_and_base_shifts_the_world() -> None:
    """On the Viper s650 (the ARM6 model ignores a Tool in its forward kinematics, on main too)."""
    arm = Simulation(robot="VIPER-S650", capture=True)
    got: dict[str, object] = {}

    def main() -> None:
        vp.move(vp.p_ppoint(10, -20, 40, 5, 50, -10))
        vp.break_()
        flange = vp.here()
        vp.tool(vp.trans(0, 0, 100))
        got["tool"] = vp.tool_value()
        got["tip"], got["flange"] = vp.here(), flange
        vp.tool(vp.null())
        vp.base(0, 0, 300)
        got["based"], got["base"] = vp.here(), vp.base_value()

    with arm:
        assert arm.run_main(main) == [], arm.console.log_text
    arm.close()
    assert callable(Robot.Tool)  # the shared Robot object is left as it was
    assert components(got["tool"]) == pytest.approx((0, 0, 100, 0, 0, 0), abs=TOL)
    assert components(got["tip"]) == pytest.approx(
        components(vp.compose(got["flange"], vp.trans(0, 0, 100))), abs=TOL)  # type: ignore[arg-type]
    x, y, z, *ypr = components(got["flange"])
    # the world frame moved 300 mm up relative to the robot: the tool reads 300 mm lower
    assert components(got["based"]) == pytest.approx((x, y, z - 300, *ypr), abs=TOL)
    assert components(got["base"]) == pytest.approx((0, 0, 300, 0, 0, 0), abs=TOL)


def test_duration_makes_a_joint_motion_last_at_least_that_long(arm: Simulation) -> None:
    times: list[float] = []

    def timed(target: object) -> None:
        t0 = arm.now()
        vp.move(target)
        vp.break_()
        times.append(arm.now() - t0)

    a, b = vp.p_ppoint(0, -30, 60, 0, 60, 0), vp.p_ppoint(40, -30, 60, 0, 60, 0)

    def main() -> None:
        vp.move(a)
        vp.break_()
        timed(b)                  # as fast as the profile allows
        vp.duration(3.0)          # one shot
        timed(a)
        timed(b)
        vp.duration(0.01, always=True)  # shorter than the motion: no effect
        timed(a)
        vp.move(a)
        vp.break_()
        start = vp.here()
        timed(vp.shift(start, 0, 0, -50))  # 50 mm away ...
        vp.duration(2.5)
        t0 = arm.now()
        vp.moves(start)                    # ... and back on a straight line stretched to 2.5 s
        vp.break_()
        times.append(arm.now() - t0)

    with arm:
        assert arm.run_main(main) == []
    fast, stretched, again, short = times[:4]
    assert fast < 3.0
    assert stretched == pytest.approx(3.0, abs=0.02)  # (the settle after the motion)
    assert again == pytest.approx(fast, rel=1e-6) and short == pytest.approx(fast, rel=1e-6)
    assert times[5] == pytest.approx(2.5, abs=0.02) and times[4] < 2.5


def test_speed_mmps_limits_the_tool_speed_on_a_straight_line() -> None:
    sim = Simulation(robot="VIPER-S650", capture=True)
    times: list[float] = []

    def main() -> None:
        vp.move(vp.p_ppoint(10, -20, 40, 5, 50, -10))
        vp.break_()
        start = vp.here()
        vp.speed(100, unit="MONITOR")  # an absolute speed needs monitor speed 100 (L6583-6594)
        for speed, unit in ((100, "MMPS"), (50, "MMPS"), (2, "IPS")):
            vp.speed(speed, unit=unit, always=True)
            t0 = sim.now()
            vp.moves(vp.shift(start, 0, 200, 0))
            vp.break_()
            times.append(sim.now() - t0)
            vp.moves(start)
            vp.break_()

    with sim:
        assert sim.run_main(main) == [], sim.console.log_text
    sim.close()
    at100, at50, at2ips = times
    # 200 mm at 100 mm/s takes at least 2 s (more for the ramps), at 50 mm/s at least 4 s
    assert 2.0 <= at100 < 3.0 and 4.0 <= at50 < 5.0
    assert 200 / 50.8 <= at2ips < 200 / 50.8 + 1.0  # 2 in/s = 50.8 mm/s
