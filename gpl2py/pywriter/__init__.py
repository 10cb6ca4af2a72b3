"""The Python writer every front end's lowering emits through (docs/design/frontends.md).

Language-neutral: it knows Python's layout rules, not GPL's, V+'s or TMscript's.

* :mod:`~gpl2py.pywriter.emit` -- lines with indentation, comments and their source lines;
* :mod:`~gpl2py.pywriter.wrap` -- breaking long lines the PEP 8 way;
* :mod:`~gpl2py.pywriter.text` -- the one gate through which input text reaches generated Python;
* :mod:`~gpl2py.pywriter.sourcemap` -- the ``_sourcemap.json`` that maps Python lines back to source.
"""
