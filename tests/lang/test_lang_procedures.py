"""Procedure registry and delegates: case-insensitive, qualified, ambiguous, missing, Private."""

from __future__ import annotations

from collections.abc import Iterator

import pytest

from gplrt.lang.delegates import Delegate, delegate_type, invoke
from gplrt.lang.procedures import (
    clear_procedures,
    find_procedure,
    find_procedure_entry,
    register_procedure,
    registered_procedures,
)
from gpltest import code_of


def main_start() -> str:
    return "Main.Start"


def tools_helper() -> str:
    return "Tools.Helper"


def io_helper() -> str:
    return "IO.Helper"


def main_secret() -> str:
    return "Main.Secret"


def io_secret() -> str:
    return "IO.Secret"


def gripper_open(width: float) -> str:
    return f"Gripper.Open({width})"


def f0(x: int) -> str:
    return f"f0({x})"


@pytest.fixture(autouse=True)
def registry() -> Iterator[None]:
    clear_procedures()
    register_procedure("Main", "Start", main_start, public=True)
    register_procedure("Main", "Secret", main_secret, public=False)
    register_procedure("Tools", "Helper", tools_helper, public=True)
    register_procedure("IO", "Helper", io_helper, public=True)
    register_procedure("IO", "Secret", io_secret, public=False)
    register_procedure("Main.Gripper", "Open", gripper_open, public=True)
    register_procedure("Main", "f0", f0, public=True)
    yield
    clear_procedures()


def test_bare_unique_public_name() -> None:
    assert find_procedure("Start")() == "Main.Start"


def test_case_insensitive() -> None:
    assert find_procedure("START")() == "Main.Start"
    assert find_procedure("main.start")() == "Main.Start"
    assert find_procedure("tOoLs.HeLpEr")() == "Tools.Helper"


def test_qualified_name() -> None:
    assert find_procedure("Tools.Helper")() == "Tools.Helper"
    assert find_procedure("IO.Helper")() == "IO.Helper"
    assert find_procedure_entry("io.helper").qualified_name == "IO.Helper"


def test_ambiguous_public_name_is_772() -> None:
    assert code_of(find_procedure, "Helper") == -772


def test_callers_own_module_wins_over_ambiguity() -> None:
    assert find_procedure("Helper", module="IO")() == "IO.Helper"
    assert find_procedure("helper", module="tools")() == "Tools.Helper"


def test_private_procedure_only_from_its_module() -> None:
    assert find_procedure("Secret", module="Main")() == "Main.Secret"
    assert find_procedure("Secret", module="IO")() == "IO.Secret"
    assert code_of(find_procedure, "Secret") == -729
    assert code_of(find_procedure, "IO.Secret", module="Main") == -729
    assert find_procedure("IO.Secret", module="IO")() == "IO.Secret"


def test_missing_procedure_is_729_and_missing_module_is_798() -> None:
    assert code_of(find_procedure, "NoSuchProc") == -729
    assert code_of(find_procedure, "Tools.NoSuchProc") == -729
    assert code_of(find_procedure, "NoModule.Start") == -798
    assert code_of(find_procedure, "") == -729
    assert code_of(find_procedure, "Main.") == -729


def test_class_shared_procedure_by_class_or_full_path() -> None:
    assert find_procedure("Gripper.Open")(5) == "Gripper.Open(5)"
    assert find_procedure("Main.Gripper.Open")(5) == "Gripper.Open(5)"
    assert code_of(find_procedure, "Open") == -729  # class members need their class name


def test_re_registration_replaces() -> None:
    register_procedure("Tools", "Helper", lambda: "new", public=True)
    assert find_procedure("Tools.Helper")() == "new"


def test_delegate_from_address_of_function() -> None:
    d = Delegate(f0)
    assert d(3) == "f0(3)"


def test_delegate_bound_method_keeps_the_original_object() -> None:
    class Counter:
        def __init__(self, n: int) -> None:
            self.n = n

        def my_fn(self, k: int) -> int:
            return self.n + k

    my_obj = Counter(10)
    d = Delegate(my_obj.my_fn)  # New D(AddressOf my_obj.My_fn)
    my_obj = Counter(100)  # reassignment does not affect the delegate
    assert d(1) == 11
    assert my_obj.n == 100


def test_delegate_from_string_resolved_at_run_time() -> None:
    my_template = delegate_type("My_template", 1)
    d = my_template.from_name("f0")
    assert d(7) == "f0(7)"
    d2 = my_template("MAIN.F0")
    assert d2(1) == "f0(1)"
    assert isinstance(d2, Delegate)


def test_delegate_from_string_errors() -> None:
    my_template = delegate_type("My_template", 1)
    assert code_of(my_template.from_name, "nothing_here") == -729
    assert code_of(my_template.from_name, "Helper") == -772
    assert code_of(my_template.from_name, "Start") == -741  # Start takes no argument


def test_nothing_delegate_is_796() -> None:
    assert code_of(invoke, None, 1) == -796
    assert code_of(Delegate, None) == -796
    assert invoke(Delegate(f0), 2) == "f0(2)"


def test_delegates_in_an_array() -> None:
    from gplrt.lang.arrays import GplArray

    tmpl = delegate_type("Tmpl", 1)
    dels = GplArray(tmpl, 1)
    assert dels[0] is None
    dels[0] = tmpl(f0)
    dels[1] = tmpl(gripper_open)
    assert dels[1](2) == "Gripper.Open(2)"  # str = del_obj(index)(3)


def log_1(msg: str) -> str:
    return f"Log.1({msg})"


def log_2(msg: str, level: int = 0) -> str:
    return f"Log.2({msg}, {level})"


def log_s(msg: str) -> str:
    return f"Log.s({msg})"


def test_overloads_stay_registered_and_the_argument_count_chooses() -> None:
    register_procedure("Tools", "Log", log_1, public=True, overload=0)
    register_procedure("Tools", "Log", log_2, public=True, overload=1)
    assert find_procedure("Log", nargs=2)("m", 3) == "Log.2(m, 3)"
    assert find_procedure("Tools.Log", nargs=2)("m", 3) == "Log.2(m, 3)"
    # one argument fits both (the second has an Optional parameter): ambiguous, as is not saying
    assert code_of(find_procedure, "Log", nargs=1) == -772
    assert code_of(find_procedure, "Tools.Log") == -772
    assert code_of(find_procedure, "Log", nargs=0) == -741  # no overload takes none
    assert code_of(find_procedure, "Log", nargs=3) == -741
    # registering again (a new session) replaces each overload, never adds a third
    register_procedure("Tools", "Log", log_s, public=True, overload=0)
    assert find_procedure("Tools.Log", "Tools", nargs=2)("m", 1) == "Log.2(m, 1)"
    register_procedure("Tools", "Log", log_2, public=True, overload=0)
    register_procedure("Tools", "Log", log_s, public=True, overload=1)
    assert len([e for e in registered_procedures() if e.name == "Log"]) == 2


def test_overloads_in_two_modules_are_still_ambiguous_without_a_module() -> None:
    register_procedure("Tools", "Log", log_1, public=True, overload=0)
    register_procedure("Tools", "Log", log_2, public=True, overload=1)
    register_procedure("IO", "Log", log_s, public=True)
    assert code_of(find_procedure, "Log", nargs=1) == -772
    assert find_procedure("Log", "IO", nargs=1)("x") == "Log.s(x)"  # the caller's own first
    assert find_procedure("IO.Log", nargs=1)("x") == "Log.s(x)"


def test_a_lone_procedure_is_found_whatever_the_count() -> None:
    # its caller checks the parameters (a thread's -741, a delegate's -741) as before
    assert find_procedure("f0", nargs=3) is f0
