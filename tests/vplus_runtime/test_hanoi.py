"""robot-sandbox demos/hanoi.v2, hand-lowered onto gplrt.vplus: recursion whose location arguments
are references to the caller's variables (SET vf.src = SHIFT(vf.src BY ...) moves the caller's
stack), on a simulated 6-axis arm; the globals a V+ data file would load (p1, dx, dz, #safe, n, ang)
are supplied with values the arm can reach."""

from __future__ import annotations

import pytest

from gplrt import vplus as vp
from gplrt.sim import Simulation
from gplrt.vplus.transforms import components

G = vp.G
TOL = 1e-6
REACHED: list[tuple[tuple[float, ...], tuple[float, ...]]] = []


@vp.program("hanoi")
def hanoi() -> None:
    vf_a, vf_v, vf_c = vp.Cell("vf.a"), vp.Cell("vf.v"), vp.Cell("vf.c")  # AUTO vf.a, vf.v, vf.c
    vf_a.v = vp.shift(G["p1"].v, 0, 0, vp.mul(G["dz"].v, G["n"].v))
    G["vf.b"].v = vp.compose(vp.rz(G["ang"].v), vp.trans(G["dx"].v, 0, 0), vp.rz(vp.neg(G["ang"].v)), G["p1"].v)
    vf_c.v = vp.compose(vp.rz(G["ang"].v), vp.trans(vp.mul(2, G["dx"].v), 0, 0), vp.rz(vp.neg(G["ang"].v)),
                        G["p1"].v)
    vp.speed(100, always=True)
    vp.open_()
    vp.move(G["#safe"].v)
    vp.break_()
    muta_discuri(vf_a, G["vf.b"], vf_c, G["n"])
    vp.move(G["#safe"].v)


@vp.program("muta.discuri")
def muta_discuri(vf_src: vp.Ref, vf_dst: vp.Ref, vf_aux: vp.Ref, n: vp.Ref) -> None:
    if vp.truth(vp.eq(n.v, 1)):
        muta_un_disc(vf_src, vf_dst)
    else:
        muta_discuri(vf_src, vf_aux, vf_dst, vp.byval(vp.sub(n.v, 1)))
        muta_un_disc(vf_src, vf_dst)
        muta_discuri(vf_aux, vf_dst, vf_src, vp.byval(vp.sub(n.v, 1)))


@vp.program("muta.un.disc")
def muta_un_disc(vf_src: vp.Ref, vf_dst: vp.Ref) -> None:
    vf_src.v = vp.shift(vf_src.v, 0, 0, vp.neg(G["dz"].v))
    pick_place(vf_src, vf_dst)
    vf_dst.v = vp.shift(vf_dst.v, 0, 0, G["dz"].v)


@vp.program("pick.place")
def pick_place(pick: vp.Ref, place: vp.Ref) -> None:
    z_pick, z_place = vp.Cell("z_pick"), vp.Cell("z_place")
    z_pick.v = 80
    z_place.v = 80
    vp.parameter_set("HAND.TIME", 0.2)
    vp.appro(pick.v, z_pick.v)
    vp.speed(50)
    vp.moves(pick.v)
    vp.closei()
    REACHED.append((components(vp.here()), components(pick.v)))
    vp.speed(50)
    vp.departs(z_pick.v)
    vp.parameter_set("HAND.TIME", 0)
    vp.appro(place.v, z_place.v)
    vp.speed(50)
    vp.moves(place.v)
    vp.openi()
    REACHED.append((components(vp.here()), components(place.v)))
    vp.speed(50)
    vp.departs(z_place.v)


@pytest.mark.parametrize("n", [1, 3])
def test_hanoi_moves_every_disc_and_the_caller_locations_follow(n: int) -> None:
    REACHED.clear()
    sim = Simulation(robot="ARM6", capture=True)

    def main() -> None:
        # what the demo's data file would hold: a start pose and a first peg the arm reaches
        G["#safe"].v = vp.p_ppoint(20, -10, 40, 0, 60, 0)
        vp.move(G["#safe"].v)
        vp.break_()
        G["p1"].v = vp.shift(vp.here(), 30, -40, -80)
        G["dx"].v, G["dz"].v, G["n"].v, G["ang"].v = 60, 20, n, 0
        start_b = G["p1"].v
        hanoi()
        vp.type_("vf.b ", vp.s_encode(*[round(v, 6) for v in components(G["vf.b"].v)]))
        vp.type_("expected ", vp.s_encode(*[round(v, 6) for v in components(
            vp.shift(vp.compose(vp.trans(60, 0, 0), start_b), 0, 0, 20 * n))]))

    with sim:
        assert sim.run_main(main) == [], sim.console.log_text
    assert sim.console.log_text == ""
    lines = sim.console.output.splitlines()
    assert lines[0].split(" ", 1)[1] == lines[1].split(" ", 1)[1]  # all n discs ended on peg b
    assert len(REACHED) == 2 * (2 ** n - 1)  # a pick and a place per move
    for got, want in REACHED:
        assert got == pytest.approx(want, abs=TOL)
    closes = [c for c in sim.io.output_trace() if c.signal == 2 and c.value]
    assert len(closes) == 2 ** n - 1
    sim.close()
