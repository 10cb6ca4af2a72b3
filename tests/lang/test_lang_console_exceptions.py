"""Console output through a replaceable sink; Python faults mapped to controller codes."""

from __future__ import annotations

import math
import threading
from typing import Any

import pytest

from gplrt.lang.arrays import GplArray
from gplrt.lang.console import Console, capture_console, set_console_sink
from gplrt.lang.delegates import invoke
from gplrt.lang.errors import GplException
from gplrt.lang.exceptions import as_gpl_exception, gpl_code_for
from gplrt.lang.gpltypes import Integer
from gplrt.lang.operators import div


def test_write_and_writeline_use_cstr_rules() -> None:
    with capture_console() as out:
        Console.Write("a")
        Console.Write(5)
        Console.WriteLine(0.1)
        Console.WriteLine(True)
        Console.WriteLine(1 / 3)
        Console.WriteLine()
        for ii in range(1, 3):
            Console.WriteLine("The square of " + str(ii) + " is " + str(ii * ii))
    assert out.text == "a50.1\n-1\n0.333333333333333\n\nThe square of 1 is 1\nThe square of 2 is 4\n"
    assert out.lines[0] == "a50.1"


def test_default_sink_is_stdout(capsys) -> None:
    Console.WriteLine("hello")
    Console.Write(2.5)
    assert capsys.readouterr().out == "hello\n2.5"


def test_set_console_sink_returns_previous() -> None:
    got: list[str] = []
    previous = set_console_sink(got.append)
    try:
        Console.WriteLine("x")
    finally:
        set_console_sink(previous)
    assert got == ["x\n"]


def test_lines_from_threads_do_not_interleave() -> None:
    with capture_console() as out:

        def writer(tag: str) -> None:
            for i in range(200):
                Console.WriteLine(f"{tag}-{i}-" + "x" * 50)

        threads = [threading.Thread(target=writer, args=(t,)) for t in "ABCD"]
        for t in threads:
            t.start()
        for t in threads:
            t.join()
    lines = out.lines
    assert len(lines) == 800
    assert all(line.endswith("x" * 50) and line.count("-") == 2 for line in lines)


NOTHING: Any = None


def catch(fn, *args) -> GplException:
    """What a lowered Try/Catch hands its Catch variable."""
    try:
        fn(*args)
    except BaseException as e:  # noqa: BLE001 -- the lowering's shape
        return as_gpl_exception(e)
    raise AssertionError("no exception")


def test_gpl_exception_passes_through_unchanged() -> None:
    exc = GplException(-786, 8)

    def throw() -> None:
        raise exc

    assert catch(throw) is exc


@pytest.mark.parametrize(
    ("fault", "code"),
    [
        (lambda: 1 / 0, -709),
        (lambda: 1.0 % 0.0, -709),
        (lambda: 2.0**5000, -710),
        (lambda: math.exp(1000), -710),
        (lambda: [1, 2][5], -767),
        (lambda: NOTHING.X, -757),
        (lambda: NOTHING[0], -757),
        (lambda: NOTHING(1), -796),
        (lambda: math.sqrt(-1), -707),
        (lambda: float("abc"), -717),
        (lambda: int(float("nan")), -708),
        (lambda: {}["k"], -201),
    ],
)
def test_python_faults_map_to_controller_codes(fault, code) -> None:
    gex = catch(fault)
    assert gex.ErrorCode == code
    assert gex.__cause__ is not None
    assert gex.Message().startswith("*")


def test_recursion_maps_to_755() -> None:
    def deep(n: int) -> int:
        return deep(n + 1) + 1

    assert catch(deep, 0).ErrorCode == -755


def test_runtime_faults_arrive_with_their_codes() -> None:
    a = GplArray(Integer, 2)
    assert catch(lambda: a[-1]).ErrorCode == -767
    assert catch(div, 1, 0).ErrorCode == -709
    assert catch(invoke, None).ErrorCode == -796


def test_base_exceptions_are_not_swallowed() -> None:
    with pytest.raises(KeyboardInterrupt):
        as_gpl_exception(KeyboardInterrupt())
    with pytest.raises(SystemExit):
        as_gpl_exception(SystemExit(0))


def test_gpl_code_for() -> None:
    assert gpl_code_for(ZeroDivisionError()) == -709
    assert gpl_code_for(GplException(-1009)) == -1009


def test_error_code_table_has_one_name_per_controller_code() -> None:
    """errors.py is the one table of code names: no code named twice, none the controller lacks."""
    from gplrt.lang import errors
    from gplrt.lang.error_codes import ERROR_MESSAGES

    named: dict[int, list[str]] = {}
    for name, value in vars(errors).items():
        if name.isupper() and type(value) is int:
            named.setdefault(value, []).append(name)
    assert {code: names for code, names in named.items() if len(names) > 1} == {}
    assert sorted(code for code in named if code not in ERROR_MESSAGES) == []
    assert named[-1036] == ["KINEMATICS_NOT_INSTALLED"]
