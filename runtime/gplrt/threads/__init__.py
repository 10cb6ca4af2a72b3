"""GPL threads on Python threads: the ``Thread`` class and the scheduler hooks.

* :class:`Thread` — GPL's Thread class (see ``gplrt.threads.thread`` for the decisions taken).
* :func:`paced` — the thread's checkpoints as an iterator: a transpiled ``While``/``Do`` loop is
  ``for _ in paced():``, one checkpoint per turn taken in C; a scheduling point when the thread's
  slice is used up or a Suspend/Abort is pending.
* :func:`checkpoint` — one checkpoint, for the loops the transpiler shapes otherwise (a ``For``
  over non-Integers, GoTo dispatch) and the runtime's own.
* :func:`paced_range` — ``range`` with a :func:`checkpoint` every 1024 iterations: the transpiler's
  Integer ``For`` loops, so a long loop gives other threads their turn without a call per step.
* :func:`external_wait` — context manager for every blocking call to the outside world (sockets,
  operator prompts), so the virtual scheduler lets other threads run and paces virtual time.
* ``gplrt.threads.scheduler`` — the VIRTUAL (deterministic token) and REAL schedulers.
"""

from gplrt.threads.scheduler import ThreadAbort, WaitQueue, checkpoint, external_wait, paced, paced_range
from gplrt.threads.thread import Thread, ThreadStateValue

__all__ = ["Thread", "ThreadStateValue", "ThreadAbort", "WaitQueue", "checkpoint", "external_wait", "paced",
           "paced_range"]
