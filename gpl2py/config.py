"""``[tool.gpl2py]`` in ``pyproject.toml``: a repository's defaults for the ``gpl2py`` command.

```toml
[tool.gpl2py]
paths = ["cells/palletiser", "cells/feeder"]   # check/translate with no PATH
robot = "PF400SX"                              # run --robot
clock = "virtual"                              # run --clock
stubs = "sim/stubs"                            # --stubs (relative to this file's folder)
strict = false                                 # --strict
select = ["GPL"]                               # --select
ignore = ["GPL1003", "GPL35"]                  # --ignore
max-source-mb = 8                              # --max-source-mb
```

Where it is found (decision): the first ``pyproject.toml`` that has a ``[tool.gpl2py]`` table, in
the **current folder** or one of its parents (mypy's and pytest's rule; a pre-commit hook runs at
the repository's root).  Never from the folder of a project given on the command line: a project
is untrusted input (docs/security.md), while this table can name ``stubs``, Python that ``run``
executes -- it is trusted like the command line, so it comes from where the user works.
``--config FILE`` names one; ``--no-config`` reads none.  A command-line option always wins over
the table.

Anything wrong (not TOML, an unknown key, a value of the wrong type) is a :class:`ConfigError`:
the command stops with GPL9003 and status 2, as for a wrong command line, before it reads a
project.  A ``pyproject.toml`` that does not mention gpl2py is skipped unparsed.
"""

from __future__ import annotations

import difflib
import math
from dataclasses import dataclass
from pathlib import Path

FILE_NAME = "pyproject.toml"
CLOCKS = ("virtual", "fast", "real")
#: Every key of the table and the type of its value.
KEYS = {
    "paths": "a list of paths",
    "robot": "a robot model name",
    "clock": "one of " + ", ".join(CLOCKS),
    "stubs": "a folder",
    "strict": "true or false",
    "select": "a list of codes or prefixes",
    "ignore": "a list of codes or prefixes",
    "max-source-mb": "a positive number",
}


class ConfigError(Exception):
    """The configuration file is wrong; ``path`` names it, ``detail`` says what is wrong."""

    def __init__(self, path: Path, detail: str) -> None:
        super().__init__(f"{path}: {detail}")
        self.path = path
        self.detail = detail


@dataclass(frozen=True)
class Config:
    """The table's values (None: not given); paths are made relative to the file's folder."""

    path: Path | None = None
    paths: tuple[str, ...] = ()
    robot: str | None = None
    clock: str | None = None
    stubs: str | None = None
    strict: bool | None = None
    select: tuple[str, ...] | None = None
    ignore: tuple[str, ...] | None = None
    max_source_mb: float | None = None


def find(start: Path) -> Path | None:
    """The first pyproject.toml with a ``[tool.gpl2py]`` table in ``start`` or above it."""
    for folder in (start, *start.parents):
        candidate = folder / FILE_NAME
        try:
            if not candidate.is_file():
                continue
            text = candidate.read_text(encoding="utf-8", errors="replace")
        except OSError:
            continue
        if "gpl2py" not in text:
            continue  # another tool's file: not even parsed
        import tomllib  # (here: a command run where no file mentions gpl2py never imports it)

        try:
            data = tomllib.loads(text)
        except tomllib.TOMLDecodeError as exc:
            raise ConfigError(candidate, f"not valid TOML: {exc}") from None
        if isinstance(data.get("tool"), dict) and "gpl2py" in data["tool"]:
            return candidate
    return None


def load(path: Path) -> Config:
    """The ``[tool.gpl2py]`` table of ``path`` (an empty Config when the file has none)."""
    import tomllib

    try:
        data = tomllib.loads(path.read_text(encoding="utf-8"))
    except OSError as exc:
        raise ConfigError(path, f"cannot read it: {exc.strerror or exc}") from None
    except (tomllib.TOMLDecodeError, UnicodeDecodeError) as exc:
        raise ConfigError(path, f"not valid TOML: {exc}") from None
    table = data.get("tool", {}).get("gpl2py", {}) if isinstance(data.get("tool"), dict) else {}
    if not isinstance(table, dict):
        raise ConfigError(path, "[tool.gpl2py] must be a table")
    for key in table:
        if key not in KEYS:
            close = difflib.get_close_matches(key.replace("_", "-"), list(KEYS), n=1, cutoff=0.6)
            hint = f"; did you mean {close[0]!r}?" if close else f" (the keys: {', '.join(KEYS)})"
            raise ConfigError(path, f"[tool.gpl2py] has no key {key!r}{hint}")
    base = path.parent

    def value(key: str, kind: type | tuple[type, ...]) -> object:
        v = table.get(key)
        if v is not None and (not isinstance(v, kind) or (kind is not bool and isinstance(v, bool))):
            raise ConfigError(path, f"[tool.gpl2py] {key} = {v!r}: must be {KEYS[key]}")
        return v

    def strings(key: str) -> tuple[str, ...] | None:
        v = table.get(key)
        if v is None:
            return None
        if isinstance(v, str):
            v = [v]
        if not isinstance(v, list) or not all(isinstance(x, str) for x in v):
            raise ConfigError(path, f"[tool.gpl2py] {key} = {v!r}: must be {KEYS[key]}")
        return tuple(v)

    clock = value("clock", str)
    if clock is not None and clock not in CLOCKS:
        raise ConfigError(path, f"[tool.gpl2py] clock = {clock!r}: must be {KEYS['clock']}")
    mb = value("max-source-mb", (int, float))
    if mb is not None and not 0 < float(mb) < math.inf:  # type: ignore[arg-type]
        raise ConfigError(path, f"[tool.gpl2py] max-source-mb = {mb!r}: must be {KEYS['max-source-mb']}")
    stubs = value("stubs", str)
    return Config(
        path=path,
        paths=tuple(str(base / p) for p in strings("paths") or ()),
        robot=value("robot", str),  # type: ignore[arg-type]
        clock=clock,  # type: ignore[arg-type]
        stubs=str(base / stubs) if isinstance(stubs, str) else None,
        strict=value("strict", bool),  # type: ignore[arg-type]
        select=strings("select"),
        ignore=strings("ignore"),
        max_source_mb=float(mb) if mb is not None else None,  # type: ignore[arg-type]
    )


def discover(explicit: str | None, disabled: bool, cwd: Path | None = None) -> Config:
    """The configuration a command uses: ``--config FILE``, else the one :func:`find` finds from
    the current folder, else none (also with ``--no-config``)."""
    if disabled:
        return Config()
    if explicit is not None:
        path = Path(explicit)
        if not path.is_file():
            raise ConfigError(path, "no such file" if not path.exists() else "not a file")
        return load(path)
    found = find((cwd or Path.cwd()).absolute())
    return load(found) if found is not None else Config()


__all__ = ["Config", "ConfigError", "discover", "find", "load"]
