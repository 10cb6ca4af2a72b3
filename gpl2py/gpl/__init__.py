"""The GPL front end: Brooks / Precise Automation GPL source -> Python on ``gplrt``.

One package per layer, as for every front end (docs/design/frontends.md):

* :mod:`gpl2py.gpl.syntax` -- characters to tokens to a dataclass syntax tree (lexer, parser, ast);
* :mod:`gpl2py.gpl.semantics` -- names, types, the controller's compile-time rules, the built-in
  catalogue;
* :mod:`gpl2py.gpl.lower` -- the checked tree as Python text, written through
  :mod:`gpl2py.pywriter`;
* :mod:`gpl2py.gpl.standins` -- Python shipped in place of protected vendor code.

What the front ends share lives beside this package: diagnostics and message codes
(:mod:`gpl2py.diagnostics`, :mod:`gpl2py.messages`), source positions (:mod:`gpl2py.source`),
project loading and input limits (:mod:`gpl2py.project`), the Python writer and source maps
(:mod:`gpl2py.pywriter`), and the command line.
"""
