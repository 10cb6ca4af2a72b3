"""Ruckig planning: limits respected, targets reached exactly, axes synchronised, Profile mapping."""

from __future__ import annotations

import math

import numpy as np
from hypothesis import example, given, settings
from hypothesis import strategies as st

from gplrt.controller.pdb import default_database
from gplrt.motion.limits import AxisLimits, RobotLimits
from gplrt.motion.planner import PLANNING_FAILED, Plan, plan_axes, plan_scalar
from gplrt.motion.profile import Profile
from gpltest import code_of

LIMITS = RobotLimits.from_pdb(default_database("PF400SX"), 1, 5)
LOWER = np.array([1.5, -93.0, 12.0, -960.0, 69.0])
UPPER = np.array([1161.5, 93.0, 348.0, 960.0, 134.0])
#: Ruckig's own position precision (profile.hpp ``p_precision``): the bound on its end-point error.
RUCKIG_P_PRECISION = 1e-8


def sample(plan: Plan, n: int = 400) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    ts = np.linspace(0.0, plan.duration, n)
    p, v, a = zip(*(plan.at(float(t)) for t in ts))
    return ts, np.array(p), np.array(v), np.array(a)


def check_within(plan: Plan, lim: AxisLimits, q0: np.ndarray, q1: np.ndarray) -> None:
    _, p, v, a = sample(plan)
    assert np.all(np.abs(v) <= lim.velocity * (1 + 1e-9) + 1e-9)
    assert np.all(np.abs(a) <= np.maximum(lim.accel, lim.decel) * (1 + 1e-9) + 1e-9)
    lo, hi = np.minimum(q0, q1), np.maximum(q0, q1)
    # Ruckig integrates in double precision: its position error grows with the travel (1.4e-9 over
    # the wrist's 1920 degrees, see the examples below), so the bound has a relative part too.  Its
    # profiles are only checked to its position precision (``p_precision`` = 1e-8 in Ruckig's
    # profile.hpp): a 6.5 nm gripper move synchronised to a 25 s wrist move ends 2.8e-9 to 6.5e-9
    # off (third example).  The motion queue holds q1 exactly at the end (test_move checks Where).
    tol = RUCKIG_P_PRECISION + 1e-12 * float(np.max(np.abs(q1 - q0)))
    assert np.all(p >= lo - tol) and np.all(p <= hi + tol)  # no overshoot from rest to rest
    end = np.array(plan.at(plan.duration)[0])
    assert np.max(np.abs(end - q1)) < tol  # Ruckig's own end; the motion queue then holds q1 exactly


joint_vec = st.lists(st.floats(0.0, 1.0), min_size=5, max_size=5).map(lambda f: LOWER + np.array(f) * (UPPER - LOWER))


@settings(max_examples=40, deadline=None)
@given(joint_vec, joint_vec, st.floats(5.0, 150.0), st.floats(10.0, 300.0), st.floats(10.0, 300.0),
       st.floats(0.0, 0.3))
# full wrist travel at low speed (found by hypothesis): the end is 1.3e-9 / 1.4e-9 off
@example(LOWER + np.array([0.0, 0.0, 0.0, 0.0, 0.1490403289436482]) * (UPPER - LOWER),
         np.array([1.5, -93.0, 12.0, 960.0, 69.0]), 5.0, 150.0, 231.875, 0.0)
@example(np.array([1.5, -93.0, 12.0, -960.0, 101.5]), np.array([1.5, -93.0, 12.0, 960.0, 69.0]), 5.0, 115.0, 150.0, 0.0)
@example(np.array([1.5, -93.0, 12.0, -960.0, 69.0]),
         LOWER + np.array([0.0, 0.0, 0.0, 0.8456194731082987, 1e-10]) * (UPPER - LOWER), 8.871559871988431, 36.0,
         18.874127743708986, 0.0234375)
# a 1e-5 degree wrist move with a 1 µs ramp (found by hypothesis): Ruckig failed at jerk = accel / 1e-6
@example(np.array([1.5, -93.0, 12.0, -960.0, 69.0]),
         LOWER + np.array([0.0, 0.0, 0.0, 0.0, 5.960464477539063e-08]) * (UPPER - LOWER), 5.0, 10.0, 90.0, 1e-06)
def test_joint_plans_respect_limits_and_end_on_target(q0: np.ndarray, q1: np.ndarray, speed: float, accel: float,
                                                      decel: float, ramp: float) -> None:
    prof = Profile()
    prof.Speed, prof.Accel, prof.Decel, prof.AccelRamp, prof.DecelRamp = speed, accel, decel, ramp, ramp
    lim = LIMITS.joint_limits(prof, 100.0)
    zero = np.zeros(5)
    plan = plan_axes(q0, zero, zero, q1, lim)
    check_within(plan, lim, q0, q1)


def test_axes_are_time_synchronised() -> None:
    """Every moving axis is still moving until the common end (none finishes early)."""
    prof = Profile()
    lim = LIMITS.joint_limits(prof, 100.0)
    q0, q1 = np.array([100.0, 0.0, 90.0, 0.0, 100.0]), np.array([400.0, 10.0, 200.0, -90.0, 101.0])
    plan = plan_axes(q0, np.zeros(5), np.zeros(5), q1, lim)
    p = np.array(plan.at(0.95 * plan.duration)[0])
    assert np.all(np.abs(p - q1) > 1e-6)
    assert np.all(np.abs(np.array(plan.at(plan.duration)[0]) - q1) < 1e-12)


def test_profile_percentages_scale_the_database_references() -> None:
    prof = Profile()
    prof.Speed, prof.Accel, prof.Decel = 40.0, 50.0, 25.0
    lim = LIMITS.joint_limits(prof, 50.0)
    assert np.allclose(lim.velocity, np.array([500, 360, 720, 720, 400]) * 0.4 * 0.5)
    assert np.allclose(lim.accel, np.array([3500, 600, 920, 4000, 10000]) * 0.5)
    assert np.allclose(lim.decel, np.array([3500, 600, 920, 4000, 10000]) * 0.25)
    # ramp: jerk = accel / ramp, the more restrictive of the two ramps
    assert np.allclose(lim.jerk, np.minimum(lim.accel / 0.1, lim.decel / 0.1))
    prof.Speed = 1000.0  # above DataID 2704 (150 %): clamped, not an error
    assert np.allclose(LIMITS.joint_limits(prof, 100.0).velocity, np.array([500, 360, 720, 720, 400]) * 1.5)


def test_accel_and_decel_apply_to_their_own_phases() -> None:
    prof = Profile()
    prof.Accel, prof.Decel, prof.AccelRamp, prof.DecelRamp = 100.0, 25.0, 0.0, 0.0
    lim = LIMITS.joint_limits(prof, 100.0)
    q0, q1 = np.zeros(5) + np.array([1.5, 0, 12, 0, 69]), np.array([801.5, 0, 12, 0, 69])
    _, _, v, a = sample(plan_axes(q0, np.zeros(5), np.zeros(5), q1, lim), 2000)
    assert math.isclose(a[:, 0].max(), 3500.0, rel_tol=1e-6)  # speeding up at Accel
    assert math.isclose(-a[:, 0].min(), 875.0, rel_tol=1e-6)  # braking at Decel
    # and the same for a move in the negative direction
    _, _, v, a = sample(plan_axes(q1, np.zeros(5), np.zeros(5), q0, lim), 2000)
    assert math.isclose(-a[:, 0].min(), 3500.0, rel_tol=1e-6)
    assert math.isclose(a[:, 0].max(), 875.0, rel_tol=1e-6)


def test_ramp_time_is_the_time_to_reach_peak_acceleration() -> None:
    prof = Profile()
    prof.AccelRamp = prof.DecelRamp = 0.2
    prof.Speed = 150.0  # 750 mm/s: the ramp completes before the speed limit binds
    lim = LIMITS.joint_limits(prof, 100.0)
    q0, q1 = np.array([1.5, 0, 12, 0, 69]), np.array([1001.5, 0, 12, 0, 69])
    plan = plan_axes(q0, np.zeros(5), np.zeros(5), q1, lim)
    # acceleration grows linearly from 0 to 3500 mm/s² in 0.2 s
    assert math.isclose(plan.at(0.1)[2][0], 1750.0, rel_tol=1e-9)
    assert math.isclose(plan.at(0.2)[2][0], 3500.0, rel_tol=1e-9)


def test_plan_from_a_moving_state_keeps_velocity_continuous() -> None:
    lim = LIMITS.joint_limits(Profile(), 100.0)
    q0, v0 = np.array([300.0, 0, 90, 0, 100]), np.array([200.0, 50, -30, 0, 0])
    q1 = np.array([100.0, 20, 150, 10, 100])
    plan = plan_axes(q0, v0, np.zeros(5), q1, lim)
    assert np.allclose(plan.at(0.0)[1], v0, atol=1e-12)
    assert np.allclose(plan.at(plan.duration)[0], q1, atol=1e-12)


def test_scalar_plan_reaches_one_within_limits() -> None:
    plan = plan_scalar(0.0, 0.0, 0.0, 1.0, 2.0, 8.0, 4.0, 80.0)
    _, p, v, a = sample(plan)
    assert p[-1, 0] == 1.0 or abs(p[-1, 0] - 1.0) < 1e-12
    assert v.max() <= 2.0 + 1e-12 and a.max() <= 8.0 + 1e-12 and a.min() >= -4.0 - 1e-12


def test_threads_planning_at_once_do_not_share_ruckig_inputs() -> None:
    """Under the real clock GPL threads run preemptively: two robots (or a motion and another
    thread's RapidDecel) may plan at the same moment.  Each plan must be the plan of its own
    inputs — no thread may see the start, target or limits another thread just wrote."""
    import sys
    import threading

    lim = LIMITS.joint_limits(Profile(), 100.0)
    errors: list[str] = []

    def worker(seed: int) -> None:
        rng = np.random.default_rng(seed)
        for _ in range(1500):
            q0, q1 = LOWER + rng.uniform(0, 1, 5) * (UPPER - LOWER), LOWER + rng.uniform(0, 1, 5) * (UPPER - LOWER)
            plan = plan_axes(q0, None, None, q1, lim)
            start, end = np.array(plan.at(0.0)[0]), np.array(plan.at(plan.duration)[0])
            if np.max(np.abs(start - q0)) > 1e-6 or np.max(np.abs(end - q1)) > 1e-6:
                errors.append(f"planned {start} -> {end} for {q0} -> {q1}")

    old = sys.getswitchinterval()
    sys.setswitchinterval(1e-6)  # switch threads as often as Python can
    try:
        threads = [threading.Thread(target=worker, args=(seed,)) for seed in (1, 2, 3)]
        for t in threads:
            t.start()
        for t in threads:
            t.join()
    finally:
        sys.setswitchinterval(old)
    assert errors == []


def test_each_thread_plans_with_its_own_ruckig_input() -> None:
    """The deterministic side of the test above: the InputParameter a plan writes its start,
    target and limits into belongs to the planning thread alone."""
    import threading

    from gplrt.motion import planner

    seen = []
    other = threading.Thread(target=lambda: seen.append(planner._solver(5)[1]))
    other.start()
    other.join()
    seen.append(planner._solver(5)[1])
    assert seen[0] is not seen[1]
    assert planner._solver(5)[1] is seen[1]  # and it is kept for the thread's next plan


def test_a_motion_beyond_ruckigs_duration_range_is_a_gpl_error_not_a_valueerror() -> None:
    # Speed 1e-9 % makes a 300 mm move last ~1e9 s: Ruckig answers -101 (ErrorTrajectoryDuration),
    # a code its Python enum does not name, so the binding raises ValueError from calculate().
    prof = Profile()
    prof.Speed = 1e-9
    lim = LIMITS.joint_limits(prof, 100.0)
    q0 = np.array([300.0, 0.0, 90.0, 0.0, 100.0])
    assert code_of(plan_axes, q0, None, None, q0 + [300.0, 0, 0, 0, 0], lim) == PLANNING_FAILED


@settings(max_examples=60, deadline=None)
@given(st.integers(1, 5), st.integers(0, 2**32 - 1), st.booleans())
def test_plan_sample_is_ruckigs_own_evaluation_bit_for_bit(n: int, seed: int, moving: bool) -> None:
    """``Plan.sample`` (every cycle of a path motion, the blend planner's overlap) gives exactly
    what ``Plan.at`` (Ruckig's ``at_time``) gives at each time, before, inside and after the plan:
    with a start in motion too, where a brake pre-phase sends it to Ruckig itself."""
    rng = np.random.default_rng(seed)
    q0, q1 = rng.uniform(LOWER, UPPER)[:n], rng.uniform(LOWER, UPPER)[:n]
    v0 = rng.uniform(-200.0, 200.0, n) if moving else None
    a0 = rng.uniform(-500.0, 500.0, n) if moving else None
    lim = LIMITS.joint_limits(Profile(), 100.0)
    lim = AxisLimits(lim.velocity[:n], lim.accel[:n], lim.decel[:n], lim.jerk[:n])
    plan = plan_axes(q0, v0, a0, q1, lim)
    ts = np.concatenate((rng.uniform(0.0, plan.duration, 50), [0.0, plan.duration, -1.0, plan.duration + 1.0]))
    P, V, A = plan.sample(ts)
    for i, t in enumerate(ts):
        p, v, a = plan.at(float(t))
        assert P[i].tolist() == p and V[i].tolist() == v and A[i].tolist() == a, t
