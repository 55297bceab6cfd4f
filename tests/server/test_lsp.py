"""`robotdesc server` driven by a real LSP client (pygls's) over stdio: initialize, didOpen,
publishDiagnostics at the right file and line (a file reached only through an include and a
macro), and a code action whose edit changes exactly the right text."""

from __future__ import annotations

import asyncio
import os
import shutil
import sys
from pathlib import Path

import pytest

pytest.importorskip("pygls")
from lsprotocol import types  # noqa: E402
from pygls.lsp.client import LanguageClient  # noqa: E402

from robotdesc.server.lsp import path_to_uri  # noqa: E402

ENGINEER = Path(__file__).resolve().parents[2] / "robots" / "engineer_description"
TIMEOUT = 120.0


@pytest.fixture()
def engineer(tmp_path: Path) -> Path:
    """A copy of the Engineer with one mistake in arm.xacro (an axis of length 2)."""
    copy = tmp_path / "engineer_description"
    shutil.copytree(ENGINEER, copy)
    arm = copy / "urdf" / "arm.xacro"
    text = arm.read_text()
    assert '      <axis xyz="0 0 1"/>\n' in text.splitlines(keepends=True)[44]
    lines = text.splitlines(keepends=True)
    lines[44] = lines[44].replace('"0 0 1"', '"0 0 2"')
    arm.write_text("".join(lines))
    return copy


async def _session(package: Path, cache: Path) -> dict:
    client = LanguageClient("test-client", "1")
    published: dict[str, list[types.Diagnostic]] = {}
    arrived = asyncio.Event()

    @client.feature(types.TEXT_DOCUMENT_PUBLISH_DIAGNOSTICS)
    def on_diagnostics(params: types.PublishDiagnosticsParams) -> None:
        published[params.uri] = params.diagnostics
        arrived.set()

    env = {**os.environ, "ROBOTDESC_CACHE_DIR": str(cache)}
    await client.start_io(sys.executable, "-m", "robotdesc", "server", env=env)
    try:
        reply = await client.initialize_async(types.InitializeParams(
            capabilities=types.ClientCapabilities(), root_uri=path_to_uri(str(package))))
        assert reply.capabilities.code_action_provider
        client.initialized(types.InitializedParams())
        arm = package / "urdf" / "arm.xacro"
        uri = path_to_uri(str(arm))
        client.text_document_did_open(types.DidOpenTextDocumentParams(types.TextDocumentItem(
            uri=uri, language_id="xml", version=1, text=arm.read_text())))
        await asyncio.wait_for(_until(lambda: uri in published, arrived), TIMEOUT)
        found = [d for d in published[uri] if d.code == "J107"]
        actions = await client.text_document_code_action_async(types.CodeActionParams(
            text_document=types.TextDocumentIdentifier(uri),
            range=types.Range(types.Position(44, 0), types.Position(44, 0)),
            context=types.CodeActionContext(diagnostics=found,
                                            only=[types.CodeActionKind.QuickFix])))
        await client.shutdown_async(None)
        client.exit(None)
        return {"uri": uri, "published": published, "found": found, "actions": actions}
    finally:
        await client.stop()


async def _until(condition, event: asyncio.Event) -> None:
    while not condition():
        event.clear()
        await event.wait()


def test_server_publishes_a_finding_in_an_included_macro_file_and_fixes_it(engineer,
                                                                            tmp_path):
    answer = asyncio.run(_session(engineer, tmp_path / "cache"))
    found = answer["found"]
    assert len(found) == 1
    diagnostic = found[0]
    assert diagnostic.range.start.line == 44  # arm.xacro line 45, 0-based
    assert diagnostic.source == "robotdesc"
    related = diagnostic.related_information or []
    assert related and related[0].location.uri.endswith("engineer.urdf.xacro")
    actions = [a for a in answer["actions"] if "J107" in a.title]
    assert len(actions) == 1
    edits = actions[0].edit.changes[answer["uri"]]
    assert len(edits) == 1
    edit = edits[0]
    line = (engineer / "urdf" / "arm.xacro").read_text().splitlines()[44]
    assert edit.range.start.line == edit.range.end.line == 44
    assert line[edit.range.start.character:edit.range.end.character] == "0 0 2"
    assert edit.new_text == "0 0 1"


CLEAN = """<?xml version="1.0"?>
<robot name="clean">
  <link name="base">
    <inertial><mass value="1"/>
      <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>
  </link>
</robot>
"""


async def _open_and_collect(path: Path, cache: Path) -> dict[str, list[types.Diagnostic]]:
    client = LanguageClient("test-client", "1")
    published: dict[str, list[types.Diagnostic]] = {}
    arrived = asyncio.Event()

    @client.feature(types.TEXT_DOCUMENT_PUBLISH_DIAGNOSTICS)
    def on_diagnostics(params: types.PublishDiagnosticsParams) -> None:
        published[params.uri] = params.diagnostics
        arrived.set()

    env = {**os.environ, "ROBOTDESC_CACHE_DIR": str(cache)}
    await client.start_io(sys.executable, "-m", "robotdesc", "server", env=env)
    try:
        await client.initialize_async(types.InitializeParams(
            capabilities=types.ClientCapabilities()))
        client.initialized(types.InitializedParams())
        uri = path_to_uri(str(path))
        client.text_document_did_open(types.DidOpenTextDocumentParams(types.TextDocumentItem(
            uri=uri, language_id="xml", version=1, text=path.read_text())))
        await asyncio.wait_for(_until(lambda: uri in published, arrived), TIMEOUT)
        await client.shutdown_async(None)
        client.exit(None)
        return published
    finally:
        await client.stop()


def test_a_clean_file_gets_an_empty_list_not_silence(tmp_path: Path) -> None:
    """An editor shows "no problems" rather than "still linting" (issue 34, item 4)."""
    robot = tmp_path / "clean" / "clean.urdf"
    robot.parent.mkdir()
    robot.write_text(CLEAN)
    published = asyncio.run(_open_and_collect(robot, tmp_path / "cache"))
    assert {uri: list(found) for uri, found in published.items()} == {
        path_to_uri(str(robot)): []}


def test_an_unchanged_description_is_read_from_the_result_cache(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    from robotdesc.linting import parallel
    from robotdesc.server.session import Session

    monkeypatch.setenv("ROBOTDESC_CACHE_DIR", str(tmp_path / "cache"))
    robot = tmp_path / "r" / "broken.urdf"
    robot.parent.mkdir()
    robot.write_text(CLEAN.replace('ixx="0.01"', 'ixx="-0.01"'))
    os.utime(robot, ns=(1_600_000_000 * 10**9,) * 2)
    first = Session().lint(str(robot))[str(robot)]
    assert first

    def refuse(*args: object, **kwargs: object) -> None:
        raise AssertionError("linted although nothing changed")

    monkeypatch.setattr(parallel, "lint_file", refuse)
    assert Session().lint(str(robot))[str(robot)] == first
