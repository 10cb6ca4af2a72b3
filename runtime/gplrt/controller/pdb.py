"""The controller's parameter database (PDb), loaded from ``.pac`` files like a real controller.

A Precise controller keeps its configuration in ``/flash/config/*.pac`` (robot-models.md §1): one
record per DataID, keyed by ``(DataID, unit, unit2)`` and holding a list of numbers or a list of
strings.  This module parses that format exactly (§1.2–1.3), layers files (later files override
earlier ones for the same key, §1.4), and serves typed reads and checked writes.  It is the data
source both for ``Controller.PDb`` / ``Controller.PDbNum`` (gplrt/controller/services.py) and for the
kinematic modules (``gplrt.motion.kinematics.build_model``), which read link lengths, limits and
axis masks from here instead of keeping constants of their own.

Key normalisation (robot-models.md §1.4 [INF]): the files write unit 1 as ``0`` and unit2 1 as
``0``; every key is stored with 0 turned into 1, and every public method does the same with its
arguments, so ``get(2000)``, ``get(2000, 0)`` and ``get(2000, 1)`` are the same read.  Records in
``robotNN.pac``, ``calibNN.pac`` and ``diomotionNN.pac`` belong to robot ``NN``.

GPL access surface (gpl-dictionary.md ``Controller.PDb``/``PDbNum``):

* ``pdb_text(data_id, unit, unit2, index=0) -> str`` — ``PDb`` get: index 0 = all elements joined
  by ``","`` (our choice of separator: the manual says "all values" without giving the format);
* ``set_pdb_text(text, data_id, unit, unit2, index=0, key=0)`` — ``PDb`` set;
* ``pdb_num(data_id, unit, unit2, index=1) -> float`` — ``PDbNum`` get (index default 1);
* ``set_pdb_num(value, data_id, unit, unit2, index=1, key=0)`` — ``PDbNum`` set.

Errors are ``GplException`` with the controller's codes: -1501 *Unknown Data ID code* (no such
DataID anywhere), -1509 *Invalid data index* (DataID exists, but not for this unit/unit2),
-1514 *Invalid parameter array index*, -209 *Read only*, -208 *Protection error* (a protected
robot-configuration DataID written without a key), -202 *Invalid argument* (a string where a
number is needed, or a whole-array write with the wrong element count), -1515 *Invalid data file
format* (bad ``.pac`` text; the detail starts with ``file:line``) and -1520 *Can't open parameter
DB file*.

Write listeners: ``ParameterDatabase.listeners`` are called as ``listener(data_id, unit, unit2)``
after every value change (GPL writes, ``set``, ``define``, layering more ``.pac`` text).  The
motion runtime registers one (``gplrt.motion.registry``) so that a written speed or acceleration
DataID reaches the limits later motions use; the database itself knows nothing of motion.
Listeners belong to one live database and are not copied by :meth:`ParameterDatabase.copy`.

Live DataIDs: some DataIDs are not stored values but the controller's own state (the GPL version,
the power state, a robot's trajectory mode, an axis's output torque) or commands (writing 213
homes the robots).  ``ParameterDatabase.live`` maps such a DataID to a :class:`LiveParameter`
whose ``read`` gives the present values and whose ``write`` acts on a GPL write (after the value
is checked and stored).  The controller registers them on the session's database
(``gplrt.controller.live_pdb``); the database only calls them, and, like listeners, they are
not copied.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, field
from pathlib import Path

from gplrt.controller.urdf_catalogue import URDF_ROBOTS, pdb_layers
from gplrt.lang.conversions import to_double
from gplrt.lang.errors import (
    CANT_OPEN_PARAMETER_DB,
    INVALID_ARGUMENT,
    INVALID_DATA_FILE_FORMAT,
    INVALID_DATA_INDEX,
    INVALID_PARAMETER_ARRAY_INDEX,
    INVALID_ROBOT_TYPE,
    PROTECTION_ERROR,
    READ_ONLY,
    UNKNOWN_DATA_ID,
    GplException,
    host_reason,
)


#: DataIDs the controller reports but never lets a program change: manufacturer, model, hardware
#: and software version fields (100–108, read-only per gpl-dictionary §13.4), controller serial
#: (110), power-on hours (136), auto-execution state (230) and power state (234), which the
#: controller itself maintains.
READ_ONLY_IDS: frozenset[int] = frozenset({*range(100, 109), 110, 136, 230, 234})

#: Robot-configuration DataIDs that need the ``key`` argument of ``Controller.PDb`` to change
#: (gpl-dictionary: "key ... overrides robot-configuration protection").  Which DataIDs a real
#: controller protects is not published; we protect the ones that redefine the robot itself:
#: robot types (116), axis count/mask/extra axes/model (2000–2004, 2007, 2008), kinematic
#: constants (16050) and hard stops (16075, 16076).  Any non-zero key unlocks them.
PROTECTED_IDS: frozenset[int] = frozenset({116, 2000, 2001, 2003, 2004, 2007, 2008, 16050, 16075, 16076})

_PER_ROBOT_FILE = re.compile(r"^(robot|calib|diomotion)(\d+)\.pac$", re.IGNORECASE)
_FILE_ORDER = ("controller", "robot", "calib", "diomotion", "gpl_vars")

Value = float | str


@dataclass
class PdbEntry:
    """One DataID instance: its values plus where they came from (for diagnostics)."""

    data_id: int
    unit: int
    unit2: int
    label: str
    values: list[Value]
    is_string: bool
    origin: str = "<set>"


@dataclass(frozen=True)
class PacRecord:
    """A parsed ``DI:`` record, before unit normalisation."""

    data_id: int
    unit: int
    unit2: int
    index: int
    label: str
    values: list[Value]
    is_string: bool
    line: int


@dataclass
class LiveParameter:
    """A DataID the controller maintains rather than stores (module docstring, "Live DataIDs").

    ``read(unit, unit2)`` gives the present values; ``units()`` the units that have the DataID
    (robot numbers; default: unit 1 only); ``write(unit, unit2, values)``, if any, is what the
    controller does when a program writes it (None: the DataID is read-only, -209)."""

    label: str
    read: Callable[[int, int], list[Value]]
    write: Callable[[int, int, list[Value]], None] | None = None
    units: Callable[[], Iterable[int]] | None = None
    is_string: bool = False


# -- parsing ------------------------------------------------------------------------------------

_TOKEN = re.compile(
    r"""\s*(?:
        (?P<string>"[^"\n]*")
      | (?P<number>[+-]?(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][+-]?\d+)?)
      | (?P<punct>[,=])
    )""",
    re.VERBOSE,
)


def _pac_error(where: str, message: str) -> GplException:
    return GplException(INVALID_DATA_FILE_FORMAT, detail=f"{where}: {message}")


def _ends_with_comma(line: str, where: str) -> bool:
    """Whether the last non-blank character outside quotes is ``,`` (a continued record)."""
    in_string = False
    last = ""
    for ch in line:
        if ch == '"':
            in_string = not in_string
            last = ch
        elif not in_string and not ch.isspace():
            last = ch
    if in_string:
        raise _pac_error(where, "unterminated string")
    return last == ","


def _tokenize(text: str, where: str) -> list[tuple[str, str]]:
    tokens: list[tuple[str, str]] = []
    pos = 0
    text = text.rstrip()
    while pos < len(text):
        m = _TOKEN.match(text, pos)
        if not m or m.end() == pos:
            raise _pac_error(where, f"unexpected text {text[pos:].strip()[:20]!r}")
        kind = m.lastgroup or ""
        tokens.append((kind, m.group(kind)))
        pos = m.end()
    return tokens


def _parse_record(text: str, line: int, where: str) -> PacRecord:
    """Parse ``DI: id, unit, unit2, index, "label" = v1, v2, ...`` (continuations already joined)."""
    tokens = _tokenize(text[3:], where)
    ints: list[int] = []
    i = 0
    for n in range(4):
        if i >= len(tokens) or tokens[i][0] != "number" or not tokens[i][1].isdigit():
            raise _pac_error(where, f"expected an unsigned integer for field {n + 1} (DataID, unit, unit2, index)")
        ints.append(int(tokens[i][1]))
        if i + 1 >= len(tokens) or tokens[i + 1][1] != ",":
            raise _pac_error(where, f"expected ',' after field {n + 1}")
        i += 2
    if i >= len(tokens) or tokens[i][0] != "string":
        raise _pac_error(where, "expected a quoted label")
    label = tokens[i][1][1:-1]
    if i + 1 >= len(tokens) or tokens[i + 1][1] != "=":
        raise _pac_error(where, "expected '=' after the label")
    i += 2
    values: list[Value] = []
    kinds: set[str] = set()
    expect_value = True
    for kind, tok in tokens[i:]:
        if expect_value:
            if kind == "string":
                values.append(tok[1:-1])
            elif kind == "number":
                values.append(float(tok))
            else:
                raise _pac_error(where, f"expected a value, found {tok!r}")
            kinds.add(kind)
        elif tok != ",":
            raise _pac_error(where, f"expected ',' between values, found {tok!r}")
        expect_value = not expect_value
    if not values:
        raise _pac_error(where, "empty value list")
    if expect_value:
        raise _pac_error(where, "value list ends with ','")
    if len(kinds) > 1:
        raise _pac_error(where, "numbers and strings mixed in one value list")
    return PacRecord(ints[0], ints[1], ints[2], ints[3], label, values, "string" in kinds, line)


def parse_pac(text: str, filename: str = "<pac>") -> list[PacRecord]:
    """Parse the text of one ``.pac`` file (robot-models.md §1.3); raises -1515 with file:line."""
    records: list[PacRecord] = []
    lines = text.replace("\r\n", "\n").replace("\r", "\n").split("\n")
    state = "head"  # head -> body -> tail
    pending: list[str] = []
    pending_line = 0
    for lineno, raw in enumerate(lines, start=1):
        where = f"{filename}:{lineno}"
        line = raw.replace("\t", " ")
        stripped = line.strip()
        if pending:
            if not stripped or not line[0].isspace():
                raise _pac_error(where, "record continues after ',' but the next line is not a continuation line")
            pending.append(stripped)
            if not _ends_with_comma(stripped, where):
                records.append(_parse_record(" ".join(pending), pending_line, f"{filename}:{pending_line}"))
                pending = []
            continue
        if not stripped or stripped.startswith("'"):
            continue
        if state == "head":
            m = re.fullmatch(r"Begin:\s*(\S+)", stripped)
            if not m:
                raise _pac_error(where, "expected 'Begin: 1.0' before the data")
            if m.group(1) != "1.0":
                raise _pac_error(where, f"unsupported format version {m.group(1)!r} (only 1.0 is known)")
            state = "body"
        elif state == "body":
            if stripped == "End:":
                state = "tail"
            elif line.startswith("DI:"):
                if _ends_with_comma(line, where):
                    pending, pending_line = [line], lineno
                else:
                    records.append(_parse_record(line, lineno, where))
            else:
                raise _pac_error(where, f"expected a 'DI:' record or 'End:', found {stripped[:30]!r}")
        else:
            raise _pac_error(where, "data after 'End:'")
    if pending:
        raise _pac_error(f"{filename}:{pending_line}", "record continues past the end of the file")
    if state == "head":
        raise _pac_error(f"{filename}:{len(lines)}", "no 'Begin: 1.0' line")
    if state == "body":
        raise _pac_error(f"{filename}:{len(lines)}", "no 'End:' line")
    return records


def format_number(value: float) -> str:
    """A PDb number as text: integers without a fraction, others in shortest round-trip form."""
    if value == int(value) and abs(value) < 1e15:
        return str(int(value))
    return repr(value).upper() if "e" in repr(value) else repr(value)


def _file_order(path: Path) -> tuple[int, str]:
    stem = re.sub(r"\d+$", "", path.stem.lower())
    rank = _FILE_ORDER.index(stem) if stem in _FILE_ORDER else len(_FILE_ORDER)
    return rank, path.name.lower()


def _norm(n: int) -> int:
    return 1 if int(n) == 0 else int(n)


def pac_file_of(data_id: int, unit: int) -> str:
    """The ``/flash/config`` file a controller keeps ``data_id`` of ``unit`` in (robot-models.md
    §1.1): ``controller.pac`` below 2000 but the GPL variables 1800-1899 (``gpl_vars.pac``); per
    robot ``unit``: ``diomotionNN.pac`` for the MotionBlocks 6100-6199, ``calibNN.pac`` from 16000,
    ``robotNN.pac`` for the rest."""
    if 1800 <= data_id < 1900:
        return "gpl_vars.pac"
    if data_id < 2000:
        return "controller.pac"
    kind = "diomotion" if 6100 <= data_id < 6200 else "calib" if data_id >= 16000 else "robot"
    return f"{kind}{_norm(unit):02d}.pac"


def _file_unit(name: str) -> int:
    """The unit a file's records default to: ``NN`` of a per-robot file, else 1."""
    m = _PER_ROBOT_FILE.match(name)
    return int(m.group(2)) if m else 1


def _render(entries: Iterable[PdbEntry], unit_in_file: int) -> str:
    """``entries`` in the ``.pac`` grammar; a unit equal to ``unit_in_file`` is written as 0."""
    out = ["' Parameter data file written by gplrt", "", "Begin: 1.0", ""]
    for e in entries:
        unit = 0 if e.unit == unit_in_file else e.unit
        vals = ", ".join(f'"{v}"' if isinstance(v, str) else format_number(v) for v in e.values)
        out.append(f'DI: {e.data_id}, {unit}, {0 if e.unit2 == 1 else e.unit2}, 0, "{e.label}" = {vals}')
    out += ["", "End:", "' End of file", ""]
    return "\n".join(out)


# -- the database -------------------------------------------------------------------------------


@dataclass
class ParameterDatabase:
    """DataID → values, per ``(unit, unit2)``; see the module docstring for the access rules."""

    entries: dict[tuple[int, int, int], PdbEntry] = field(default_factory=dict)
    #: Called after each change as ``listener(data_id, unit, unit2)`` (module docstring).
    listeners: list[Callable[[int, int, int], None]] = field(default_factory=list, compare=False, repr=False)
    #: DataID -> the controller's live value (module docstring, "Live DataIDs").
    live: dict[int, LiveParameter] = field(default_factory=dict, compare=False, repr=False)

    # -- loading --------------------------------------------------------------------------------

    @classmethod
    def load(cls, *sources: str | Path | Iterable[str | Path]) -> ParameterDatabase:
        """Load folders (every ``*.pac`` in them) and/or files, in order; later ones override."""
        db = cls()
        for source in sources:
            if isinstance(source, (str, Path)):
                db.load_into(source)
            else:
                for item in source:
                    db.load_into(item)
        return db

    def load_into(self, source: str | Path) -> None:
        """Layer one folder or file over the current contents."""
        path = Path(source)
        if path.is_dir():
            files = sorted(path.glob("*.pac"), key=_file_order)
            if not files:
                raise GplException(CANT_OPEN_PARAMETER_DB, detail=f"{path}: no .pac files")
            for f in files:
                self.load_into(f)
            return
        try:
            text = path.read_text(encoding="ascii")
        except (OSError, UnicodeDecodeError) as exc:
            raise GplException(CANT_OPEN_PARAMETER_DB, detail=f"{path}: {host_reason(exc)}") from None
        self.load_text(text, str(path))

    def load_text(self, text: str, filename: str = "<pac>") -> None:
        """Layer the records of one ``.pac`` text; ``filename`` decides per-robot files (``robotNN``)."""
        m = _PER_ROBOT_FILE.match(Path(filename).name)
        file_unit = int(m.group(2)) if m else None
        changed: dict[tuple[int, int, int], None] = {}  # keys in file order, for the listeners
        for rec in parse_pac(text, filename):
            unit = _norm(rec.unit) if file_unit is None or rec.unit else _norm(file_unit)
            key = (rec.data_id, unit, _norm(rec.unit2))
            changed[key] = None
            origin = f"{filename}:{rec.line}"
            if rec.index == 0:
                self.entries[key] = PdbEntry(rec.data_id, key[1], key[2], rec.label, list(rec.values),
                                             rec.is_string, origin)
                continue
            # A non-zero index sets one element (1-based) of an existing or new array (§1.4 [P]).
            entry = self.entries.get(key)
            if entry is None:
                entry = PdbEntry(rec.data_id, key[1], key[2], rec.label, [], rec.is_string, origin)
                self.entries[key] = entry
            filler: Value = "" if rec.is_string else 0.0
            while len(entry.values) < rec.index + len(rec.values) - 1:
                entry.values.append(filler)
            entry.values[rec.index - 1 : rec.index - 1 + len(rec.values)] = rec.values
        if self.listeners:
            for changed_key in changed:
                self._changed(*changed_key)

    def copy(self) -> ParameterDatabase:
        """An independent copy (per-session databases start from a shared default)."""
        return ParameterDatabase({k: PdbEntry(e.data_id, e.unit, e.unit2, e.label, list(e.values),
                                              e.is_string, e.origin) for k, e in self.entries.items()})

    # -- lookup ---------------------------------------------------------------------------------

    def entry(self, data_id: int, unit: int = 1, unit2: int = 1) -> PdbEntry:
        """The record for a key, or -1501 (unknown DataID) / -1509 (not for this unit)."""
        key = (int(data_id), _norm(unit), _norm(unit2))
        live = self.live.get(key[0]) if self.live else None
        if live is not None:
            return self._live_entry(live, key)
        found = self.entries.get(key)
        if found is not None:
            return found
        if any(k[0] == key[0] for k in self.entries):
            raise GplException(INVALID_DATA_INDEX, detail=f"DataID {data_id} has no unit {key[1]}, unit2 {key[2]}")
        raise GplException(UNKNOWN_DATA_ID, detail=f"DataID {data_id}")

    def _live_entry(self, live: LiveParameter, key: tuple[int, int, int]) -> PdbEntry:
        """A fresh record of a live DataID's present values (-1509 for a unit it does not have)."""
        units = list(live.units()) if live.units is not None else [1]
        if key[1] not in units or key[2] != 1:
            raise GplException(INVALID_DATA_INDEX, detail=f"DataID {key[0]} has no unit {key[1]}, unit2 {key[2]}")
        return PdbEntry(key[0], key[1], key[2], live.label, list(live.read(key[1], key[2])), live.is_string, "<live>")

    def has(self, data_id: int, unit: int = 1, unit2: int = 1) -> bool:
        if int(data_id) in self.live:
            try:
                self.entry(data_id, unit, unit2)
            except GplException:
                return False
            return True
        return (int(data_id), _norm(unit), _norm(unit2)) in self.entries

    def units(self, data_id: int) -> list[int]:
        """The units (robot/device numbers) that have ``data_id``, sorted."""
        live = self.live.get(int(data_id))
        if live is not None:
            return sorted(live.units()) if live.units is not None else [1]
        return sorted({k[1] for k in self.entries if k[0] == data_id})

    def robots(self) -> list[int]:
        """Robot numbers configured in this database (units that have DataID 2000, Number of axes)."""
        return self.units(2000)

    def get(self, data_id: int, unit: int = 1, unit2: int = 1, index: int = 0) -> list[Value] | Value:
        """Index 0: a copy of all values; index i ≥ 1: element i (1-based)."""
        entry = self.entry(data_id, unit, unit2)
        if index == 0:
            return list(entry.values)
        return entry.values[self._check_index(entry, index)]

    def get_nums(self, data_id: int, unit: int = 1, unit2: int = 1) -> list[float]:
        """All values of a numeric DataID (-202 if it holds text)."""
        entry = self._numeric(data_id, unit, unit2)
        return [float(v) for v in entry.values]

    def get_num(self, data_id: int, unit: int = 1, unit2: int = 1, index: int = 1, default: float | None = None) -> float:
        """One element (1-based) of a numeric DataID; ``default`` is returned when the DataID or the
        element is missing (for optional data such as 16050 elements), otherwise an error is raised."""
        try:
            entry = self._numeric(data_id, unit, unit2)
            return float(entry.values[self._check_index(entry, index)])
        except GplException:
            if default is None:
                raise
            return float(default)

    def get_str(self, data_id: int, unit: int = 1, unit2: int = 1, index: int = 1) -> str:
        """One element of a DataID as text (strings as they are, numbers formatted)."""
        entry = self.entry(data_id, unit, unit2)
        value = entry.values[self._check_index(entry, index)]
        return value if isinstance(value, str) else format_number(value)

    # -- GPL surface ----------------------------------------------------------------------------

    def pdb_text(self, data_id: int, unit: int = 1, unit2: int = 1, index: int = 0) -> str:
        """``Controller.PDb(dataid, unit, unit2, array_index)``: index 0 joins all values with ','."""
        entry = self.entry(data_id, unit, unit2)
        if index == 0:
            return ",".join(v if isinstance(v, str) else format_number(v) for v in entry.values)
        return self.get_str(data_id, unit, unit2, index)

    def pdb_num(self, data_id: int, unit: int = 1, unit2: int = 1, index: int = 1) -> float:
        """``Controller.PDbNum(dataid, unit, unit2, array_index)``; index 0 reads element 1."""
        return self.get_num(data_id, unit, unit2, max(1, index))

    def set_pdb_text(self, text: str, data_id: int, unit: int = 1, unit2: int = 1, index: int = 0, key: int = 0) -> None:
        """``Controller.PDb(...) = text``: for numeric DataIDs the text is parsed as number(s)."""
        entry = self._writable(data_id, unit, unit2, key)
        if entry.is_string:
            # One element, or a one-element DataID: the text as given (it may contain commas).
            whole = index == 0 and len(entry.values) > 1
            self._store(entry, [p.strip() for p in text.split(",")] if whole else [text], index)
        else:
            self._store(entry, [self._parse_number(p.strip(), data_id) for p in text.split(",")], index)

    def set_pdb_num(self, value: float, data_id: int, unit: int = 1, unit2: int = 1, index: int = 1, key: int = 0) -> None:
        """``Controller.PDbNum(...) = value``; index 0 writes element 1.  The value converts by
        GPL's Double rules (numeric text parsed, -717 on bad text), never a bare ValueError."""
        self.set(data_id, to_double(value), unit, unit2, max(1, index), key)

    def set(self, data_id: int, value: Value | Sequence[Value], unit: int = 1, unit2: int = 1,
            index: int = 0, key: int = 0) -> None:
        """Write one element (index ≥ 1) or the whole array (index 0, same element count)."""
        entry = self._writable(data_id, unit, unit2, key)
        values = [value] if isinstance(value, (str, int, float)) else list(value)
        for v in values:
            if isinstance(v, str) != entry.is_string:
                raise GplException(INVALID_ARGUMENT, detail=f"DataID {data_id} holds {'text' if entry.is_string else 'numbers'}")
        self._store(entry, [v if isinstance(v, str) else float(v) for v in values], index)

    def define(self, data_id: int, values: Sequence[Value], unit: int = 1, unit2: int = 1, label: str = "") -> None:
        """Create or replace a DataID without access checks (simulator set-up, not GPL code)."""
        key = (int(data_id), _norm(unit), _norm(unit2))
        is_string = bool(values) and isinstance(values[0], str)
        self.entries[key] = PdbEntry(key[0], key[1], key[2], label, list(values), is_string, "<define>")
        self._changed(*key)

    # -- saving ---------------------------------------------------------------------------------

    def dump_pac(self, data_ids: Iterable[int] | None = None, unit_in_file: int | None = None) -> str:
        """Re-emit entries in the ``.pac`` grammar (unit written as 0 when it is the file's unit)."""
        wanted = None if data_ids is None else set(data_ids)
        return _render([self.entries[k] for k in sorted(self.entries) if wanted is None or k[0] in wanted],
                       unit_in_file or 1)

    def pac_files(self) -> dict[str, str]:
        """The stored DataIDs as a controller saves them to ``/flash/config`` (DataID 901): file
        name -> text, each DataID in the file :func:`pac_file_of` names, so that loading the folder
        gives this database back."""
        groups: dict[str, list[PdbEntry]] = {}
        for k in sorted(self.entries):
            entry = self.entries[k]
            groups.setdefault(pac_file_of(entry.data_id, entry.unit), []).append(entry)
        return {name: _render(entries, _file_unit(name)) for name, entries in sorted(groups.items())}

    # -- helpers --------------------------------------------------------------------------------

    @staticmethod
    def _check_index(entry: PdbEntry, index: int) -> int:
        if not 1 <= index <= len(entry.values):
            raise GplException(INVALID_PARAMETER_ARRAY_INDEX,
                               detail=f"DataID {entry.data_id} index {index} (1..{len(entry.values)})")
        return index - 1

    def _numeric(self, data_id: int, unit: int, unit2: int) -> PdbEntry:
        entry = self.entry(data_id, unit, unit2)
        if entry.is_string:
            raise GplException(INVALID_ARGUMENT, detail=f"DataID {data_id} holds text, not a number")
        return entry

    def _writable(self, data_id: int, unit: int, unit2: int, key: int) -> PdbEntry:
        entry = self.entry(data_id, unit, unit2)
        live = self.live.get(entry.data_id)
        if entry.data_id in READ_ONLY_IDS or (live is not None and live.write is None):
            raise GplException(READ_ONLY, detail=f"DataID {data_id}")
        if entry.data_id in PROTECTED_IDS and not key:
            raise GplException(PROTECTION_ERROR, detail=f"DataID {data_id} needs the key argument")
        return entry

    @staticmethod
    def _parse_number(text: str, data_id: int) -> float:
        try:
            return float(text)
        except ValueError:
            raise GplException(INVALID_ARGUMENT, detail=f"DataID {data_id}: {text!r} is not a number") from None

    def _store(self, entry: PdbEntry, values: list[Value], index: int) -> None:
        if index == 0:
            if len(values) != len(entry.values):
                raise GplException(INVALID_ARGUMENT, detail=(
                    f"DataID {entry.data_id} has {len(entry.values)} values, {len(values)} given"))
            entry.values[:] = values
        else:
            if len(values) != 1:
                raise GplException(INVALID_ARGUMENT, detail=f"DataID {entry.data_id}: one value expected at index {index}")
            entry.values[self._check_index(entry, index)] = values[0]
        live = self.live.get(entry.data_id) if entry.origin == "<live>" else None
        if live is not None and live.write is not None:
            live.write(entry.unit, entry.unit2, list(entry.values))  # the controller acts on it
        self._changed(entry.data_id, entry.unit, entry.unit2)

    def _changed(self, data_id: int, unit: int, unit2: int) -> None:
        """Tell the listeners that a DataID changed (after the change is stored)."""
        for listener in list(self.listeners):
            listener(data_id, unit, unit2)


# -- shipped default databases ------------------------------------------------------------------

DATA_DIR = Path(__file__).resolve().parent.parent / "data" / "robots"

#: Model name → layers (folders or files under ``data/robots``), loaded in order.  Real backups
#: come first; the ``variants/`` overlays (ours, documented in data/robots/variants/README.md)
#: change only what distinguishes a variant.  Naming follows Precise's letters: S = servo
#: gripper, X = extended reach (302/289 mm links; without X: standard 225/210 mm), L = linear
#: rail; ``-TALL`` / ``-SHORT`` pick the 1160 mm or the 400 mm column when the default differs
#: (the real SX backup has the tall column, the SXL backup the short one).
MODELS: dict[str, tuple[str, ...]] = {
    "PF400SX": ("pf400sx",),
    "PF400SX-TALL": ("pf400sx",),
    "PF400SX-SHORT": ("pf400sx", "variants/column-short-5axis"),
    "PF400S": ("pf400sx", "variants/reach-standard"),
    "PF400S-TALL": ("pf400sx", "variants/reach-standard"),
    "PF400S-SHORT": ("pf400sx", "variants/column-short-5axis", "variants/reach-standard"),
    "PF400SXL": ("pf400sxl-rail",),
    "PF400SXL-SHORT": ("pf400sxl-rail",),
    "PF400SXL-TALL": ("pf400sxl-rail", "variants/column-tall-6axis"),
    "PF400SL": ("pf400sxl-rail", "variants/reach-standard"),
    "PF400SL-TALL": ("pf400sxl-rail", "variants/column-tall-6axis", "variants/reach-standard"),
    "PF400SX-2020": ("pf400sx-2020",),
    "PF3400SX": ("pf400sx", "variants/pf3400sx"),
    "GANTRY4": ("gantry4",),
    "XYZT-GCU": ("gcu-default-4axis",),
    "ARM6": ("arm6",),
}
MODEL_ALIASES: dict[str, str] = {"PF400": "PF400SX", "PF3400": "PF3400SX", "PP100": "GANTRY4", "GANTRY": "GANTRY4"}

_DEFAULT_CACHE: dict[str, ParameterDatabase] = {}


def model_names() -> list[str]:
    """All model names ``default_database`` accepts (aliases included): the ``.pac`` models above
    and the URDF ones (``gplrt.controller.urdf_catalogue``)."""
    return sorted([*MODELS, *MODEL_ALIASES, *URDF_ROBOTS])


def default_database(model: str = "PF400SX") -> ParameterDatabase:
    """A fresh copy of the shipped database for ``model`` (case-insensitive; see ``MODELS``).

    Unknown names (and anything that is not a name) raise -221 *Invalid robot type*."""
    if not isinstance(model, str):
        raise GplException(INVALID_ROBOT_TYPE, detail=f"a robot model is a name, not {model!r}; known: {', '.join(model_names())}")
    name = model.strip().upper()
    name = MODEL_ALIASES.get(name, name)
    if name not in _DEFAULT_CACHE and name not in MODELS:
        if name in URDF_ROBOTS:  # a database derived from the robot's URDF
            db = ParameterDatabase()
            for filename, text in pdb_layers(name):
                db.load_text(text, filename)
            _DEFAULT_CACHE[name] = db
    if name not in MODELS and name not in _DEFAULT_CACHE:
        raise GplException(INVALID_ROBOT_TYPE, detail=f"unknown robot model {model!r}; known: {', '.join(model_names())}")
    if name not in _DEFAULT_CACHE:
        _DEFAULT_CACHE[name] = ParameterDatabase.load([DATA_DIR / layer for layer in MODELS[name]])
    return _DEFAULT_CACHE[name].copy()
