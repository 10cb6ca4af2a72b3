"""Which GPL thread runs on the calling Python thread: the one thread-local the runtime keeps.

A scheduler binds its record of a GPL thread (``gplrt.threads.scheduler.ThreadCtx``) to the Python
thread that runs it, for as long as it runs there; code anywhere in the runtime asks
:func:`current_ctx` who is calling (``checkpoint``, the waits, ``gplrt.session.current_session``).
None means a Python thread no scheduler runs (a notebook, a test).

It sits below both the scheduler and the session, which read it, so that neither depends on the
other's package to find the calling thread.
"""

from __future__ import annotations

import threading
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from gplrt.threads.scheduler import ThreadCtx

__all__ = ["bind_current", "current_ctx"]


class _Local(threading.local):
    ctx: ThreadCtx | None = None


#: The binding itself; the scheduler's hot paths (``checkpoint``) read ``_tls.ctx`` directly.
_tls = _Local()


def current_ctx() -> ThreadCtx | None:
    """The calling Python thread's scheduler record, or None for a thread unknown to the scheduler."""
    return _tls.ctx


def bind_current(ctx: ThreadCtx | None) -> None:
    """Bind ``ctx`` to the calling Python thread (None: unbind)."""
    _tls.ctx = ctx
