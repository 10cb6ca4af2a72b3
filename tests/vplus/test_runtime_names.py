"""Every runtime name the V+ lowering can write exists in ``gplrt.vplus`` (docs/design/vplus-runtime.md
is the contract): each function of the semantic table and each instruction, lowered as the
lowering writes it, calls only attributes the runtime layer has -- a missing one would be a Python
AttributeError at run time instead of V+'s *Not implemented* (GPL4126)."""

from __future__ import annotations

import re

import gplrt.vplus as vp
from gpl2py.diagnostics import DiagnosticSink
from gpl2py.source import SourceFile
from gpl2py.vplus.lower.expressions import Exprs
from gpl2py.vplus.lower.instructions import instruction
from gpl2py.vplus.semantics.check import analyze
from gpl2py.vplus.semantics.types import FUNCTIONS
from gpl2py.vplus.syntax.keywords import GENERIC
from gpl2py.vplus.syntax.parser import parse

_ASSIGNED = {"TIMER", "PARAMETER", "SWITCH", "SELECT", "AIO.OUT", "KEYMODE", "DEFBELT", "SETBELT", "WINDOW",
             "DECOMPOSE", "BITS"}
_UNIT = {"ATTACH", "DETACH", "READ", "WRITE", "FOPEN", "FOPENR", "FOPENW", "FOPENA", "FOPEND", "FCLOSE",
         "FDELETE", "FEMPTY", "FSEEK", "FCMND", "SETDEVICE"}


def _lowered(line: str) -> str:
    sink = DiagnosticSink()
    module = parse(SourceFile("t.v2", f".PROGRAM p()\n  {line}\n.END\n"), sink)
    model = analyze([module], sink)
    x = Exprs(model, lambda sym: "v")
    stmt = module.programs[0].body[0]
    if line.startswith("x = "):
        return x.value(stmt.value)  # type: ignore[attr-defined]
    return instruction(stmt, x)  # type: ignore[arg-type]


def test_every_instruction_lowers_to_runtime_functions_that_exist() -> None:
    missing = []
    for word in sorted(GENERIC):
        line = f"{word} x = 1" if word in _ASSIGNED else f"{word} (1) 1" if word in _UNIT else f"{word} 1"
        for name in re.findall(r"vp\.(\w+)", _lowered(line)):
            if not hasattr(vp, name):
                missing.append((word, name))
    assert missing == []


def test_every_function_lowers_to_a_runtime_function_that_exists() -> None:
    missing = []
    for name in sorted(FUNCTIONS):
        sigil = name[0] if name[0] in "$#" else ""
        args = "(p BY 1)" if name in ("SHIFT", "SCALE") else "" if not FUNCTIONS[name][1] else "(1)"
        for called in re.findall(r"vp\.(\w+)", _lowered(f"x = {sigil}{name[len(sigil):]}{args}")):
            if not hasattr(vp, called):
                missing.append((name, called))
    assert missing == []
