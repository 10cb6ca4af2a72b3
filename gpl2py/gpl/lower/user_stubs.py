"""``--stubs DIR``: Python implementations a user supplies for stubs (see semantics/stubs.py).

Convention (README "Porting your own project"), case-insensitive throughout:

* ``Module.Name`` of a protected module -> file ``module.py`` (the GPL module name, or its
  snake_case form: ``VendorLib`` -> ``vendorlib.py`` or ``vendor_lib.py``) defining ``Name``
  (a function for a procedure, a class for a class, a value for a variable);
* a bare protected name ``Foo`` -> ``Foo`` defined in any file of DIR (the first file in sorted
  order that defines it);
* an unknown built-in member ``Controller.Foo`` -> file ``controller.py`` defining ``Foo``; an
  instance member (``Robot.Bar`` on a Robot object) receives the object as its first argument, and
  an assigned member is set through ``set_Bar(obj, value)`` (Shared: ``set_Foo(value)``).

The files are read with :mod:`ast` (never imported at translation time) and copied verbatim into the
generated package as ``_user_<file>.py``, so the package stays self-contained.

gpl2py also ships stand-ins of its own for protected vendor code that real projects need on paths
every user takes (``gpl2py/gpl/standins/``: the TCS PARobot plug-in's ``PARobot_auto_center``).  They
follow the same convention, are copied as ``_standin_<file>.py``, and are used only for stubs that
the user's ``--stubs`` folder does not implement (:func:`with_shipped_standins`).
"""

from __future__ import annotations

import ast
import os
from dataclasses import dataclass, field
from pathlib import Path

from gpl2py import messages as M
from gpl2py.diagnostics import DiagnosticSink
from gpl2py.gpl.lower.names import snake_case
from gpl2py.gpl.semantics.stubs import Stub

#: gpl2py's own stand-ins (see the module docstring).
SHIPPED_DIR = Path(__file__).resolve().parent.parent / "standins"
USER_PREFIX = "_user_"
SHIPPED_PREFIX = "_standin_"

@dataclass
class UserFile:
    """One user stub file: its module-level names, lower-cased -> as spelled."""

    path: Path
    text: str
    names: dict[str, str] = field(default_factory=dict)
    prefix: str = USER_PREFIX

    @property
    def stem(self) -> str:
        return self.path.stem.lower()

    @property
    def package_module(self) -> str:
        """The module name of its copy in the generated package."""
        return f"{self.prefix}{snake_case(self.path.stem)}"

    @property
    def shipped(self) -> bool:
        """A stand-in shipped with gpl2py rather than one of the user's ``--stubs`` files."""
        return self.prefix == SHIPPED_PREFIX


@dataclass
class UserStubs:
    root: Path
    files: list[UserFile] = field(default_factory=list)

    def provider(self, stub: Stub) -> str | None:
        """Who implements ``stub``, for its warning: "the --stubs file vendorlib.py" or "gpl2py's
        stand-in parobot_auto_center.py"; None when nothing does."""
        found = self.find(stub)
        if found is None:
            return None
        file = found[0]
        return f"gpl2py's stand-in {file.path.name}" if file.shipped else f"the --stubs file {file.path.name}"

    def _files_for(self, qualifier: str) -> list[UserFile]:
        keys = {qualifier.lower(), snake_case(qualifier)}
        return [f for f in self.files if f.stem in keys]

    def find(self, stub: Stub, setter: bool = False) -> tuple[UserFile, str] | None:
        """The file and spelled name implementing ``stub`` (its ``set_`` companion if ``setter``)."""
        name = ("set_" + stub.member if setter else stub.member).lower()
        qualifier = stub.module or stub.builtin
        files = self._files_for(qualifier) if qualifier is not None else self.files
        for f in files:
            if name in f.names:
                return f, f.names[name]
        return None


def _top_level_names(tree: ast.Module) -> dict[str, str]:
    names: dict[str, str] = {}
    for node in tree.body:
        found: list[str] = []
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
            found.append(node.name)
        elif isinstance(node, ast.Assign):
            found.extend(t.id for t in node.targets if isinstance(t, ast.Name))
        elif isinstance(node, ast.AnnAssign) and isinstance(node.target, ast.Name):
            found.append(node.target.id)
        for n in found:
            names.setdefault(n.lower(), n)
    return names


def load_user_stubs(path: str | os.PathLike[str], sink: DiagnosticSink,
                    prefix: str = USER_PREFIX) -> UserStubs | None:
    """Read every ``*.py`` of ``path``; None (with error GPL3503) if the folder or a file is unusable."""
    root = Path(path)
    if not root.is_dir():
        what = "not a folder" if root.exists() else "no such folder"
        sink.report(M.STUBS_DIR_ERROR, None, path=str(path), detail=what)
        return None
    out = UserStubs(root)
    ok = True
    for file in sorted(root.glob("*.py"), key=lambda p: p.name.lower()):
        try:
            text = file.read_text(encoding="utf-8")
            tree = ast.parse(text, filename=str(file))
        except (OSError, UnicodeDecodeError, SyntaxError) as exc:
            sink.report(M.STUBS_DIR_ERROR, None, path=str(path), detail=f"{file.name}: {exc}")
            ok = False
            continue
        out.files.append(UserFile(file, text, _top_level_names(tree), prefix))
    return out if ok else None


def with_shipped_standins(user: UserStubs | None, sink: DiagnosticSink) -> UserStubs | None:
    """The user's stubs (if any) followed by gpl2py's shipped stand-ins: ``find`` tries the
    user's files first, so a ``--stubs`` implementation always wins over a shipped one."""
    shipped = load_user_stubs(SHIPPED_DIR, sink, SHIPPED_PREFIX) if SHIPPED_DIR.is_dir() else None
    if shipped is None or not shipped.files:
        return user
    if user is None:
        return shipped
    return UserStubs(user.root, [*user.files, *shipped.files])


__all__ = ["SHIPPED_DIR", "UserFile", "UserStubs", "load_user_stubs", "with_shipped_standins"]
