"""gpl2py: transpile GPL robot-controller projects into Python packages that run on ``gplrt``.

Layers (each ignorant of the others' business):

* ``gpl2py.gpl.syntax``    characters -> tokens -> AST (lexer, parser)
* ``gpl2py.project``   Project.gpr / folder / single file -> ordered source set
* ``gpl2py.gpl.semantics`` names, scopes, static types, conversions
* ``gpl2py.gpl.lower``     typed AST -> Python source (a PEP 8 line writer, see docs/design/lowering.md)
* ``gpl2py.cli``       the ``gpl2py`` command
"""

__version__ = "0.1.0"
