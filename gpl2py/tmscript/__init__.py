"""The TMscript front end (Techman TM robots; issue 22, docs/design/tmscript.md).

``syntax`` reads a script (a script project or a Listen-node packet's statement list),
``semantics`` checks names and types, ``lower`` writes Python onto ``gplrt.tm``; ``pipeline`` is
what ``gpl2py.transpile`` calls, and ``translate_packet`` what the Listen node calls at run time.
"""
