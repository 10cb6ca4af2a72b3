"""Composition and inverse identities on 10,000 random poses, checked against scipy's intrinsic ZYZ.

The Location side runs the real GPL members (XYZ, Mul, Inverse, Pos through RefFrames, X..Roll);
the oracle side is an independent, vectorised numpy/scipy computation.  Tolerances: 1e-9 mm and
1e-9 degrees, away from the singular pitches 0/180 (those have their own tests).
"""

from __future__ import annotations

import numpy as np
import pytest
from numpy.typing import NDArray
from scipy.spatial.transform import Rotation

from gplrt.geometry import Location, RefFrame

N = 10_000
TOL = 1e-9
# Oracle poses whose pitch is this close to 0/180 are excluded from angle comparisons: there yaw and
# roll are only determined to ~eps/sin(pitch).
SINGULAR_MARGIN_DEG = 0.01


def _random_xyzypr(rng: np.random.Generator, n: int) -> NDArray[np.float64]:
    xyz = rng.uniform(-2000.0, 2000.0, size=(n, 3))
    yaw = rng.uniform(-180.0, 180.0, size=n)
    pitch = rng.uniform(0.0, 180.0, size=n)
    roll = rng.uniform(-180.0, 180.0, size=n)
    return np.column_stack([xyz, yaw, pitch, roll])


def _oracle_matrices(v: NDArray[np.float64]) -> NDArray[np.float64]:
    m = np.zeros((len(v), 4, 4))
    m[:, :3, :3] = Rotation.from_euler("ZYZ", v[:, 3:], degrees=True).as_matrix()
    m[:, :3, 3] = v[:, :3]
    m[:, 3, 3] = 1.0
    return m


def _oracle_xyzypr(m: NDArray[np.float64]) -> NDArray[np.float64]:
    eul = Rotation.from_matrix(m[:, :3, :3]).as_euler("ZYZ", degrees=True)
    return np.column_stack([m[:, :3, 3], eul])


def _locations(v: NDArray[np.float64]) -> list[Location]:
    out = []
    for row in v.tolist():
        loc = Location()
        loc.XYZ(*row)
        out.append(loc)
    return out


def _read(locs: list[Location]) -> NDArray[np.float64]:
    return np.array([(p.X, p.Y, p.Z, p.Yaw, p.Pitch, p.Roll) for p in locs])


def _assert_close(got: NDArray[np.float64], want: NDArray[np.float64]) -> None:
    """mm to TOL; angles to TOL on the circle; rows near the singular pitches skipped."""
    pitch = want[:, 4]
    regular = (pitch > SINGULAR_MARGIN_DEG) & (pitch < 180.0 - SINGULAR_MARGIN_DEG)
    assert regular.sum() > 0.99 * len(want)
    pos_err = np.max(np.abs(got[:, :3] - want[:, :3]))
    ang = got[regular, 3:] - want[regular, 3:]
    ang_err = np.max(np.abs((ang + 180.0) % 360.0 - 180.0))
    assert pos_err <= TOL, f"position error {pos_err} mm"
    assert ang_err <= TOL, f"angle error {ang_err} deg"
    assert np.all((got[:, 3] > -180.0) & (got[:, 3] <= 180.0))
    assert np.all((got[:, 4] >= 0.0) & (got[:, 4] <= 180.0))
    assert np.all((got[:, 5] > -180.0) & (got[:, 5] <= 180.0))


@pytest.fixture(scope="module")
def data() -> tuple[NDArray[np.float64], NDArray[np.float64], list[Location], list[Location]]:
    rng = np.random.default_rng(20260)
    va, vb = _random_xyzypr(rng, N), _random_xyzypr(rng, N)
    return va, vb, _locations(va), _locations(vb)


def test_matrices_match_the_oracle(data) -> None:  # type: ignore[no-untyped-def]
    va, _, la, _ = data
    want = _oracle_matrices(va)
    got = np.array([loc.matrix() for loc in la])
    assert np.max(np.abs(got - want)) <= TOL


def test_mul_matches_the_oracle(data) -> None:  # type: ignore[no-untyped-def]
    va, vb, la, lb = data
    want = _oracle_xyzypr(_oracle_matrices(va) @ _oracle_matrices(vb))
    got = _read([a.Mul(b) for a, b in zip(la, lb)])
    _assert_close(got, want)


def test_inverse_matches_the_oracle(data) -> None:  # type: ignore[no-untyped-def]
    va, _, la, _ = data
    want = _oracle_xyzypr(np.linalg.inv(_oracle_matrices(va)))
    _assert_close(_read([a.Inverse() for a in la]), want)


def test_a_times_inverse_is_identity(data) -> None:  # type: ignore[no-untyped-def]
    """A·A⁻¹ = I: reads (0,0,0,0,0,0) — the identity is a pitch-0 pose, so the rotation is all roll."""
    _, _, la, _ = data
    got = _read([a.Mul(a.Inverse()) for a in la] + [a.Inverse().Mul(a) for a in la])
    assert np.max(np.abs(got[:, :3])) <= TOL
    assert np.all(got[:, 3] == 0.0)
    assert np.max(np.abs(got[:, 4:])) <= TOL


def test_inverse_of_product_is_product_of_inverses(data) -> None:  # type: ignore[no-untyped-def]
    va, vb, la, lb = data
    lhs = _read([a.Mul(b).Inverse() for a, b in zip(la, lb)])
    rhs = _read([b.Inverse().Mul(a.Inverse()) for a, b in zip(la, lb)])
    want = _oracle_xyzypr(np.linalg.inv(_oracle_matrices(va) @ _oracle_matrices(vb)))
    _assert_close(lhs, want)
    _assert_close(rhs, want)


def test_pos_through_a_three_frame_chain_is_the_product(data) -> None:  # type: ignore[no-untyped-def]
    """loc -> f1 -> f2 -> f3: Pos = T(f3.Loc)·T(f2.Loc)·T(f1.Loc)·PosWrtRef(loc), on N chains."""
    va, vb, _, _ = data
    rng = np.random.default_rng(7)
    n = N
    v3, v2, v1, v0 = va[:n], vb[:n], _random_xyzypr(rng, n), _random_xyzypr(rng, n)
    got = []
    for r3, r2, r1, r0 in zip(v3.tolist(), v2.tolist(), v1.tolist(), v0.tolist()):
        f3, f2, f1 = RefFrame(), RefFrame(), RefFrame()
        f3.Loc.XYZ(*r3)
        f2.Loc.XYZ(*r2)
        f2.Loc.RefFrame = f3
        f1.Loc.XYZ(*r1)
        f1.Loc.RefFrame = f2
        loc = Location()
        loc.XYZ(*r0)
        loc.RefFrame = f1
        p = loc.Pos
        assert p.RefFrame is None
        got.append((p.X, p.Y, p.Z, p.Yaw, p.Pitch, p.Roll))
        # PosWrtRef is untouched by the chain
        assert (loc.X, loc.Y, loc.Z) == tuple(r0[:3])
    m = _oracle_matrices(v3) @ _oracle_matrices(v2) @ _oracle_matrices(v1) @ _oracle_matrices(v0)
    _assert_close(np.array(got), _oracle_xyzypr(m))


def test_pos_assignment_back_solves_through_the_frame(data) -> None:  # type: ignore[no-untyped-def]
    """loc.Pos = v with a RefFrame: PosWrtRef = T(frame)⁻¹·T(v), so loc.Pos reads v back."""
    va, vb, la, lb = data
    n = 2_000
    got = []
    for a, b in zip(la[:n], lb[:n]):
        f = RefFrame()
        f.Loc = a.Clone()
        loc = Location()
        loc.RefFrame = f
        loc.Pos = b
        p = loc.Pos
        got.append((p.X, p.Y, p.Z, p.Yaw, p.Pitch, p.Roll))
    want = _oracle_xyzypr(_oracle_matrices(vb[:n]))
    _assert_close(np.array(got), want)
    want_wrt = _oracle_xyzypr(np.linalg.inv(_oracle_matrices(va[:n])) @ _oracle_matrices(vb[:n]))
    f = RefFrame()
    f.Loc = la[0]
    loc = Location()
    loc.RefFrame = f
    loc.Pos = lb[0]
    _assert_close(np.array([(loc.X, loc.Y, loc.Z, loc.Yaw, loc.Pitch, loc.Roll)]), want_wrt[:1])


def test_distance_matches_numpy(data) -> None:  # type: ignore[no-untyped-def]
    va, vb, la, lb = data
    got = np.array([Location.Distance(a, b) for a, b in zip(la, lb)])
    want = np.linalg.norm(va[:, :3] - vb[:, :3], axis=1)
    assert np.max(np.abs(got - want)) <= TOL


# -- the singular pitches 0 and 180, on their own -------------------------------------------------------


def _singular_xyzypr(rng: np.random.Generator, n: int) -> NDArray[np.float64]:
    v = _random_xyzypr(rng, n)
    v[:, 4] = rng.choice([0.0, 180.0], size=n)
    return v


def _matrix_of_readback(loc: Location) -> NDArray[np.float64]:
    """The transform the six values read from ``loc`` describe (rebuilt by the oracle)."""
    return _oracle_matrices(np.array([[loc.X, loc.Y, loc.Z, loc.Yaw, loc.Pitch, loc.Roll]]))[0]


def test_singular_products_and_inverses_follow_the_documented_rule() -> None:
    """At pitch 0/180 yaw and roll are not separable: the computed result reads yaw 0, pitch exactly
    0 or 180, and the six values it reads describe the oracle's transform to 1e-9."""
    rng = np.random.default_rng(180)
    n = 2_000
    va, vb = _singular_xyzypr(rng, n), _singular_xyzypr(rng, n)
    la, lb = _locations(va), _locations(vb)
    ma, mb = _oracle_matrices(va), _oracle_matrices(vb)
    cases = [(a.Mul(b), ma[i] @ mb[i]) for i, (a, b) in enumerate(zip(la, lb))]
    cases += [(a.Inverse(), np.linalg.inv(ma[i])) for i, a in enumerate(la)]
    for loc, want in cases:
        assert loc.Yaw == 0.0 and loc.Pitch in (0.0, 180.0)
        assert np.max(np.abs(_matrix_of_readback(loc) - want)) <= TOL
    # A·A⁻¹ = I reads exactly zero orientation at a singular pose too
    for a in la[:200]:
        p = a.Mul(a.Inverse())
        assert (p.Yaw, p.Pitch) == (0.0, 0.0) and abs(p.Roll) <= TOL
        assert max(abs(p.X), abs(p.Y), abs(p.Z)) <= TOL


def test_written_singular_angles_read_back_but_compose_as_the_matrix() -> None:
    """Written values read back as written (issue: X..Roll round-trip), while every computation uses
    the transform they define — so Pos through a frame at a singular pose matches the oracle."""
    rng = np.random.default_rng(0)
    v = _singular_xyzypr(rng, 500)
    frames = _random_xyzypr(rng, 500)
    for row, fr in zip(v.tolist(), frames.tolist()):
        loc = Location()
        loc.XYZ(*row)
        assert [loc.X, loc.Y, loc.Z, loc.Yaw, loc.Pitch, loc.Roll] == [c + 0.0 for c in row]
        f = RefFrame()
        f.Loc.XYZ(*fr)
        loc.RefFrame = f
        want = _oracle_matrices(np.array([fr]))[0] @ _oracle_matrices(np.array([row]))[0]
        assert np.max(np.abs(loc.matrix() - want)) <= TOL
