"""Serve PyLabRobot: a PyLabRobot script drives the vendor's TCP Command Server on a simulated PF400.

The server is Precise Automation's TCP Command Server (TCS 3.0C1 with the PARobot plug-in),
unchanged, run by gpl2py on a simulated PF400SX; the client is PyLabRobot's own
``PreciseFlex400Backend``, exactly as it drives a real arm.  From the repository root, with
``.venv`` active (``bash scripts/test.sh`` or ``bash scripts/demo.sh`` make it), and ``TCS`` the
folder of TCS with the PARobot plug-in (not in this repository: the README's *The real code the
tests use* says where to get it; ``$GPL_CORPUS/tcs-3.0C1-pa`` where the tests find it):

    gpl2py run "$TCS" --robot PF400SX --clock fast
    python samples/pylabrobot/arm_session.py            # in a second terminal

The first command serves robot 1 on port 10100 and the status port on 10000 (stop it with
Ctrl-C).  ``--clock fast`` lets a client that waits for a motion (``waitForEom``, which
PyLabRobot's ``get_joint_position`` sends) get its reply without waiting out the motion in wall
time; docs/design/clock.md says when that is safe.  ``--moves N`` sets how many moves to make.
"""

from __future__ import annotations

import argparse
import asyncio
import time

from pylabrobot.arms.precise_flex import PreciseFlex400Backend
from pylabrobot.arms.precise_flex.joints import PFAxis

# Two joint poses of a PF400: Z (mm), shoulder, elbow, wrist (degrees), gripper (mm).
POSES = [(300.0, 10.0, 90.0, -100.0, 90.0), (250.0, -20.0, 110.0, -80.0, 90.0)]


async def session(host: str, port: int, moves: int) -> None:
    arm = PreciseFlex400Backend(host, port)
    await arm.setup()  # PC mode, high power, attach, home
    print("connected:", await arm.get_version())
    await arm.set_speed(50)
    print("profile 1 speed:", await arm.get_speed(), "%")
    start = time.monotonic()
    for i in range(moves):
        await arm.move_j(1, dict(zip(PFAxis, POSES[i % 2])))
        joints = await arm.get_joint_position()  # waits for the end of the move, then reads
    wall = time.monotonic() - start
    print(f"{moves} moves in {wall:.1f} s of wall time; now at",
          " ".join(f"{joints[axis]:.3f}" for axis in PFAxis if axis != PFAxis.RAIL))
    print("tool at", await arm.get_cartesian_position())
    await arm.stop()  # release the arm, power off, close the connection


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--host", default="127.0.0.1")
    parser.add_argument("--port", type=int, default=10100, help="TCS robot 1 port (default 10100)")
    parser.add_argument("--moves", type=int, default=10)
    args = parser.parse_args()
    asyncio.run(session(args.host, args.port, args.moves))


if __name__ == "__main__":
    main()
