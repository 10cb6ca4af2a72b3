"""V+ instructions without a construct of their own (:class:`ast.Instr`) -> one runtime call each.

One table says what each keyword becomes (docs/design/vplus-runtime.md §5-10): ``MOVE t`` is
``vp.move(t)``, ``SPEED 50 ALWAYS`` is ``vp.speed(50, always=True)``, ``WRITE (lun) $m, /S`` is
``vp.write(lun, s_m.v, vp.fmt("/S"))``.  A keyword not in the table calls the runtime function of
its name (``vp.<keyword>``), and a tier-3 keyword calls ``vp.unsupported`` (*Not implemented*).
"""

from __future__ import annotations

from gpl2py.pywriter.text import py_string
from gpl2py.vplus.lower.expressions import Exprs
from gpl2py.vplus.lower.names import runtime_name
from gpl2py.vplus.syntax import ast as A
from gpl2py.vplus.syntax.keywords import UNSIMULATED

#: Keywords whose call takes no arguments, by runtime name.
_BARE = {
    "READY": "ready", "ALIGN": "align", "BREAK": "break_", "BRAKE": "brake", "OPEN": "open_", "OPENI": "openi",
    "CLOSE": "close", "CLOSEI": "closei", "RELAX": "relax", "RELAXI": "relaxi", "RESET": "reset",
    "HALT": "halt", "STOP": "stop", "PAUSE": "pause", "WAIT.START": "wait_start", "PROCEED": "proceed",
}
_CONFIG = frozenset("ABOVE BELOW LEFTY RIGHTY FLIP NOFLIP".split())
_MODIFIER = frozenset("COARSE FINE NULL NONULL OVERLAP NOOVERLAP SINGLE MULTIPLE".split())


def instruction(s: A.Instr, x: Exprs) -> str:  # noqa: C901 (one table of keywords)
    """The Python statement of ``s``."""
    word = s.word
    if s.tier3 or word in UNSIMULATED:  # the runtime's *Not implemented*, naming it
        return f"vp.unsupported({py_string(word)})"
    if word == "SELECT" and s.target and _system_name(s.target[0]) != "ROBOT":
        return f"vp.unsupported({py_string('SELECT ' + _system_name(s.target[0]))})"
    if word in ("ENABLE", "DISABLE"):  # (switch names, not variables)
        names = ", ".join(py_string(_system_name(a)) for a in s.args)
        return f"vp.{word.lower()}({names})"
    always = "ALWAYS" in s.modifiers
    args = [x.value(a) if a is not None else "None" for a in s.args]
    unit = [x.value(a) if a is not None else "None" for a in s.unit or []]
    if word in _BARE:
        return f"vp.{_BARE[word]}({', '.join(args)})"
    if word in _CONFIG:
        return f"vp.config({py_string(word)})"
    if word in _MODIFIER:
        return f"vp.modifier({py_string(word)}{', always=True' if always else ''})"
    if word in ("CPON", "CPOFF"):
        return f"vp.cp({word == 'CPON'})"
    if word == "SPEED":
        unit_word = next((m for m in s.modifiers if m != "ALWAYS"), None)
        values = list(args)
        if len(s.args) > 1 and isinstance(s.args[1], A.Str):  # SPEED v, "MONITOR": the sandbox's MONITOR
            unit_word, values = s.args[1].value.upper(), values[:1]
        extra = ([f"unit={py_string(unit_word)}"] if unit_word else []) + (["always=True"] if always else [])
        return f"vp.speed({', '.join(values + extra)})"
    if word == "DURATION":
        return f"vp.duration({', '.join(args + (['always=True'] if always else []))})"
    if word == "ACCEL":
        return f"vp.accel({', '.join(args)})"
    if word == "WAIT":
        if not s.args or s.args[0] is None:
            return "vp.wait()"
        return f"vp.wait_for(lambda: {x.condition(s.args[0])})"
    if word == "WAIT.EVENT":
        return f"vp.wait_event({', '.join((args + ['None', 'None'])[:2])})"
    if word == "TIMER" and s.target is not None:
        return f"vp.timer_set({_values(s.target, x)}, {', '.join(args)})"
    if word in ("PARAMETER", "SWITCH") and s.target is not None:
        name = _system_name(s.target[0])
        index = _system_index(s.target[0], x)
        return f"vp.{word.lower()}_set({py_string(name)}, {', '.join(args)}{index})"
    if word == "SELECT" and s.target is not None:
        return f"vp.select_{_system_name(s.target[0]).lower()}({', '.join(args)})"
    if word == "DECOMPOSE" and s.target:
        target = s.target[0]
        assert isinstance(target, A.Var)
        sym = x.model.symbol_of[id(target)]
        first = x.value(target.index[0]) if target.index else "0"
        return f"vp.decompose({x.var(sym)}, {first}, {', '.join(args)})"
    if word == "SIGNAL":
        return f"vp.signal({', '.join(args)})"
    if word == "BITS" and s.target is not None:
        return f"vp.bits_set({_values(s.target, x)}, {', '.join(args)})"
    if word == "ATTACH":
        if not s.unit:
            return "vp.attach(0)"
        lun = s.unit[0]
        first = x.ref(lun) if isinstance(lun, A.Var) and len(s.unit) > 1 and _mode(s.unit[1]) == 4 else unit[0]
        rest = unit[1:] + args
        return f"vp.attach({', '.join([first] + rest)})"
    if word in ("DETACH", "FCLOSE", "FEMPTY"):
        return f"vp.{runtime_name(word)}({', '.join(unit or ['0'])})"
    if word == "READ":
        refs = [x.ref(a) if isinstance(a, A.Var) else x.argument(a) for a in s.args]
        mode = [f"mode={unit[1]}"] if len(unit) > 1 else []
        return f"vp.read({', '.join(unit[:1] + refs + mode)})"
    if word == "PROMPT":
        refs = [x.ref(a) if isinstance(a, A.Var) else x.value(a) if a is not None else "None" for a in s.args]
        return f"vp.prompt({', '.join(refs)})"
    if word == "FOPEN":
        mode = [f"mode={unit[1]}"] if len(unit) > 1 else []
        return f"vp.fopen({', '.join(unit[:1] + args + mode)})"
    if word in ("WRITE", "FOPENR", "FOPENW", "FOPENA", "FOPEND", "FDELETE", "FCMND", "FSEEK", "SETDEVICE"):
        return f"vp.{runtime_name(word)}({', '.join(unit + args)})"
    if word in ("MOVET", "MOVEST"):  # MOVE/MOVES with the hand set as the motion starts
        hand = x.condition(s.args[1]) if len(s.args) > 1 and s.args[1] is not None else "False"
        set_hand = {"True": "vp.open_()", "False": "vp.close()"}.get(hand, f"vp.open_() if {hand} else vp.close()")
        return f"{set_hand}\nvp.{word[:-1].lower()}({args[0]})"
    if word == "TOOL" and s.args:
        return f"vp.tool({args[0]})"
    fn = runtime_name(word)
    target = [x.value(a) if a is not None else "None" for a in s.target or []]
    return f"vp.{fn}({', '.join(unit + target + args)})"


def _values(items: list[A.Expr | None], x: Exprs) -> str:
    return ", ".join(x.value(a) if a is not None else "None" for a in items)


def _system_name(e: A.Expr | None) -> str:
    """The name of a parameter or switch as written (``HAND.TIME``)."""
    if isinstance(e, A.Var):
        return e.shown.upper()
    if isinstance(e, A.Call):
        return (e.sigil + e.name).upper()
    return "?"


def _system_index(e: A.Expr | None, x: Exprs) -> str:
    if isinstance(e, A.Var) and e.index:
        return f", index={x.value(e.index[0])}"
    return ""


def _mode(e: A.Expr | None) -> float | None:
    return e.value if isinstance(e, A.Num) else None
