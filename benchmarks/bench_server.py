"""`robotdesc server`: a save re-lints the Engineer from the caches, measured as an editor sees
it: the time from `didSave` to the `publishDiagnostics` that answers it, over stdio.

Input: a copy of robots/engineer_description with one finding added in an included macro file
(urdf/arm.xacro line 45: an axis of length 2), so that every save publishes diagnostics for
that file. The three config targets (matrix variants) are linted on each save.

- cold:  the first didOpen, with an empty cache (expansion of every variant, meshes, rules);
- save:  didSave of arm.xacro with the caches filled (median and max of --repeat saves);
- baseline: `robotdesc lint` of the same package as a whole process, warm caches (what an
  editor integration without a server would run on each save).

Aim (issue 19): a save re-lints in well under a second on the Engineer.

Usage: python benchmarks/bench_server.py [--repeat N]
"""

from __future__ import annotations

import argparse
import asyncio
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from lsprotocol import types
from pygls.lsp.client import LanguageClient

ENGINEER = Path(__file__).resolve().parents[1] / "robots" / "engineer_description"


def _prepare(folder: Path) -> Path:
    copy = folder / "engineer_description"
    shutil.copytree(ENGINEER, copy)
    arm = copy / "urdf" / "arm.xacro"
    lines = arm.read_text().splitlines(keepends=True)
    lines[44] = lines[44].replace('"0 0 1"', '"0 0 2"')
    arm.write_text("".join(lines))
    return arm


async def _measure(arm: Path, env: dict, repeat: int) -> tuple[float, list[float]]:
    client = LanguageClient("bench", "1")
    uri = "file://" + str(arm)
    arrived: asyncio.Queue = asyncio.Queue()

    @client.feature(types.TEXT_DOCUMENT_PUBLISH_DIAGNOSTICS)
    def on_diagnostics(params: types.PublishDiagnosticsParams) -> None:
        if params.uri == uri:
            arrived.put_nowait(time.perf_counter())

    await client.start_io(sys.executable, "-m", "robotdesc", "server", env=env)
    await client.initialize_async(types.InitializeParams(capabilities=types.ClientCapabilities()))
    client.initialized(types.InitializedParams())
    start = time.perf_counter()
    client.text_document_did_open(types.DidOpenTextDocumentParams(types.TextDocumentItem(
        uri=uri, language_id="xml", version=1, text=arm.read_text())))
    cold = await arrived.get() - start
    saves = []
    for _ in range(repeat):
        start = time.perf_counter()
        client.text_document_did_save(types.DidSaveTextDocumentParams(
            types.TextDocumentIdentifier(uri)))
        saves.append(await arrived.get() - start)
    await client.shutdown_async(None)
    client.exit(None)
    await client.stop()
    return cold, saves


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=10)
    ns = parser.parse_args()
    with tempfile.TemporaryDirectory() as folder:
        arm = _prepare(Path(folder))
        env = {**os.environ, "ROBOTDESC_CACHE_DIR": str(Path(folder) / "cache")}
        cold, saves = asyncio.run(_measure(arm, env, ns.repeat))
        runs = []
        for _ in range(3):
            start = time.perf_counter()
            subprocess.run([sys.executable, "-m", "robotdesc", "lint", str(arm.parents[1])],
                           env=env, capture_output=True)
            runs.append(time.perf_counter() - start)
    save = statistics.median(saves)
    baseline = statistics.median(runs)
    print(f"Engineer (3 variants), {ns.repeat} saves")
    print(f"  cold didOpen -> publishDiagnostics: {cold:.3f} s")
    print(f"  didSave -> publishDiagnostics: median {save:.3f} s, max {max(saves):.3f} s")
    print(f"  baseline `robotdesc lint` process, warm: median {baseline:.3f} s "
          f"(save is {save / baseline:.2f} x)")
    print(f"  aim: save < 1 s: {'met' if save < 1.0 else 'NOT met'}")


if __name__ == "__main__":
    main()
