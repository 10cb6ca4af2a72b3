"""The naming rules (gpl2py/gpl/lower/names.py, docs/security.md "Names"): one-to-one, and the
reserved-name table is what generated code really imports."""

from __future__ import annotations

import importlib
import keyword
import os
from pathlib import Path

from hypothesis import given, settings
from hypothesis import strategies as st

from gpl2py.diagnostics import DiagnosticSink
from gpl2py.gpl.lower.context import ProjectNames, Scope, builtin_names
from gpl2py.gpl.lower.names import PYTHON_NAMES, RUNTIME_IMPORTS, module_base, package_name, py_ident
from gpl2py.gpl.pipeline import LOCALS_KEY, MODEL_KEY
from gpl2py.transpile import transpile

# GPL identifiers: a letter or underscore, then letters, digits and underscores; hostile ones
# are Python keywords, builtins and dunders with underscores added anywhere
RESERVED_SAMPLE = sorted(PYTHON_NAMES)[:400]
gpl_names = st.one_of(
    st.from_regex(r"[A-Za-z_][A-Za-z0-9_]{0,12}", fullmatch=True),
    st.tuples(st.sampled_from(RESERVED_SAMPLE), st.sampled_from(["", "_", "__", "___"]),
              st.sampled_from(["", "_", "__"])).map(lambda t: t[2] + t[0] + t[1]),
)


@settings(max_examples=300, deadline=None, database=None)
@given(st.lists(gpl_names, min_size=2, max_size=30, unique=True))
def test_py_ident_is_one_to_one_and_never_reserved(names: list[str]) -> None:
    out = [py_ident(n) for n in names]
    assert len(set(out)) == len(out), list(zip(names, out))
    for n, p in zip(names, out):
        assert p.isidentifier() and not keyword.iskeyword(p) and p not in PYTHON_NAMES, (n, p)
        assert p.startswith("_u") if n.startswith("_") else not p.startswith("_")


def test_py_ident_keeps_ordinary_names() -> None:
    assert [py_ident(n) for n in ["MoveToPick", "list", "list_", "list__", "Station", "_x", "sys", "Cmd_"]] \
        == ["MoveToPick", "list_", "list__", "list___", "Station", "_u_x", "sys_", "Cmd_"]


def test_every_runtime_import_exists_in_the_runtime() -> None:
    # the table is what ModuleContext.helper allows: a name it lists must be importable, so the
    # reserved names are exactly what generated code can import
    for module, names in RUNTIME_IMPORTS.items():
        mod = importlib.import_module(module)
        missing = sorted(n for n in names if not hasattr(mod, n))
        assert not missing, (module, missing)
    builtins_mod = importlib.import_module("gplrt.builtins")
    assert sorted(n for n in builtin_names() if not hasattr(builtins_mod, n)) == []


def test_module_files_avoid_runtime_and_package_names() -> None:
    assert module_base("ChkInt32") == "chk_int32_mod"
    assert module_base("Current") == "current_mod"
    assert module_base("Main") == "main_mod"
    assert module_base("Con") == "con_mod"
    assert module_base("Globals") == "globals_"  # a builtin: the trailing underscore as before
    assert module_base("Station") == "station"


def test_packages_avoid_standard_and_runtime_modules() -> None:
    assert package_name("Numpy") == "numpy_gpl"
    assert package_name("json") == "json_gpl"
    assert package_name("gplrt") == "gplrt_gpl"
    assert package_name("tcp_cmd_server") == "tcp_cmd_server"
    assert package_name("") == "gpl_project"
    long_a, long_b = package_name("x" * 300), package_name("x" * 301)  # "File name too long" before
    assert len(long_a) <= 64 and long_a.startswith("xxxx") and long_a != long_b


def test_scope_hands_out_each_name_once_in_claim_order() -> None:
    scope = Scope({"a"})
    assert [scope.claim(n) for n in ["a", "a", "b", "a_2", "b"]] == ["a_2", "a_3", "b", "a_2_2", "b_2"]


def test_names_kept_between_checks_follow_a_procedure_checked_again(tmp_path: Path) -> None:
    """The language server's lowering keeps what it found among each procedure's locals
    (``LocalsTaken``, in the memo): after an edit adds a local named as a runtime import
    (``chk_int32``) or removes it again, the names a build keeps from the package's are a fresh
    build's -- the procedure checked again has a new locals table."""
    src = tmp_path / "M.gpl"
    plain = "Module M\n    Public Sub Main()\n        Dim a As Integer\n        a = 1\n    End Sub\nEnd Module\n"
    hiding = plain.replace("        a = 1\n", "        Dim chk_int32 As Integer\n        a = 1\n")
    src.write_text(plain)
    memo: dict[object, object] = {}
    seen = []
    for text in (plain, hiding, plain, hiding):
        sink = DiagnosticSink()
        transpile(tmp_path, sink, keep_modules=False, texts={os.path.abspath(src): text}, memo=memo)
        assert not sink.has_errors(), [d.header() for d in sink]
        model = memo[MODEL_KEY][2]  # type: ignore[index]
        kept = ProjectNames.build(model, kept=memo[LOCALS_KEY])  # type: ignore[arg-type]
        assert kept.taken == ProjectNames.build(model).taken
        seen.append("chk_int32" in kept.taken)
    assert seen == [False, True, False, True]
