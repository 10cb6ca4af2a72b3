"""V+ system parameters and switches (L5602-5920, spec §3.14), per session.

Names are matched case-insensitively and may be abbreviated to a unique prefix (L5606-5608).
"""

from __future__ import annotations

from typing import Any

from gplrt.vplus.errors import ILLEGAL_VALUE, UNDEFINED_NAME, VError
from gplrt.vplus.values import session_data

PARAMETERS: dict[str, float] = {
    "BELT.MODE": 0.0,
    "HAND.TIME": 0.05,
    "KERMIT.RETRY": 15.0,
    "KERMIT.TIMEOUT": 8.0,
    "NOT.CALIBRATED": 0.0,  # [D] the simulated robot is calibrated
    "SCREEN.TIMEOUT": 0.0,
    "TERMINAL": 4.0,
}

SWITCHES: dict[str, bool] = {
    "AUTO.POWER.OFF": False,
    "BELT": False,
    "CP": True,
    "DECEL.100": False,
    "DRY.RUN": False,
    "FORCE": False,
    "INTERACTIVE": True,
    "MCP.MESSAGES": False,
    "MCS.MESSAGES": False,
    "MESSAGES": True,
    "MONITORS": False,
    "POWER": True,  # [D] the simulated robot starts powered (a V+ program cannot press the button)
    "SET.SPEED": True,
    "TRACE": False,
    "UPPER": True,
}


def _resolve(name: str, table: dict[str, Any]) -> str:
    key = name.strip().upper()
    if key in table:
        return key
    hits = [k for k in table if k.startswith(key)]
    if len(hits) == 1:
        return hits[0]
    raise VError(UNDEFINED_NAME, detail=name if not hits else f"{name} is ambiguous: {', '.join(hits)}")


def _tables() -> tuple[dict[str, float], dict[str, bool]]:
    data = session_data()
    if "parameters" not in data.extra:
        data.extra["parameters"] = dict(PARAMETERS)
        data.extra["switches"] = dict(SWITCHES)
    return data.extra["parameters"], data.extra["switches"]


def parameter(name: str) -> float:
    params, _ = _tables()
    return params[_resolve(name, params)]


def parameter_set(name: str, value: Any) -> None:
    params, _ = _tables()
    key = _resolve(name, params)
    value = float(value)
    if value < 0:
        raise VError(ILLEGAL_VALUE, detail=f"PARAMETER {key} = {value}")
    if key == "HAND.TIME":
        value = round(value / 0.016) * 0.016  # a multiple of 16 ms (L5670-5682)
    params[key] = value


def switch(name: str) -> float:
    _, sw = _tables()
    return -1.0 if sw[_resolve(name, sw)] else 0.0


def switch_set(name: str, value: Any) -> None:
    _, sw = _tables()
    sw[_resolve(name, sw)] = value != 0


def enable(*names: str) -> None:
    for n in names:
        switch_set(n, -1.0)


def disable(*names: str) -> None:
    for n in names:
        switch_set(n, 0.0)
