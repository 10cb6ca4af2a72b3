"""Cartesian paths (straight line, arc, circle), and their joints on a sample grid.

A path maps a parameter ``u`` in [0, 1] to a tool pose (4×4, mm): the tool-tip position moves on
the line / circle at constant rate in ``u`` and the orientation is interpolated by slerp (the
geodesic ``R0 · exp(u · log(R0ᵀ R1))``).  ``Move.Loc`` with ``Profile.Straight`` plans a 1-D Ruckig
profile of ``u`` from the Cartesian limits and solves the joints cycle by cycle as the motion
runs (``path_run.PathRun``, gpl-classes §22.4).  :class:`PathJoints` solves a path on a fixed
grid at once; the blend planner uses it for its estimate of a line's joint rates where it
overlaps the previous motion (``PathJoints.rates``).
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np
import pinocchio as pin

from gplrt.geometry.transforms import Pose, matrix_to_pose, pose_to_matrix
from gplrt.lang.errors import INVALID_CARTESIAN, GplException
from gplrt.motion.limits import Vec

#: Sampling density of a fixed grid (``PathJoints.sample``): one interval per this many mm / degrees.
MM_PER_SAMPLE = 25.0
DEG_PER_SAMPLE = 15.0
MIN_SAMPLES, MAX_SAMPLES = 4, 48


def _base_intervals(path: Path) -> int:
    """Sampling intervals of the base grid: one per ``MM_PER_SAMPLE`` mm and ``DEG_PER_SAMPLE``°."""
    return int(min(MAX_SAMPLES, max(MIN_SAMPLES, math.ceil(path.length / MM_PER_SAMPLE)
                                    + math.ceil(path.turn / DEG_PER_SAMPLE))))


class Path:
    """A tool path: ``pose(u)`` for u in [0, 1], its length (mm) and turning angle (deg), and the
    pose it ends on as a pose tuple (``end_pose``: the destination the IK solves when queued)."""

    length: float
    turn: float
    end_pose: Pose

    def pose(self, u: float) -> np.ndarray:
        raise NotImplementedError

    def poses(self, us: np.ndarray) -> np.ndarray:
        """``pose(u)`` for every u of ``us``, stacked (N×4×4): one numpy pass where a path can."""
        return np.array([self.pose(float(u)) for u in us])


def as_pose(T: Pose | np.ndarray) -> Pose:
    """A pose tuple (``gplrt.geometry.transforms``) of a pose tuple or a 4×4 matrix."""
    return T if type(T) is tuple else matrix_to_pose(T)


def _rodrigues(w: np.ndarray, us: np.ndarray) -> np.ndarray:
    """``exp3(w · u)`` for every u (N×3×3), the closed form of Pinocchio's ``exp3``."""
    theta = float(np.linalg.norm(w))
    out = np.broadcast_to(np.eye(3), (len(us), 3, 3)).copy()
    if theta == 0.0:
        return out
    k = w / theta
    K = np.array([[0.0, -k[2], k[1]], [k[2], 0.0, -k[0]], [-k[1], k[0], 0.0]])
    a = theta * us
    out += np.sin(a)[:, None, None] * K + (1.0 - np.cos(a))[:, None, None] * (K @ K)
    return out


def turn_between(P0: Pose, P1: Pose) -> float:
    """The angle (deg) of the rotation taking ``P0``'s orientation to ``P1``'s: the ``turn`` of a
    slerp between them.  ``atan2(|axis|, trace − 1)`` of ``R0ᵀ R1`` keeps full precision at small
    angles, where ``acos`` of the trace alone loses half the digits."""
    a11, a12, a13, a21, a22, a23, a31, a32, a33 = P0[:9]
    b11, b12, b13, b21, b22, b23, b31, b32, b33 = P1[:9]
    # R = R0ᵀ R1: only its trace and antisymmetric part are needed
    r11 = a11 * b11 + a21 * b21 + a31 * b31
    r22 = a12 * b12 + a22 * b22 + a32 * b32
    r33 = a13 * b13 + a23 * b23 + a33 * b33
    r12 = a11 * b12 + a21 * b22 + a31 * b32
    r21 = a12 * b11 + a22 * b21 + a32 * b31
    r13 = a11 * b13 + a21 * b23 + a31 * b33
    r31 = a13 * b11 + a23 * b21 + a33 * b31
    r23 = a12 * b13 + a22 * b23 + a32 * b33
    r32 = a13 * b12 + a23 * b22 + a33 * b32
    sin2 = math.sqrt((r32 - r23) ** 2 + (r13 - r31) ** 2 + (r21 - r12) ** 2)
    return math.degrees(math.atan2(sin2, r11 + r22 + r33 - 1.0))


class _Slerp:
    def __init__(self, R0: np.ndarray, R1: np.ndarray) -> None:
        self.R0 = R0
        self.w = pin.log3(R0.T @ R1)
        self.turn = math.degrees(float(np.linalg.norm(self.w)))

    def at(self, u: float) -> np.ndarray:
        if u >= 1.0 or self.turn == 0.0:
            return self.R0 @ pin.exp3(self.w) if u >= 1.0 else self.R0.copy()
        return self.R0 @ pin.exp3(self.w * u)

    def at_many(self, us: np.ndarray) -> np.ndarray:
        """``at(u)`` for every u (N×3×3); the end (u ≥ 1) exactly as ``at`` gives it."""
        out = self.R0 @ _rodrigues(self.w, np.minimum(us, 1.0)) if self.turn else np.broadcast_to(self.R0, (len(us), 3, 3)).copy()
        end = us >= 1.0
        if end.any():
            out[end] = self.at(1.0)
        return out


class LinePath(Path):
    """Straight line of the tool tip from ``P0`` to ``P1`` (pose tuples or 4×4 matrices, mm).

    Only the length and the turn are computed when the line is made (from the pose tuples, in
    Python floats): that is all a straight ``Move.Loc`` needs when it is queued.  The matrices
    and the slerp are built the first time a pose along the line is asked for (the motion's
    cycles, ``path_run``)."""

    def __init__(self, P0: Pose | np.ndarray, P1: Pose | np.ndarray) -> None:
        if type(P0) is not tuple:  # (``as_pose``, inlined: a straight Move.Loc makes one of these)
            P0 = matrix_to_pose(P0)
        if type(P1) is not tuple:
            P1 = matrix_to_pose(P1)
        self.start_pose, self.end_pose = P0, P1
        dx, dy, dz = P1[9] - P0[9], P1[10] - P0[10], P1[11] - P0[11]
        self.length = math.sqrt(dx * dx + dy * dy + dz * dz)
        self.turn = 0.0 if P0[:9] == P1[:9] else turn_between(P0, P1)

    @functools.cached_property
    def T0(self) -> np.ndarray:
        return pose_to_matrix(self.start_pose)

    @functools.cached_property
    def T1(self) -> np.ndarray:
        return pose_to_matrix(self.end_pose)

    @functools.cached_property
    def p0(self) -> np.ndarray:
        return self.T0[:3, 3].copy()

    @functools.cached_property
    def p1(self) -> np.ndarray:
        return self.T1[:3, 3].copy()

    @functools.cached_property
    def slerp(self) -> _Slerp:
        return _Slerp(self.T0[:3, :3], self.T1[:3, :3])

    def pose(self, u: float) -> np.ndarray:
        if u >= 1.0:
            return self.T1.copy()
        T = np.eye(4)
        T[:3, :3] = self.slerp.at(u)
        T[:3, 3] = self.p0 + (self.p1 - self.p0) * u
        return T

    def poses(self, us: np.ndarray) -> np.ndarray:
        T = np.broadcast_to(np.eye(4), (len(us), 4, 4)).copy()
        T[:, :3, :3] = self.slerp.at_many(us)
        T[:, :3, 3] = self.p0 + (self.p1 - self.p0) * us[:, None]
        end = us >= 1.0
        if end.any():
            T[end] = self.T1
        return T


class ArcPath(Path):
    """Circular arc from ``T0`` through the point ``p_mid`` to ``T2`` (``full``: the whole circle
    through the three points, back to ``T0`` with constant orientation).  ``T0`` and ``T2`` are
    pose tuples or 4×4 matrices (mm)."""

    def __init__(self, T0: Pose | np.ndarray, p_mid: Sequence[float], T2: Pose | np.ndarray,
                 full: bool = False) -> None:
        self.T0, self.T2 = pose_to_matrix(as_pose(T0)), pose_to_matrix(as_pose(T2))
        self.end_pose = as_pose(T0) if full else as_pose(T2)
        a, b, c = self.T0[:3, 3], np.asarray(p_mid, float), self.T2[:3, 3]
        ab, ac = b - a, c - a
        n = np.cross(ab, ac)
        nn = float(np.dot(n, n))
        if nn < 1e-12 * max(1.0, float(np.dot(ab, ab)) * float(np.dot(ac, ac))):
            raise GplException(INVALID_CARTESIAN, detail="arc points are collinear or coincident")
        centre = a + (np.dot(ac, ac) * np.cross(n, ab) + np.dot(ab, ab) * np.cross(ac, n)) / (2.0 * nn)
        self.centre = centre
        self.radius = float(np.linalg.norm(a - centre))
        self.e1 = (a - centre) / self.radius
        self.normal = n / math.sqrt(nn)
        self.e2 = np.cross(self.normal, self.e1)

        def angle(p: np.ndarray) -> float:
            d = p - centre
            return math.atan2(float(np.dot(d, self.e2)), float(np.dot(d, self.e1))) % (2.0 * math.pi)

        # a → b → c runs counter-clockwise about ``normal`` by construction of n = ab × ac.
        self.sweep = 2.0 * math.pi if full else angle(c)
        self.full = full
        self.slerp = _Slerp(self.T0[:3, :3], self.T0[:3, :3] if full else self.T2[:3, :3])
        self.length = self.radius * self.sweep
        self.turn = self.slerp.turn

    def pose(self, u: float) -> np.ndarray:
        if u >= 1.0 and not self.full:
            return self.T2.copy()
        phi = self.sweep * min(u, 1.0)
        T = np.eye(4)
        T[:3, :3] = self.slerp.at(u)
        T[:3, 3] = self.centre + self.radius * (math.cos(phi) * self.e1 + math.sin(phi) * self.e2)
        return T

    def poses(self, us: np.ndarray) -> np.ndarray:
        phi = self.sweep * np.minimum(us, 1.0)
        T = np.broadcast_to(np.eye(4), (len(us), 4, 4)).copy()
        T[:, :3, :3] = self.slerp.at_many(us)
        T[:, :3, 3] = self.centre + self.radius * (np.cos(phi)[:, None] * self.e1 + np.sin(phi)[:, None] * self.e2)
        if not self.full:
            end = us >= 1.0
            if end.any():
                T[end] = self.T2
        return T


def _gradient(f: np.ndarray, h: float) -> np.ndarray:
    """``np.gradient(f, h, axis=0)`` (central inside, one-sided at the ends), without its overhead
    on these small arrays."""
    out = np.empty_like(f)
    out[1:-1] = (f[2:] - f[:-2]) / (2.0 * h)
    out[0] = (f[1] - f[0]) / h
    out[-1] = (f[-1] - f[-2]) / h
    return out


#: (poses N×4×4 mm, seeds N×n: the start joints with the linearly moving axes set) -> joints N×n,
#: or None to solve pose by pose (``RobotModel.inverse_path``).
PathIK = Callable[[np.ndarray, np.ndarray], "np.ndarray | None"]


@dataclass
class PathJoints:
    """The IK of a path at sample points, and joints anywhere on it (seeded by the nearest sample)."""

    path: Path
    ik: Callable[[np.ndarray, Vec], Vec]  # (pose, seed joints with extra axes set) -> joints
    u: np.ndarray
    q: np.ndarray  # (len(u), n)
    extra_start: Vec
    extra_end: Vec
    extra_mask: np.ndarray
    #: The IK without the soft-limit check, for reading the path between its samples; None: ``ik``.
    ik_between: Callable[[np.ndarray, Vec], Vec] | None = None

    @classmethod
    def sample(cls, path: Path, ik: Callable[[np.ndarray, Vec], Vec], q0: Vec, q_extra_end: Vec,
               extra_mask: np.ndarray, ik_path: PathIK | None = None) -> PathJoints:
        """Solve the path on the base grid: one interval per ``MM_PER_SAMPLE`` / ``DEG_PER_SAMPLE``."""
        return cls._solve_grid(path, ik, q0, q_extra_end, extra_mask, ik_path, _base_intervals(path))

    @classmethod
    def _solve_grid(cls, path: Path, ik: Callable[[np.ndarray, Vec], Vec], q0: Vec, q_extra_end: Vec,
                    extra_mask: np.ndarray, ik_path: PathIK | None, n: int) -> PathJoints:
        """The IK at u = k / n, each sample seeded by the previous solution.

        ``ik_path`` (the model's ``inverse_path``) solves them all in one pass; it returns None
        when some sample needs the pose-by-pose rules (a limit, an unreachable pose, a branch
        boundary), and then ``ik`` solves them one by one — which raises the proper code."""
        us = np.arange(n + 1) / n  # k / n: 0 and 1 exactly at the ends
        self = cls(path, ik, us, np.empty((n + 1, len(q0))), np.asarray(q0, float).copy(),
                   np.asarray(q_extra_end, float), extra_mask)
        # The path starts where the robot is: q0 itself is the first sample (no IK, and no
        # rounding step between the previous motion's end and this one's start).
        seed = self.q[0] = self.extra_start
        if ik_path is not None:
            m = self.extra_mask
            seeds = np.broadcast_to(self.extra_start, (n, len(q0))).copy()
            seeds[:, m] = self.extra_start[m] + (self.extra_end[m] - self.extra_start[m]) * us[1:, None]
            solved = ik_path(path.poses(us[1:]), seeds)
            if solved is not None:
                self.q[1:] = solved
                return self
        for k in range(1, len(us)):
            u = float(us[k])
            seed = self._seed(seed, u)
            seed = self.q[k] = ik(path.pose(u), seed)
        return self

    def _seed(self, seed: Vec, u: float) -> Vec:
        s = np.array(seed, float)
        m = self.extra_mask
        s[m] = self.extra_start[m] + (self.extra_end[m] - self.extra_start[m]) * u
        return s

    def joints(self, u: float) -> Vec:
        """Joints at ``u``; the exact samples at the ends so the motion ends exactly on target."""
        if u <= 0.0:
            return self.q[0].copy()
        if u >= 1.0:
            return self.q[-1].copy()
        k = int(round(u * (len(self.u) - 1)))
        return (self.ik_between or self.ik)(self.path.pose(u), self._seed(self.q[k], u))

    def rates(self, u: np.ndarray, ud: np.ndarray, udd: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Joint velocities and accelerations (N×n) at path states (u, u̇, ü), by the chain rule
        ``q̇ = q' u̇``, ``q̈ = q' ü + q'' u̇²`` with ``q'``, ``q''`` of the nearest sample: the
        cheap estimate the blend planner bounds the overlap of two motions with."""
        h = float(self.u[1] - self.u[0])
        dq = _gradient(self.q, h)
        ddq = _gradient(dq, h)
        k = np.clip(np.rint(np.asarray(u) / h).astype(int), 0, len(self.u) - 1)
        ud, udd = np.asarray(ud)[:, None], np.asarray(udd)[:, None]
        return dq[k] * ud, dq[k] * udd + ddq[k] * ud * ud
