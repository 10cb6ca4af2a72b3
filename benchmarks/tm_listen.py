"""The simulated TM robot under a real client, and what a Listen-node packet costs to translate.

1. **Client session**: techmanpy 1.2 sends MOVES joint moves (``move_to_joint_angles_ptp`` at
   SPEED % then ``set_queue_tag(n, wait_for_completion=True)``: each move waited for) to a TM5-900
   Listen node on the fast clock, in this process; printed: the wall time of the session against
   the simulated motion time (the robot's ``sim_time``), medians of ``--runs`` sessions with their
   spread, as benchmarks/client_session.py does for TCS.
2. **Transpile cost per packet**: ``translate_packet`` (lexer, parser, checks, lowering: what the
   node does for every ``$TMSCT``) on packets of 1, 10 and 100 statements (declarations,
   arithmetic, a motion call); median µs per packet over ``--runs`` samples of 50 packets, with
   the spread, and in µR.

After each sample the reference workload R runs (benchmarks/_reference.py) and the figures are
printed once more normalised by R of the same turn.

    python benchmarks/tm_listen.py [--moves 50] [--speed 50] [--runs 5]
"""

from __future__ import annotations

import argparse
import asyncio
import statistics
import time

from _reference import HOW_TO_COMPARE, Reference, per_r, times_r

from gpl2py.tmscript.pipeline import translate_packet


def session(moves: int, speed: float) -> tuple[float, float, float]:
    """(wall s, CPU s, simulated motion s) of one client session on a fresh robot."""
    import techmanpy

    from gplrt.tm import context
    from gplrt.tm.listen import ListenNode

    from gpl2py.tmscript.pipeline import translate_packet

    robot = context.use_robot("TM5-900")
    node = ListenNode(robot, translate_packet, "127.0.0.1", 0).serve()
    techmanpy.TMSCT_client.PORT = node.port
    targets = ([0.0, 0.0, 90.0, 0.0, 90.0, 0.0], [45.0, -20.0, 110.0, 10.0, 60.0, 30.0])

    async def run() -> None:
        async with techmanpy.connect_sct(robot_ip="127.0.0.1") as sct:
            for i in range(moves):
                await sct.move_to_joint_angles_ptp(targets[(i + 1) % 2], speed / 100.0, 200)
                await sct.set_queue_tag(i % 15 + 1, wait_for_completion=True)
    w0, c0 = time.perf_counter(), time.process_time()
    asyncio.run(run())
    wall, cpu = time.perf_counter() - w0, time.process_time() - c0
    node.close()
    getattr(robot, "close", lambda: None)()  # (its session's threads; before issue 22's clock work, none)
    return wall, cpu, robot.sim_time


STATEMENTS = [
    "int n{i} = {i} * 3 + 1",
    "float f{i} = {i} / 2.5",
    'string s{i} = "p" + {i}',
    "int m{i} = ({i} > 10) ? {i} - 1 : {i}",
    'PTP("JPP",0,0,90,0,90,{i},50,200,0,false)',
]


def packet(count: int) -> str:
    return "\r\n".join(STATEMENTS[i % len(STATEMENTS)].format(i=i) for i in range(count))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--moves", type=int, default=50)
    parser.add_argument("--speed", type=float, default=50.0)
    parser.add_argument("--runs", type=int, default=5)
    args = parser.parse_args()
    ref = Reference()
    ref.run(record=False)
    walls, cpus, motion = [], [], 0.0
    for _ in range(args.runs):
        wall, cpu, motion = session(args.moves, args.speed)
        walls.append(wall)
        cpus.append(cpu)
        ref.run(match=wall)
    median = statistics.median(walls)
    print(f"techmanpy session, TM5-900, fast clock: {args.moves} PTP moves at {args.speed:g} %, each waited for "
          f"(QueueTag): {motion:.1f} s of simulated motion; wall time over {args.runs} sessions: median "
          f"{median:.3f} s (spread {min(walls):.3f}-{max(walls):.3f} s): {motion / median:.1f}x faster than the "
          f"robot; CPU {statistics.median(cpus):.3f} s (spread {min(cpus):.3f}-{max(cpus):.3f})")
    for what, times, refs in (("wall", walls, ref.wall), ("CPU ", cpus, ref.cpu)):
        in_r = per_r(times, refs)
        per_ref = times_r([motion / t for t in times], refs)
        print(f"  {what} time {statistics.median(in_r):.2f} R (spread {min(in_r):.2f}-{max(in_r):.2f}): "
              f"{statistics.median(per_ref):.2f} s of simulated motion per R (spread "
              f"{min(per_ref):.2f}-{max(per_ref):.2f})")
    texts = {n: packet(n) for n in (1, 10, 100)}
    for text in texts.values():
        assert not translate_packet(text).errors
    per: dict[int, list[float]] = {n: [] for n in texts}
    refs: dict[int, list[float]] = {n: [] for n in texts}
    for _ in range(args.runs):
        for n, text in texts.items():
            reps = 50
            t0 = time.perf_counter()
            for _ in range(reps):
                translate_packet(text)
            per[n].append((time.perf_counter() - t0) / reps)
            ref.run(match=per[n][-1] * reps)
            refs[n].append(ref.wall[-1])
    print("translate_packet (what the Listen node does per $TMSCT), median of "
          f"{args.runs} samples of 50 packets:")
    for n in texts:
        us = [t * 1e6 for t in per[n]]
        in_r = [x * 1e6 for x in per_r(per[n], refs[n])]
        print(f"  {n:3d} statements: {statistics.median(us):8.0f} µs per packet (spread {min(us):.0f}-{max(us):.0f}); "
              f"{statistics.median(in_r):.0f} µR (spread {min(in_r):.0f}-{max(in_r):.0f})")
    print(ref.line())
    print(HOW_TO_COMPARE)


if __name__ == "__main__":
    main()
