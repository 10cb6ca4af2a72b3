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
"""

from __future__ import annotations

import ast
import os
from dataclasses import dataclass, field
from pathlib import Path

from gpl2py import messages as M
from gpl2py.diagnostics import DiagnosticSink
from gpl2py.lower.names import snake_case
from gpl2py.semantics.stubs import Stub


@dataclass
class UserFile:
    """One user stub file: its module-level names, lower-cased -> as spelled."""

    path: Path
    text: str
    names: dict[str, str] = field(default_factory=dict)

    @property
    def stem(self) -> str:
        return self.path.stem.lower()

    @property
    def package_module(self) -> str:
        """The module name of its copy in the generated package."""
        return f"_user_{snake_case(self.path.stem)}"


@dataclass
class UserStubs:
    root: Path
    files: list[UserFile] = field(default_factory=list)

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


def load_user_stubs(path: str | os.PathLike[str], sink: DiagnosticSink) -> UserStubs | None:
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
        out.files.append(UserFile(file, text, _top_level_names(tree)))
    return out if ok else None


__all__ = ["UserFile", "UserStubs", "load_user_stubs"]
