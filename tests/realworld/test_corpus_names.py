"""The vendor's TCP Command Server, read in place from the shared corpus (issue 11 items 5, 6, 9):
every name it declares resolves, and its Consts have the values a controller gives them.

The corpus is never copied: ``gpltest.corpus_dir`` finds it (``../shared/corpus`` or
``$GPL_CORPUS``); under ``CI=true`` a missing corpus fails these tests.
"""

from __future__ import annotations

import pytest

from gpl2py.gpl.semantics.info import BuiltinMemberInfo, VarInfo
from gpl2py.gpl.semantics.symbols import ClassSym, VarSym
from gpltest import analyze_project, corpus_dir

PROJECTS = ["tcs-3.0C1", "tcs-3.0C1-pa"]


def _declared_names(model: object) -> set[str]:
    """Every name the readable sources declare: modules, classes and their members."""
    project = model.project  # type: ignore[attr-defined]
    names = {m.name.lower() for m in project.module_list}
    for table in [m.members for m in project.modules.values()] + [c.members for c in project.classes]:
        names.update(table)
    return names


@pytest.mark.parametrize("name", PROJECTS)
def test_names_the_server_declares_all_resolve(name: str) -> None:
    model, sink = analyze_project(corpus_dir() / name)
    by_code: dict[str, list[str]] = {}
    for d in sink:
        by_code.setdefault(d.code, []).append(d.header())
    # not declared / 'Me' in a Shared procedure (a class Const) / assigning through CTL As Controller
    for code in ("GPL2001", "GPL2006", "GPL2021", "GPL2008"):
        assert code not in by_code, by_code[code]
    # a protected-code stub only for names no readable source declares (Command.AddPlugin,
    # Vector3.UnitX, GPV_TY_MAX ... were stubbed before)
    declared = _declared_names(model)
    stubbed = [d.message.split("'")[1] for d in sink if d.code == "GPL3501"]
    # (Module.Name of a module only the protected file declares is a stub rightly)
    wrongly = [s for s in stubbed if s.split(".")[0].lower() in declared]
    assert wrongly == [], wrongly


@pytest.mark.parametrize("name", PROJECTS)
def test_server_constants_have_their_values_whatever_the_module_order(name: str) -> None:
    model, _ = analyze_project(corpus_dir() / name)
    values = {(getattr(v.owner, "name", ""), v.name): value for v, value in model.const_values.items()}
    # Globals initialises before Startup (Project.gpr order); N_ROB sizes every per-robot array
    assert values[("Globals", "N_ROB")] == values[("Startup", "NumRobots")] == 4
    assert values[("GpoVar", "GPV_TY_MAX")] == 7
    assert values[("Station", "STA_FL_PAL")] == 1
    # GPL_Version needs the running controller's parameter database: computed at start-up
    consts = {(getattr(v.owner, "name", ""), v.name) for cls in model.project.classes for v in cls.fields()
              if isinstance(v, VarSym) and v.const}
    assert ("Command", "MAX_PLUGIN") in consts
    gpl_version = model.project.modules["globals"].members["gpl_version"]
    assert isinstance(gpl_version, VarSym) and gpl_version not in model.const_values


def test_a_controller_variable_of_the_plugin_is_the_controller_class() -> None:
    model, _ = analyze_project(corpus_dir() / "tcs-3.0C1-pa")
    ssgrip = model.project.modules["ssgrip"]
    ctl = ssgrip.members["ctl"]
    assert isinstance(ctl, VarSym) and str(ctl.type) == "Controller"
    through_ctl = [i for e, i in model.info.items() if isinstance(i, BuiltinMemberInfo)
                   and getattr(e, "target", None) is not None
                   and isinstance(model.info.get(e.target), VarInfo) and model.info[e.target].sym is ctl]
    assert through_ctl and all(i.static and i.receiver is None for i in through_ctl)
    assert not any(isinstance(c, ClassSym) and c.name == "Controller" for c in model.project.classes)
