"""The one gate through which input text reaches generated Python (docs/security.md).

GPL source, Project.gpr, file names and folder names are untrusted: a project named
``x`` + three double quotes + ``;__import__("os").system(...)`` must stay a name.  Identifiers need no gate (the lexer
admits only ``[A-Za-z_][A-Za-z0-9_]*`` and :func:`gpl2py.gpl.lower.names.py_ident` maps them), but every
other piece of input text that lands in a generated file -- string literals, docstrings that name
the project or a source file, comments carried over from GPL -- goes through :func:`escape`, and
nothing else in lowering writes input text into a file.  ``tests/lower/test_text_gate.py`` feeds it
hostile text and compiles the result.

Three places, one function:

* ``"string"``: the body of a ``"..."`` literal.  Backslash and ``"`` are escaped, every control
  character and every code point above 126 becomes ``\\xNN``/``\\uNNNN``, so the literal is ASCII,
  stable and cannot end early.
* ``"docstring"``: the same escapes (no double quote survives, so none can close the docstring, and
  no backslash can start an escape the text did not mean).
* ``"comment"``: the text after ``#``.  Readable text, non-ASCII letters included, is kept as it
  is; what Python or an editor could take for the end of the line (CR, LF, VT, FF, the file, group
  and record separators, NEL, U+2028/U+2029) and the other C0 controls but TAB are shown as
  ``\\xNN``/``\\uNNNN``, so a comment can never carry code onto a line of its own.
"""

from __future__ import annotations

from typing import Literal

Context = Literal["string", "docstring", "comment"]

# Characters that end a line for Python's tokenizer, str.splitlines() or common editors.
_LINE_ENDS = frozenset("\n\r\x0b\x0c\x1c\x1d\x1e\x85\u2028\u2029")


def _code(ch: str) -> str:
    o = ord(ch)
    if o < 256:
        return f"\\x{o:02x}"
    if o < 0x10000:
        return f"\\u{o:04x}"
    return f"\\U{o:08x}"


_STRING_ESCAPES = {"\\": "\\\\", '"': '\\"', "\n": "\\n", "\r": "\\r", "\t": "\\t"}


def escape(text: str, context: Context) -> str:
    """``text`` made safe to write inside generated Python at ``context`` (see the module doc)."""
    if context == "comment":
        if text.isprintable() and not any(ch in _LINE_ENDS for ch in text):
            return text
        return "".join(_code(ch) if ch in _LINE_ENDS or (ord(ch) < 32 and ch != "\t") or ord(ch) == 127
                       else ch for ch in text)
    if context not in ("string", "docstring"):
        raise ValueError(f"unknown context {context!r}")
    if text.isascii() and text.isprintable() and "\\" not in text and '"' not in text:
        return text
    out: list[str] = []
    for ch in text:
        o = ord(ch)
        if ch in _STRING_ESCAPES:
            out.append(_STRING_ESCAPES[ch])
        elif o < 32 or o > 126:
            out.append(_code(ch))
        else:
            out.append(ch)
    return "".join(out)


def py_string(text: str) -> str:
    """A Python string literal for ``text`` (double quotes, ASCII, escapes for the rest)."""
    return '"' + escape(text, "string") + '"'


__all__ = ["Context", "escape", "py_string"]
