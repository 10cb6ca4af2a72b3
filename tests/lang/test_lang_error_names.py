"""The error-code name table and what an exception tells a program that catches it."""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

from gplrt.lang import errors
from gplrt.lang.errors import GplException
from gplrt.lang.exceptions import not_available

RUNTIME = Path(errors.__file__).resolve().parents[1]


def _literal_codes(path: Path) -> list[str]:
    """``GplException(-NNN, ...)`` / ``gpl_error(-NNN)`` calls with a bare number in ``path``."""
    found = []
    for node in ast.walk(ast.parse(path.read_text(), str(path))):
        if isinstance(node, ast.Call) and node.args and getattr(node.func, "id", "") in ("GplException", "gpl_error"):
            code = node.args[0]
            if isinstance(code, ast.UnaryOp) and isinstance(code.operand, ast.Constant):
                found.append(f"{path.relative_to(RUNTIME)}:{node.lineno}: -{code.operand.value}")
    return found


def test_conveyor_code_is_named_once_in_the_table() -> None:
    assert errors.CONVEYOR_MUST_BE_BASE == -791
    assert errors.error_text(errors.CONVEYOR_MUST_BE_BASE) == "Conveyor must be base RefFrame"


#: Every package of the runtime, found on disk (so a new one is checked without editing this list),
#: and "." for the modules at the top (sim.py, notebook.py...).
AREAS = sorted(p.name for p in RUNTIME.iterdir() if (p / "__init__.py").is_file()) + ["."]


def test_the_areas_are_found() -> None:
    """Guards the discovery above: were the runtime moved, the check below would pass vacuously."""
    assert {"lang", "geometry", "controller", "threads", "motion", "io"} <= set(AREAS)


@pytest.mark.parametrize("area", AREAS)
def test_runtime_raises_named_codes_not_literals(area: str) -> None:
    """errors.py is where every code is named once; every runtime module raises by name."""
    target = RUNTIME / area
    files = sorted(target.glob("*.py")) if area == "." else sorted(target.rglob("*.py"))
    assert files, f"{target} has no modules"
    offenders = [hit for f in files if f != Path(errors.__file__).resolve() for hit in _literal_codes(f)]
    assert offenders == []


def _caught_from_stub(name: str, builtin: bool = False) -> GplException:
    with pytest.raises(GplException) as info:
        not_available(name, builtin=builtin)
    return info.value


def test_caught_stub_error_names_the_protected_name_in_message() -> None:
    exc = _caught_from_stub("VendorLib.Grip")
    assert exc.ErrorCode == -204
    assert exc.Message() == "*Not implemented*: protected source not available: VendorLib.Grip"
    # the Python-side text does not repeat it
    assert str(exc).count("VendorLib.Grip") == 1


def test_caught_builtin_stub_error_names_the_member() -> None:
    exc = _caught_from_stub("Controller.Frobnicate", builtin=True)
    assert exc.Message() == "*Not implemented*: not available in the simulated controller: Controller.Frobnicate"


def test_subject_survives_clone_and_follows_a_qualifier() -> None:
    exc = _caught_from_stub("Home")
    assert exc.Clone().Message() == exc.Message()
    exc.Qualifier = 3
    assert exc.Message() == "*Not implemented*: 3: protected source not available: Home"


def test_changing_the_error_code_drops_the_old_subject() -> None:
    exc = _caught_from_stub("Home")
    exc.ErrorCode = -204  # same code: still about Home
    assert exc.Message().endswith("Home")
    exc.ErrorCode = -786
    assert exc.Message() == "*Project generated error*"


def test_plain_exceptions_keep_the_controller_format() -> None:
    assert GplException(-786, 8).Message() == "*Project generated error*: 8"
    assert GplException(-709, detail="x / 0").Message() == "*Division by 0*"


def test_integer_members_use_gpl_integer_conversion() -> None:
    """From Python, ``ex.Qualifier = "3"`` parses and 2.5 rounds half away from zero (not int())."""
    exc = GplException("-786", 2.5)
    assert (exc.ErrorCode, exc.Qualifier) == (-786, 3)
    exc.Qualifier = "7"
    exc.Axis = 1.5
    exc.RobotNum = "2"
    assert (exc.Qualifier, exc.Axis, exc.RobotNum) == (7, 2, 2)


@pytest.mark.parametrize(
    ("member", "value", "code"),
    [("ErrorCode", "abc", -717), ("Qualifier", "abc", -717), ("Qualifier", float("nan"), -710),
     ("Axis", float("inf"), -710), ("RobotNum", "x", -717), ("Qualifier", 70000, -707)],
)  # fmt: skip
def test_bad_integer_members_raise_gpl_codes(member: str, value: object, code: int) -> None:
    exc = GplException(-786, 4)
    with pytest.raises(GplException) as info:
        setattr(exc, member, value)
    assert info.value.ErrorCode == code
    assert (exc.ErrorCode, exc.Qualifier) == (-786, 4)
