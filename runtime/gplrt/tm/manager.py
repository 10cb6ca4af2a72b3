"""The simulated TMmanager (Techman's Robot Management System) that ``VarSync`` pushes variables to
(manual L7626-L7706), and the name lookup ``VarSync`` and ``GetVarValue`` share (L6650).

A robot's manager is ``Robot.manager`` (one per simulated robot, in its session): it records
every variable object it receives -- ``received`` in order, ``variables`` the last value of each
name -- so a notebook or a test reads what a script synchronised.  ``enabled = False`` is a
robot whose TMmanager function is off (``VarSync`` returns -1); ``fail_next = n`` makes the next
``n`` sends fail (the manager unreachable), which ``VarSync`` retries as the manual says.

Names are resolved at run time in the variables visible where the call is written: the front end
passes them (``scope``), as a map from the TMscript name to its value.
"""

from __future__ import annotations

import threading
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

#: The retry interval when none is given or a negative one is (L7626: "The default value,
#: 1000ms, will be applied").
DEFAULT_INTERVAL_MS = 1000


@dataclass(frozen=True)
class Sync:
    """One successful ``VarSync`` send: controller time (s) and the variables sent, name -> value."""

    time: float
    values: dict[str, Any]


@dataclass
class TMManager:
    """What the simulated TMmanager received (see the module docstring)."""

    enabled: bool = True
    #: Sends that fail from now on (each a try ``VarSync`` retries after its interval).
    fail_next: int = 0
    received: list[Sync] = field(default_factory=list)
    attempts: int = 0

    def __post_init__(self) -> None:
        self._lock = threading.Lock()

    def send(self, time: float, values: dict[str, Any]) -> bool:
        """One try: True when the manager took ``values`` (recorded), False when it failed."""
        with self._lock:
            self.attempts += 1
            if self.fail_next > 0:
                self.fail_next -= 1
                return False
            self.received.append(Sync(time, dict(values)))
            return True

    @property
    def variables(self) -> dict[str, Any]:
        """The last value received of each variable name."""
        with self._lock:
            out: dict[str, Any] = {}
            for sync in self.received:
                out.update(sync.values)
            return out


def lookup(name: str, scope: dict[str, Any] | None, node: Any) -> tuple[bool, Any]:
    """(found, value) of the variable called ``name`` (spaces around it ignored): in ``scope``
    (the variables visible at the call), else a Listen node's variables."""
    key = name.strip()
    if scope is not None and key in scope:
        return True, scope[key]
    if node is not None and key and hasattr(node.vars, key):
        return True, getattr(node.vars, key)
    return False, None


def _names(value: Any) -> list[str] | None:
    """The names a ``VarSync`` argument gives: a string, or each string of a string array; None
    for anything else (an invalid parameter)."""
    if isinstance(value, str):
        return [value]
    if isinstance(value, list) and all(isinstance(x, str) for x in value):
        return list(value)
    return None


def _is_int(value: Any) -> bool:
    return isinstance(value, int) and not isinstance(value, bool)


def var_sync(args: tuple[Any, ...], scope: dict[str, Any] | None, robot: Any, node: Any,
             sleep: Callable[[int], bool]) -> int:
    """``VarSync([retries [, intervalMs],] names...)`` (L7626): send the variables named to
    ``robot``'s TMmanager, retrying a failed send after ``sleep(intervalMs)`` (controller time;
    false: interrupted) up to ``retries`` sends (<= 0: until it succeeds).  Returns the number of
    sends made when one succeeded, 0 when every try failed or none of the names is a variable
    (nothing sent), -1 when the TMmanager function is not enabled, -9 for invalid parameters (no
    name, or a name that is not a string or string array).  ``node``: the Listen node whose
    variables count too, or None."""
    rest = list(args)
    retries, interval = 0, DEFAULT_INTERVAL_MS
    if rest and _is_int(rest[0]):
        retries = rest.pop(0)
        if rest and _is_int(rest[0]):
            interval = rest.pop(0)
            if interval < 0:
                interval = DEFAULT_INTERVAL_MS
    names: list[str] = []
    for value in rest:
        found = _names(value)
        if found is None:
            return -9
        names.extend(found)
    if not names:
        return -9
    manager = robot.manager
    if not manager.enabled:
        return -1
    values: dict[str, Any] = {}
    for name in names:
        ok, value = lookup(name, scope, node)
        if ok:
            values[name.strip()] = list(value) if isinstance(value, list) else value
    if not values:
        return 0
    sends = 0
    while True:
        sends += 1
        if manager.send(robot.clock.now(), values):
            return sends
        if 0 < retries <= sends:
            return 0
        if not sleep(interval):
            return 0
