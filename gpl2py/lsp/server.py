"""``gpl2py lsp``: the language server, on pygls (the protocol) and lsprotocol (its types).

This module is the wiring only: the protocol's requests and notifications in, the workspace's
checks (:mod:`gpl2py.lsp.projects`) and a language's features (:data:`FEATURES`) called, the
answers converted to the protocol's types (:mod:`gpl2py.lsp.convert`).  What a feature knows of a
language lives in that language's module: ``gpl2py.lsp.gpl`` (a package) for GPL; V+ and TMscript
(``gpl2py.lsp.vplus``, ``gpl2py.lsp.tmscript``) have the outline (document and workspace symbols)
and get diagnostics through the door like GPL; a function a language's module lacks answers nothing.

Robustness: every handler runs inside :func:`guarded`, so an exception inside gpl2py is logged to
the client (``window/logMessage``, with its traceback) and the request answered with nothing; the
server goes on, and a half-typed file is only a file with syntax errors to the pipeline, which
contains a fault to the file it happened in.
"""

from __future__ import annotations

import asyncio
import importlib
import os
import traceback
from collections.abc import Callable
from types import ModuleType
from typing import Any, TypeVar

from lsprotocol import types as T
from pygls.exceptions import JsonRpcException
from pygls.lsp.server import LanguageServer
from pygls.uris import from_fs_path, to_fs_path

from gpl2py import __version__
from gpl2py.config import Config, ConfigError
from gpl2py.diagnostics import Diagnostic
from gpl2py.lsp import convert
from gpl2py.lsp.projects import CheckResult, ProjectState, Workspace

#: The module of each language's navigation features (hover, definition, completion ...), by the
#: front end's name (gpl2py.languages); a language without one gets diagnostics only.
FEATURES: dict[str, str] = {"gpl": "gpl2py.lsp.gpl", "vplus": "gpl2py.lsp.vplus", "tmscript": "gpl2py.lsp.tmscript"}
#: How long after the last change a file is checked (seconds); ``initializationOptions``'s
#: ``debounceMs`` changes it (0: at once, what the latency benchmark measures).
DEBOUNCE = 0.15
#: The extensions of the files the editor is asked to watch (each spelling a controller may use).
WATCHED = ("gpl", "gpo", "gpr", "GPL", "GPO", "GPR", "Gpl", "Gpr", "v2", "V2", "pg", "PG", "tms", "TMS", "tmscript")
#: The features that read the text being typed rather than the last check.
TYPING = ("completion", "signature_help")

R = TypeVar("R")


class GplServer(LanguageServer):
    """The server and what it holds: the workspace (projects, open texts), the pending checks."""

    def __init__(self) -> None:
        super().__init__("gpl2py", __version__)
        self.gpl = Workspace()
        self.debounce = DEBOUNCE
        self.pending: dict[str, asyncio.Task[None]] = {}
        self.published: dict[str, set[str]] = {}  # project -> the files it published to
        #: project -> file -> what was last published for it: (version, diagnostics, text)
        self.sent: dict[str, dict[str, tuple[int | None, list[Diagnostic], str]]] = {}

    # -- diagnostics ------------------------------------------------------------------------------

    def config(self) -> Config:
        try:
            return self.gpl.config()
        except ConfigError as exc:
            self.log(T.MessageType.Error, f"gpl2py: {exc}; checking without [tool.gpl2py]")
            return Config()

    def schedule(self, path: str) -> None:
        """Check the project of ``path`` once the edits pause (:data:`DEBOUNCE`)."""
        state = self.gpl.project_of(path)
        task = self.pending.pop(state.path, None)
        if task is not None:
            task.cancel()
        self.pending[state.path] = asyncio.ensure_future(self._check_later(state))

    async def _check_later(self, state: ProjectState) -> None:
        if self.debounce:
            await asyncio.sleep(self.debounce)
        self.pending.pop(state.path, None)
        self.check_now(state)

    def check_now(self, state: ProjectState) -> None:
        """Check ``state``'s project and publish every file's diagnostics."""
        result = guarded(self, "checking " + state.path, lambda: state.check(self.gpl.texts, self.config()))
        if result is not None:
            guarded(self, "publishing the diagnostics of " + state.path, lambda: self._publish(state, result))

    def _publish(self, state: ProjectState, result: CheckResult) -> None:
        """Publish the diagnostics of each file of the project that differ from those last
        published for it: other diagnostics, another text (their ranges are counted in its
        characters) or another version of the open document.  An edit usually changes one file's:
        publishing all fifteen of the TCS project after each edit was a fifth of a body edit's
        time (each notification serialised and written, each file's lines split)."""
        before = self.published.get(state.path, set())
        sent = self.sent.setdefault(state.path, {})
        now = set(result.by_file)
        for path in sorted(now | before):
            diags = result.by_file.get(path, [])
            text = result.files.get(path, "")
            uri = from_fs_path(path) or path
            doc = self.workspace.text_documents.get(uri)  # an open document: the version checked
            version = doc.version if doc is not None else None
            last = sent.get(path)
            if last is not None and last[0] == version and last[1] == diags and last[2] == text:
                continue
            lines = convert.lines_of(text)
            items = [convert.diagnostic(d, lines, self.workspace.position_codec) for d in diags]
            self.text_document_publish_diagnostics(T.PublishDiagnosticsParams(
                uri=uri, diagnostics=items, version=version))
            sent[path] = (version, diags, text)
        for path in before - now:
            sent.pop(path, None)
        self.published[state.path] = now

    def log(self, kind: T.MessageType, text: str) -> None:
        self.window_log_message(T.LogMessageParams(type=kind, message=text))

    # -- features ---------------------------------------------------------------------------------

    def features(self, uri: str, fresh: bool = True) -> tuple[ModuleType, ProjectState, str] | None:
        """The feature module, project and path of the document ``uri``, when its language has
        features.  ``fresh``: a check still waiting for the edits to pause is made now, so that
        positions are those of the text the editor shows (not for completion and signature help,
        which read the text being typed and come right after a keystroke)."""
        path = fs_path(uri)
        state = self.gpl.project_of(path)
        name = FEATURES.get(state.frontend.name)
        if name is None:
            return None
        waiting = self.pending.get(state.path)
        if state.last is None or (fresh and waiting is not None):
            if waiting is not None:
                waiting.cancel()
                self.pending.pop(state.path, None)
            self.check_now(state)
        return importlib.import_module(name), state, path


def fs_path(uri: str) -> str:
    return os.path.abspath(to_fs_path(uri) or uri)


def guarded(server: GplServer, doing: str, work: Callable[[], R]) -> R | None:
    """``work()``, or None after logging its exception to the client: the server goes on."""
    try:
        return work()
    except JsonRpcException:  # a request declined with a reason (a rename that would collide)
        raise
    except Exception as exc:  # noqa: BLE001 - an internal error must not stop the server
        if os.environ.get("GPL2PY_TRACEBACK"):
            raise
        server.log(T.MessageType.Error, f"gpl2py internal error while {doing}: {type(exc).__name__}: {exc}\n"
                   + "".join(traceback.format_exception(exc)))
        return None


def build() -> GplServer:
    """The server with every handler registered."""
    server = GplServer()

    @server.feature(T.INITIALIZE)
    def initialize(ls: GplServer, params: T.InitializeParams) -> None:
        root = params.root_uri or (params.workspace_folders[0].uri if params.workspace_folders else None)
        ls.gpl.root = fs_path(root) if root else (params.root_path or None)
        options = params.initialization_options if isinstance(params.initialization_options, dict) else {}
        if isinstance(options.get("debounceMs"), (int, float)):
            ls.debounce = max(0.0, float(options["debounceMs"]) / 1000)

    @server.feature(T.INITIALIZED)
    def initialized(ls: GplServer, params: T.InitializedParams) -> None:
        """Ask the editor to tell about sources changed on disk (a git checkout, another tool), when
        it can register watchers: the projects that hold them are checked again."""
        caps = ls.client_capabilities.workspace
        watched = caps.did_change_watched_files if caps is not None else None
        if watched is not None and watched.dynamic_registration:
            ls.client_register_capability(T.RegistrationParams(registrations=[T.Registration(
                id="gpl2py-sources", method=T.WORKSPACE_DID_CHANGE_WATCHED_FILES,
                register_options=T.DidChangeWatchedFilesRegistrationOptions(watchers=[
                    T.FileSystemWatcher(glob_pattern=f"**/*.{ext}") for ext in WATCHED]))]))

    @server.feature(T.WORKSPACE_DID_CHANGE_WATCHED_FILES)
    def watched_files(ls: GplServer, params: T.DidChangeWatchedFilesParams) -> None:
        for change in params.changes:
            path = fs_path(change.uri)
            if path in ls.gpl.texts:
                continue  # open in the editor: its text there is the one checked
            if any(k == path or k == os.path.dirname(path) for k in ls.gpl.projects):
                ls.schedule(path)  # (a project already held: its folder, or the file alone)

    @server.feature(T.TEXT_DOCUMENT_DID_OPEN)
    def did_open(ls: GplServer, params: T.DidOpenTextDocumentParams) -> None:
        path = fs_path(params.text_document.uri)
        ls.gpl.texts[path] = params.text_document.text
        ls.schedule(path)

    @server.feature(T.TEXT_DOCUMENT_DID_CHANGE)
    def did_change(ls: GplServer, params: T.DidChangeTextDocumentParams) -> None:
        path = fs_path(params.text_document.uri)
        doc = ls.workspace.get_text_document(params.text_document.uri)  # pygls applied the edits
        ls.gpl.texts[path] = doc.source
        ls.schedule(path)

    @server.feature(T.TEXT_DOCUMENT_DID_SAVE)
    def did_save(ls: GplServer, params: T.DidSaveTextDocumentParams) -> None:
        ls.schedule(fs_path(params.text_document.uri))

    @server.feature(T.TEXT_DOCUMENT_DID_CLOSE)
    def did_close(ls: GplServer, params: T.DidCloseTextDocumentParams) -> None:
        path = fs_path(params.text_document.uri)
        ls.gpl.texts.pop(path, None)  # the file on disk is the project's again
        ls.schedule(path)

    _register_features(server)
    return server


def _register_features(server: GplServer) -> None:
    """Each navigation request goes to the document's language module, guarded."""

    def route(method: str, name: str, options: Any = None) -> None:
        def handler(ls: GplServer, params: Any) -> Any:
            def work() -> Any:
                found = ls.features(params.text_document.uri, fresh=name not in TYPING)
                if found is None:
                    return None
                module, state, path = found
                fn = getattr(module, name, None)
                return fn(ls, state, path, params) if fn is not None else None

            return guarded(ls, method, work)

        handler.__name__ = name
        if options is None:
            server.feature(method)(handler)
        else:
            server.feature(method, options)(handler)

    route(T.TEXT_DOCUMENT_HOVER, "hover")
    route(T.TEXT_DOCUMENT_DEFINITION, "definition")
    route(T.TEXT_DOCUMENT_REFERENCES, "references")
    route(T.TEXT_DOCUMENT_DOCUMENT_HIGHLIGHT, "highlight")
    route(T.TEXT_DOCUMENT_DOCUMENT_SYMBOL, "document_symbols")
    route(T.TEXT_DOCUMENT_COMPLETION, "completion", T.CompletionOptions(trigger_characters=["."]))
    route(T.TEXT_DOCUMENT_SIGNATURE_HELP, "signature_help",
          T.SignatureHelpOptions(trigger_characters=["(", ","], retrigger_characters=[","]))
    route(T.TEXT_DOCUMENT_PREPARE_RENAME, "prepare_rename")
    route(T.TEXT_DOCUMENT_RENAME, "rename")
    route(T.TEXT_DOCUMENT_CODE_ACTION, "code_actions",
          T.CodeActionOptions(code_action_kinds=[T.CodeActionKind.QuickFix]))

    @server.feature(T.WORKSPACE_SYMBOL)
    def workspace_symbols(ls: GplServer, params: T.WorkspaceSymbolParams) -> list[T.WorkspaceSymbol] | None:
        def work() -> list[T.WorkspaceSymbol]:
            out: list[T.WorkspaceSymbol] = []
            for state in list(ls.gpl.projects.values()):
                name = FEATURES.get(state.frontend.name)
                if name is not None:
                    out.extend(importlib.import_module(name).workspace_symbols(ls, state, params.query))
            return out

        return guarded(ls, "workspace/symbol", work)


def serve() -> None:
    """Serve the protocol on stdin/stdout until the client says exit."""
    build().start_io()


__all__ = ["FEATURES", "GplServer", "build", "fs_path", "guarded", "serve"]
