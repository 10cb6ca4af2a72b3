"""``gpl2py lsp``: gpl2py's diagnostics, types and navigation in any editor, over the Language
Server Protocol (docs/editors.md; design: docs/design/lsp.md).

``projects`` holds the workspace (which project a file belongs to, each project's warm state);
``server`` wires the protocol to it; ``convert`` turns positions and diagnostics into the
protocol's terms; ``gpl`` is GPL's navigation (hover, definition, references, symbols,
completion, signature help, rename, code actions).  The protocol libraries are the ``lsp`` extra
(``pip install 'gpl2py[lsp]'``), imported only by ``gpl2py lsp``.
"""
