"""GPL's navigation for the language server, read off the last check's analysis.

``index`` (where each name is written and what the checker made of it), ``describe`` (how a
symbol reads), ``navigation`` (hover, definition, references, highlight), ``symbols`` (outline,
workspace symbols), ``complete`` (completion, signature help), ``edits`` (rename, quick fixes).
The server calls the functions below by name for a GPL file (``gpl2py.lsp.server.FEATURES``); a
V+ or TMscript module would offer the same ones.
"""

from gpl2py.lsp.gpl.complete import completion, signature_help
from gpl2py.lsp.gpl.edits import code_actions, prepare_rename, rename
from gpl2py.lsp.gpl.navigation import definition, highlight, hover, references
from gpl2py.lsp.gpl.symbols import document_symbols, workspace_symbols

__all__ = ["code_actions", "completion", "definition", "document_symbols", "highlight", "hover", "prepare_rename",
           "references", "rename", "signature_help", "workspace_symbols"]
