"""Parameter database: .pac loading (robot-models.md §1), typed reads, checked writes, errors."""

from __future__ import annotations

from pathlib import Path

import pytest

from gplrt.controller.pdb import (
    DATA_DIR,
    ParameterDatabase,
    default_database,
    model_names,
    parse_pac,
)
from gplrt.lang.errors import GplException

# The project's shared corpus of real controller files: beside the checkout (as CI lays it out) or
# at the workplace's mount point.
SHARED = next(
    (p for p in (Path(__file__).resolve().parents[3] / "shared" / "data" / "robots",
                 Path("/work/shared/data/robots")) if p.is_dir()),
    Path("/work/shared/data/robots"),
)
SETS = ["pf400sx", "pf400sx-2020", "pf400sxl-rail", "gcu-default-4axis"]


def _sets_root() -> Path:
    """The shared corpus when present, else the byte-identical copies shipped in gplrt."""
    return SHARED if SHARED.is_dir() else DATA_DIR


def _code(exc: pytest.ExceptionInfo[GplException]) -> int:
    return exc.value.ErrorCode


# -- loading the real files ---------------------------------------------------------------------


def test_every_shared_pac_file_parses_with_the_documented_record_counts() -> None:
    """All 22 files: 2,874 records, 251 of them string-valued (robot-models.md §1.3 [VER])."""
    files = sorted(p for s in SETS for p in (_sets_root() / s).glob("*.pac"))
    assert len(files) == 22
    records = [r for f in files for r in parse_pac(f.read_text(), str(f))]
    assert len(records) == 2874
    assert sum(r.is_string for r in records) == 251
    # Every record's value count equals the count of value tokens we can see in the file text.
    for f in files:
        assert len(parse_pac(f.read_text(), str(f))) == f.read_text().count("\nDI:")


@pytest.mark.parametrize("folder", SETS)
def test_shipped_copies_are_identical_to_the_shared_corpus(folder: str) -> None:
    if not SHARED.is_dir():
        pytest.skip("shared corpus not mounted")
    for f in (SHARED / folder).glob("*.pac"):
        assert (DATA_DIR / folder / f.name).read_bytes() == f.read_bytes()


def test_pf400sx_values_keyed_on_dataid_and_robot_unit() -> None:
    db = ParameterDatabase.load(_sets_root() / "pf400sx")
    assert db.get_nums(16050) == [0, 302, 289] + [0] * 13
    assert db.get(2002) == ["PreciseFlex 400SX"]
    assert db.get_num(2003) == 47
    assert db.get_nums(116) == [12] + [0] * 11
    assert db.get_nums(16077) == [1161.5, 93, 348, 960, 134]
    assert db.get_nums(16078) == [1.5, -93, 12, -960, 69]
    assert db.get_num(600) == 0.004
    assert db.get_num(604) == 6.25e-05
    # unit 0 in the file is unit 1; the robot file's records belong to robot 1
    assert db.get(2000) == db.get(2000, 0) == db.get(2000, 1) == [5.0]
    assert db.robots() == [1]


def test_sxl_rail_set_has_six_axes_and_rail_angle_zero() -> None:
    db = ParameterDatabase.load(_sets_root() / "pf400sxl-rail")
    assert db.get_num(2000) == 6 and db.get_num(2003) == 111
    assert db.get_num(16050, 1, 1, 5) == 0
    assert db.get_nums(16077)[-1] == 500 and db.get_nums(16078)[0] == 1.5


def test_multi_unit_controller_records_and_motion_blocks() -> None:
    db = ParameterDatabase.load(_sets_root() / "pf400sx")
    assert {1, 2, 3} <= set(db.units(405))  # serial ports written as units 0, 2, 3
    # diomotion: unit2 = MotionBlock number; block 1 targets (robot-models.md §2.8)
    assert db.get_nums(6102, 1, 1)[:5] == pytest.approx([207.8956, -50.2901, 87.1367, 326.3494, 126.0843])
    assert db.has(6102, 1, 20) and db.get_num(6101, 1, 1) == 1


def test_gcu_default_set_grammar_edge_cases_and_second_robot() -> None:
    db = ParameterDatabase.load(_sets_root() / "gcu-default-4axis")
    assert db.get(2012) == ["", "", "", ""]  # "","","","" without spaces
    assert db.get_nums(16075) == [3.402823e38] * 4  # 3.402823E+38,3.402823E+38
    assert db.get_num(2000, unit=2) == 1  # robot02.pac: Encoder Only Module
    assert db.get_str(2002, 2) == "Encoder Only Module"
    assert db.robots() == [1, 2]


# -- typed reads and the GPL surface ------------------------------------------------------------


def test_pdb_text_and_pdbnum_index_rules() -> None:
    db = default_database("PF400SX")
    assert db.pdb_text(16077) == "1161.5,93,348,960,134"  # index 0: all values
    assert db.pdb_text(16077, 1, 1, 2) == "93"
    assert db.pdb_text(2002) == "PreciseFlex 400SX"
    assert db.pdb_num(16077) == 1161.5  # PDbNum: index defaults to 1
    assert db.pdb_num(16077, 1, 1, 3) == 348
    assert db.pdb_text(604) == "6.25E-05"


def test_writes_read_back_and_copies_are_independent() -> None:
    db = default_database("PF400SX")
    db.set_pdb_num(75, 601)
    assert db.pdb_num(601) == 75
    db.set_pdb_text("10, 20, 30, 40, 50", 2700)
    assert db.get_nums(2700) == [10, 20, 30, 40, 50]
    db.set(16077, 1000.0, index=1)
    assert db.get_nums(16077)[0] == 1000
    db.set_pdb_text("My arm", 2002)
    assert db.get(2002) == ["My arm"]
    assert default_database("PF400SX").pdb_num(601) == 50  # the shipped default is untouched


def test_read_only_and_protected_ids_refuse() -> None:
    db = default_database("PF400SX")
    db.define(103, ["GPL 4.2J2, Mar 6 2020, Release"], label="Software version")
    with pytest.raises(GplException) as exc:
        db.set_pdb_text("hacked", 103)
    assert _code(exc) == -209
    assert db.get(103) == ["GPL 4.2J2, Mar 6 2020, Release"]
    with pytest.raises(GplException) as exc:
        db.set(16050, 250.0, index=2)
    assert _code(exc) == -208
    db.set(16050, 250.0, index=2, key=1)
    assert db.get_num(16050, 1, 1, 2) == 250


@pytest.mark.parametrize(
    ("call", "code"),
    [
        (lambda db: db.get(99999), -1501),
        (lambda db: db.set_pdb_num(1, 99999), -1501),
        (lambda db: db.get(2000, unit=7), -1509),
        (lambda db: db.pdb_num(16077, 1, 1, 6), -1514),
        (lambda db: db.get_num(16077, index=0), -1514),
        (lambda db: db.set(2700, "fast", index=1), -202),
        (lambda db: db.set_pdb_text("1, 2", 2700), -202),  # whole array needs 5 values
        (lambda db: db.set_pdb_text("abc", 601), -202),
        (lambda db: db.pdb_num(2002), -202),
    ],
)
def test_bad_access_raises_the_controller_codes(call, code: int) -> None:  # type: ignore[no-untyped-def]
    with pytest.raises(GplException) as exc:
        call(default_database("PF400SX"))
    assert _code(exc) == code


# -- grammar details ----------------------------------------------------------------------------

GOOD = """' Robot kinematic module parameter data file
' Controller: test

Begin: 1.0

DI: 2000, 0, 0, 0, "Number of axes" = 3
DI: 2700, 0, 0, 0, "Speeds, in (mm/s), = a list" = 1, -2.5,
     .5, 6.25E-05,
     1e3
DI: 2002, 0, 0, 0, "Robot name" = "A, B = C"
DI: 2700, 0, 0, 2, "Speeds" = 7

End:

' End of file
"""


def test_continuations_labels_with_punctuation_and_element_records() -> None:
    db = ParameterDatabase()
    db.load_text(GOOD, "robot03.pac")
    assert db.get_nums(2700, 3) == [1, 7, 0.5, 6.25e-05, 1000]  # index 2 record set element 2
    assert db.get(2002, 3) == ["A, B = C"]
    assert db.robots() == [3]


def test_crlf_and_tabs_are_accepted() -> None:
    db = ParameterDatabase()
    db.load_text(GOOD.replace("\n", "\r\n").replace("     .5", "\t.5"), "robot01.pac")
    assert db.get_nums(2700)[:3] == [1, 7, 0.5]


def test_later_files_override_earlier_ones(tmp_path: Path) -> None:
    a = tmp_path / "a"
    a.mkdir()
    (a / "controller.pac").write_text('Begin: 1.0\nDI: 601, 0, 0, 0, "Test speed" = 50\nEnd:\n')
    b = tmp_path / "b.pac"
    b.write_text('Begin: 1.0\nDI: 601, 0, 0, 0, "Test speed" = 20\nEnd:\n')
    assert ParameterDatabase.load(a, b).get_num(601) == 20
    assert ParameterDatabase.load(b, a).get_num(601) == 50


def test_dump_round_trips_through_the_parser() -> None:
    db = default_database("PF400SXL")
    text = db.dump_pac(unit_in_file=1)
    again = ParameterDatabase()
    again.load_text(text, "controller.pac")
    assert again.get_nums(16077) == db.get_nums(16077)
    assert again.get(109) == db.get(109)
    assert again.get_nums(6101, 1, 7) == db.get_nums(6101, 1, 7)
    assert len(again.entries) == len(db.entries)


@pytest.mark.parametrize("model", ["PF400SX", "PF400SXL", "XYZT-GCU"])
def test_pac_files_keep_each_dataid_in_its_controller_file(model: str, tmp_path: Path) -> None:
    """What DataID 901 saves: every DataID in the file a real controller keeps it in (the file it
    was loaded from: robot 2's records of the GCU set in robot02/calib02), and the folder loads
    back into the same database."""
    db = default_database(model)
    files = db.pac_files()
    for name, text in files.items():
        (tmp_path / name).write_text(text, encoding="ascii")
    loaded_from = {k: Path(e.origin.rsplit(":", 1)[0]).name for k, e in db.entries.items()}
    saved_in = {k: Path(e.origin.rsplit(":", 1)[0]).name
                for k, e in ParameterDatabase.load(tmp_path).entries.items()}
    assert saved_in == loaded_from
    again = ParameterDatabase.load(tmp_path)
    assert {k: (e.label, e.values) for k, e in again.entries.items()} == \
        {k: (e.label, e.values) for k, e in db.entries.items()}


@pytest.mark.parametrize(
    ("text", "line", "words"),
    [
        ('DI: 1, 0, 0, 0, "x" = 1\nEnd:\n', 1, "Begin"),
        ("Begin: 2.0\nEnd:\n", 1, "version"),
        ('Begin: 1.0\nDI: 1, 0, 0, 0, "x" = 1\n', 3, "End:"),
        ('Begin: 1.0\n\nDI: 1, 0, 0, "x" = 1\nEnd:\n', 3, "field 4"),
        ('Begin: 1.0\nDI: 1, 0, 0, 0, "x = 1\nEnd:\n', 2, "unterminated"),
        ('Begin: 1.0\nDI: 1, 0, 0, 0, "x" = 1, "a"\nEnd:\n', 2, "mixed"),
        ('Begin: 1.0\nDI: 1, 0, 0, 0, "x" = 1,\nDI: 2, 0, 0, 0, "y" = 1\nEnd:\n', 3, "continuation"),
        ('Begin: 1.0\nDI: 1, 0, 0, 0, "x" = 1 2\nEnd:\n', 2, "','"),
        ('Begin: 1.0\nDI: 1, 0, 0, 0, "x" =\nEnd:\n', 2, "empty"),
        ('Begin: 1.0\nDI: 1, 0, 0, 0, "x" = 0x1F\nEnd:\n', 2, "unexpected"),
        ('Begin: 1.0\nFoo: 1\nEnd:\n', 2, "DI:"),
        ('Begin: 1.0\nEnd:\nDI: 1, 0, 0, 0, "x" = 1\n', 3, "after"),
    ],
)
def test_bad_pac_text_reports_file_and_line(text: str, line: int, words: str) -> None:
    with pytest.raises(GplException) as exc:
        parse_pac(text, "bad.pac")
    assert _code(exc) == -1515
    assert exc.value.detail is not None
    assert exc.value.detail.startswith(f"bad.pac:{line}:"), exc.value.detail
    assert words in exc.value.detail


def test_missing_file_and_unknown_model() -> None:
    with pytest.raises(GplException) as exc:
        ParameterDatabase.load("/nonexistent/robot01.pac")
    assert _code(exc) == -1520
    with pytest.raises(GplException) as exc:
        default_database("PD400")
    assert _code(exc) == -221


def test_a_file_that_cannot_be_read_says_why_without_pythons_words(tmp_path: Path) -> None:
    """The detail was Python's rendering of the exception: "[Errno 2] No such file or directory:
    '...'" and "'ascii' codec can't decode byte 0xe9 in position 17: ordinal not in range(128)"."""
    with pytest.raises(GplException) as exc:
        ParameterDatabase.load("/nonexistent/robot01.pac")
    assert exc.value.detail == "/nonexistent/robot01.pac: No such file or directory"
    accented = tmp_path / "robot01.pac"
    accented.write_bytes('Begin: 1.0\nDI: 1, 0, 0, 0, "café" = 1\nEnd:\n'.encode("latin-1"))
    with pytest.raises(GplException) as exc:
        ParameterDatabase.load(accented)
    assert _code(exc) == -1520
    assert exc.value.detail == f"{accented}: not ASCII text (byte 0xE9 at offset 31)"


@pytest.mark.parametrize("model", model_names())
def test_every_default_model_loads(model: str) -> None:
    db = default_database(model)
    assert db.robots() == [1] or db.robots() == [1, 2]
    n = int(db.get_num(2000))
    assert len(db.get_nums(16077)) >= n and len(db.get_nums(16078)) >= n


def test_variant_overlays_change_only_what_they_say() -> None:
    sx, s_short = default_database("PF400SX"), default_database("PF400S-SHORT")
    assert s_short.get_nums(16050)[1:3] == [225, 210]
    assert s_short.get_num(16077) == 401.5
    assert s_short.get_nums(2700) == sx.get_nums(2700)
    assert default_database("PF400SXL-TALL").get_nums(16077) == [1161.5, 93, 348, 960, 134, 500]
    assert default_database("PF3400").get(2002) == ["PreciseFlex 3400SX"]
