"""The LSP protocol layer of `robotdesc server` (pygls, the optional extra `robotdesc[lsp]`).

On open and save of a .urdf/.xacro file it lints the descriptions the file belongs to and
publishes each finding in the file and at the line it points to (files reached only through
includes and macros too), with the macro call chain as related information; the file itself
always gets a publication, an empty list when it is clean. Code actions
apply the fixes of `robotdesc lint --fix` (unsafe ones marked), and "fix all" the safe ones.
"""

from __future__ import annotations

import importlib.metadata
import logging
import os
import urllib.parse
import urllib.request
from typing import Any

from lsprotocol import types
from pygls.lsp.server import LanguageServer

from robotdesc.diagnostics import Diagnostic, Severity
from robotdesc.server.session import SUFFIXES, FixAction, Session

log = logging.getLogger(__name__)

SOURCE = "robotdesc"
FIX_ALL = "source.fixAll.robotdesc"
_SEVERITY = {Severity.ERROR: types.DiagnosticSeverity.Error,
             Severity.WARNING: types.DiagnosticSeverity.Warning,
             Severity.INFO: types.DiagnosticSeverity.Information}


def uri_to_path(uri: str) -> str:
    parsed = urllib.parse.urlparse(uri)
    return os.path.abspath(urllib.request.url2pathname(parsed.path))


def path_to_uri(path: str) -> str:
    return "file://" + urllib.request.pathname2url(os.path.abspath(path))


def build_server(session: Session | None = None) -> LanguageServer:
    """The language server (not started)."""
    server = LanguageServer("robotdesc", _version())
    state = session or Session()
    published: set[str] = set()

    def relint(path: str) -> None:
        if not path.endswith(SUFFIXES):
            return
        for file, findings in state.lint(path).items():
            items = [_lsp_diagnostic(d) for d in findings]
            items += [_error_diagnostic(e) for e in state.errors(file)]
            # the file opened or saved always gets an answer, an empty list when it is clean
            # (so that "clean" does not look like "still linting"); others when they change
            if items or file in published or file == path:
                server.text_document_publish_diagnostics(types.PublishDiagnosticsParams(
                    uri=path_to_uri(file), diagnostics=items))
                (published.add if items else published.discard)(file)

    @server.feature(types.TEXT_DOCUMENT_DID_OPEN)
    def did_open(ls: LanguageServer, params: types.DidOpenTextDocumentParams) -> None:
        relint(uri_to_path(params.text_document.uri))

    @server.feature(types.TEXT_DOCUMENT_DID_SAVE)
    def did_save(ls: LanguageServer, params: types.DidSaveTextDocumentParams) -> None:
        relint(uri_to_path(params.text_document.uri))

    @server.feature(types.TEXT_DOCUMENT_CODE_ACTION, types.CodeActionOptions(
        code_action_kinds=[types.CodeActionKind.QuickFix, FIX_ALL]))
    def code_action(ls: LanguageServer, params: types.CodeActionParams
                    ) -> list[types.CodeAction]:
        path = uri_to_path(params.text_document.uri)
        lines = (params.range.start.line + 1, params.range.end.line + 1)
        only = params.context.only
        actions = []
        if not only or types.CodeActionKind.QuickFix in only:
            actions += [_code_action(a, types.CodeActionKind.QuickFix)
                        for a in state.fix_actions(path, lines)]
        fix_all = state.fix_all(path) if not only or FIX_ALL in only \
            or types.CodeActionKind.SourceFixAll in only else []
        if fix_all:
            merged = FixAction("Fix all safe robotdesc findings", fix_all[0].diagnostic, True,
                               tuple(e for a in fix_all for e in a.edits))
            actions.append(_code_action(merged, FIX_ALL))
        return actions

    return server


def _range(diagnostic: Diagnostic) -> types.Range:
    if diagnostic.where is None:  # not published: findings without a location have no file
        return types.Range(types.Position(0, 0), types.Position(1, 0))
    span = diagnostic.where.span
    line = max(span.line - 1, 0)
    column = max(span.col - 1, 0)
    return types.Range(types.Position(line, column), types.Position(line + 1, 0))


def _lsp_diagnostic(diagnostic: Diagnostic) -> types.Diagnostic:
    stack = diagnostic.where.macro_stack if diagnostic.where else ()
    related = [types.DiagnosticRelatedInformation(
        types.Location(path_to_uri(site.path), types.Range(
            types.Position(max(site.line - 1, 0), 0), types.Position(max(site.line, 1), 0))),
        "macro called here" if depth == 0 else "called from here")
        for depth, site in enumerate(stack)]
    message = diagnostic.message
    if diagnostic.target and diagnostic.where and diagnostic.where.span.path != diagnostic.target:
        message += f" (in {os.path.basename(diagnostic.target)})"
    return types.Diagnostic(range=_range(diagnostic), message=message,
                            severity=_SEVERITY[diagnostic.severity], code=diagnostic.code,
                            source=SOURCE, related_information=related or None,
                            data={"element": diagnostic.element, "name": diagnostic.name})


def _error_diagnostic(error: Any) -> types.Diagnostic:
    line = max(error.span.line - 1, 0)
    return types.Diagnostic(range=types.Range(types.Position(line, 0), types.Position(line + 1, 0)),
                            message=getattr(error, "message", str(error)),
                            severity=types.DiagnosticSeverity.Error, source=SOURCE)


def _code_action(action: FixAction, kind: str) -> types.CodeAction:
    changes: dict[str, list[types.TextEdit]] = {}
    for edit in action.edits:
        changes.setdefault(path_to_uri(edit.path), []).append(types.TextEdit(
            types.Range(types.Position(*edit.start), types.Position(*edit.end)), edit.text))
    return types.CodeAction(title=action.title, kind=kind,
                            diagnostics=[_lsp_diagnostic(action.diagnostic)],
                            is_preferred=action.safe, edit=types.WorkspaceEdit(changes=changes))


def _version() -> str:
    try:
        return importlib.metadata.version("robotdesc")
    except importlib.metadata.PackageNotFoundError:
        return "0"


def serve(session: Session | None = None) -> None:
    """Run the server on stdin/stdout until the client says exit."""
    build_server(session).start_io()
