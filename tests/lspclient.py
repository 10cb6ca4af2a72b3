"""A real LSP client for the language server's end-to-end tests: ``gpl2py lsp`` in a subprocess,
driven over stdio by pygls's own client (the protocol's framing, requests and notifications as an
editor sends them), behind synchronous methods a test can call.

Why not pytest-lsp: it drives the same pygls client, but through pytest-asyncio fixtures, a
plugin that would change how the rest of the suite's ~3,900 tests are collected; a loop of our
own per session is all these tests need.
"""

from __future__ import annotations

import asyncio
import os
import sys
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

from lsprotocol import types as T
from pygls.lsp.client import LanguageClient
from pygls.uris import from_fs_path

REPO = Path(__file__).resolve().parents[1]


def uri(path: Path | str) -> str:
    return from_fs_path(str(Path(path).absolute())) or str(path)


class Session:
    """One server, initialised for ``root``; ``diagnostics[uri]`` holds the last ones published
    for each file and ``logs`` what the server logged."""

    def __init__(self, root: Path, debounce_ms: int = 0, env: dict[str, str] | None = None,
                 capabilities: T.ClientCapabilities | None = None) -> None:
        self.loop = asyncio.new_event_loop()
        self.client = LanguageClient("gpl2py-tests", "1")
        self.diagnostics: dict[str, list[T.Diagnostic]] = {}
        self.published: list[tuple[float, str, int | None]] = []
        self.logs: list[str] = []
        self.versions: dict[str, int] = {}
        self.registrations: list[T.Registration] = []

        @self.client.feature(T.TEXT_DOCUMENT_PUBLISH_DIAGNOSTICS)
        def on_diagnostics(params: T.PublishDiagnosticsParams) -> None:
            self.diagnostics[params.uri] = list(params.diagnostics)
            self.published.append((time.perf_counter(), params.uri, params.version))

        @self.client.feature(T.WINDOW_LOG_MESSAGE)
        def on_log(params: T.LogMessageParams) -> None:
            self.logs.append(params.message)

        @self.client.feature(T.CLIENT_REGISTER_CAPABILITY)
        def on_register(params: T.RegistrationParams) -> None:
            self.registrations.extend(params.registrations)

        environ = {**os.environ, **(env or {})}
        environ.pop("GPL2PY_TRACEBACK", None)
        self.run(self.client.start_io(sys.executable, "-m", "gpl2py", "lsp", cwd=str(root), env=environ))
        self.run(self.client.initialize_async(T.InitializeParams(
            capabilities=capabilities or T.ClientCapabilities(), root_uri=uri(root),
            initialization_options={"debounceMs": debounce_ms})))
        self.client.initialized(T.InitializedParams())

    def run(self, coro: Any) -> Any:
        return self.loop.run_until_complete(coro)

    def close(self) -> None:
        try:
            self.run(asyncio.wait_for(self.client.shutdown_async(None), 30))
            self.client.exit(None)
            self.run(asyncio.wait_for(self.client.stop(), 30))
        finally:
            self.loop.close()

    def __enter__(self) -> Session:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    # -- documents ----------------------------------------------------------------------------------

    def open(self, path: Path, text: str | None = None) -> str:
        u = uri(path)
        self.versions[u] = 1
        self.client.text_document_did_open(T.DidOpenTextDocumentParams(T.TextDocumentItem(
            uri=u, language_id="gpl", version=1, text=path.read_text() if text is None else text)))
        return u

    def change(self, path: Path, text: str) -> None:
        """Replace the whole text (a full-document change)."""
        u = uri(path)
        self.versions[u] += 1
        self.client.text_document_did_change(T.DidChangeTextDocumentParams(
            T.VersionedTextDocumentIdentifier(uri=u, version=self.versions[u]),
            [T.TextDocumentContentChangeWholeDocument(text=text)]))

    def edit(self, path: Path, line: int, col: int, end_line: int, end_col: int, text: str) -> None:
        """An incremental change, 0-based positions, as an editor sends a keystroke."""
        u = uri(path)
        self.versions[u] += 1
        self.client.text_document_did_change(T.DidChangeTextDocumentParams(
            T.VersionedTextDocumentIdentifier(uri=u, version=self.versions[u]),
            [T.TextDocumentContentChangePartial(range=T.Range(T.Position(line, col), T.Position(end_line, end_col)),
                                                text=text)]))

    def wait(self, until: Callable[[], bool], timeout: float = 60.0) -> None:
        """Let the client's loop run until ``until()`` is true."""
        async def poll() -> None:
            deadline = time.monotonic() + timeout
            while not until():
                if time.monotonic() > deadline:
                    raise TimeoutError(f"the server did not answer in {timeout} s; its log: {self.logs}")
                await asyncio.sleep(0.005)
        self.run(poll())

    def wait_diagnostics(self, path: Path, after: int | None = None, timeout: float = 60.0) -> list[T.Diagnostic]:
        """The diagnostics of ``path``: for an open document, those of the version last sent
        (whenever they came); else the next ones published (after ``after`` publications)."""
        u = uri(path)
        version = self.versions.get(u)
        start = 0 if version is not None else len(self.published) if after is None else after
        self.wait(lambda: any(p == u and (version is None or (v or 0) >= version)
                              for _, p, v in self.published[start:]), timeout)
        return self.diagnostics[u]

    def settle(self) -> None:
        """Wait until the server has answered everything sent so far (a request round trip)."""
        self.run(self.client.workspace_symbol_async(T.WorkspaceSymbolParams(query="")))

    # -- requests -------------------------------------------------------------------------------------

    def _pos(self, path: Path, line: int, col: int) -> dict[str, Any]:
        return {"text_document": T.TextDocumentIdentifier(uri=uri(path)), "position": T.Position(line, col)}

    def hover(self, path: Path, line: int, col: int) -> T.Hover | None:
        return self.run(self.client.text_document_hover_async(T.HoverParams(**self._pos(path, line, col))))

    def definition(self, path: Path, line: int, col: int) -> Any:
        return self.run(self.client.text_document_definition_async(T.DefinitionParams(**self._pos(path, line, col))))

    def references(self, path: Path, line: int, col: int, declaration: bool = True) -> list[T.Location]:
        return self.run(self.client.text_document_references_async(T.ReferenceParams(
            **self._pos(path, line, col), context=T.ReferenceContext(include_declaration=declaration)))) or []

    def highlight(self, path: Path, line: int, col: int) -> list[T.DocumentHighlight]:
        return self.run(self.client.text_document_document_highlight_async(
            T.DocumentHighlightParams(**self._pos(path, line, col)))) or []

    def document_symbols(self, path: Path) -> list[Any]:
        return self.run(self.client.text_document_document_symbol_async(
            T.DocumentSymbolParams(text_document=T.TextDocumentIdentifier(uri=uri(path))))) or []

    def workspace_symbols(self, query: str) -> list[Any]:
        return self.run(self.client.workspace_symbol_async(T.WorkspaceSymbolParams(query=query))) or []

    def completion(self, path: Path, line: int, col: int) -> list[T.CompletionItem]:
        got = self.run(self.client.text_document_completion_async(T.CompletionParams(**self._pos(path, line, col))))
        return list(got.items if isinstance(got, T.CompletionList) else got or [])

    def signature_help(self, path: Path, line: int, col: int) -> T.SignatureHelp | None:
        return self.run(self.client.text_document_signature_help_async(
            T.SignatureHelpParams(**self._pos(path, line, col))))

    def rename(self, path: Path, line: int, col: int, new_name: str) -> T.WorkspaceEdit | None:
        return self.run(self.client.text_document_rename_async(
            T.RenameParams(**self._pos(path, line, col), new_name=new_name)))

    def code_actions(self, path: Path, line: int, diagnostics: list[T.Diagnostic]) -> list[Any]:
        return self.run(self.client.text_document_code_action_async(T.CodeActionParams(
            text_document=T.TextDocumentIdentifier(uri=uri(path)),
            range=T.Range(T.Position(line, 0), T.Position(line, 0)),
            context=T.CodeActionContext(diagnostics=diagnostics)))) or []


def apply_edits(text: str, edits: list[T.TextEdit]) -> str:
    """``text`` with ``edits`` (non-overlapping, ASCII) applied, as an editor would."""
    lines = text.split("\n")
    offsets = [0]
    for ln in lines:
        offsets.append(offsets[-1] + len(ln) + 1)

    def at(p: T.Position) -> int:
        return offsets[p.line] + p.character

    for e in sorted(edits, key=lambda e: at(e.range.start), reverse=True):
        text = text[:at(e.range.start)] + e.new_text + text[at(e.range.end):]
    return text
