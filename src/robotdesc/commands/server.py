"""`robotdesc server`: the language server over stdio (needs the extra `robotdesc[lsp]`)."""

from __future__ import annotations

import argparse
import logging
import os
from typing import Any

from robotdesc.errors import UsageError
from robotdesc.expansion import ExpandOptions

log = logging.getLogger(__name__)


def register(commands: Any, *, common: argparse.ArgumentParser,
             expansion: argparse.ArgumentParser) -> None:
    parser = commands.add_parser(
        "server", parents=[common, expansion], help="run the language server (LSP, stdio)",
        description="A language server over stdin/stdout for .urdf and .xacro files: findings "
                    "at their file and line (through includes and macros) on open and save, "
                    "and code actions that apply `lint --fix`'s fixes. Needs "
                    "the extra `lsp` (pygls); see docs/editors.md.")
    parser.add_argument("--stdio", action="store_true",
                        help="accepted for editors that pass it (stdio is the only transport)")
    parser.set_defaults(handler=run)


def run(ns: argparse.Namespace) -> int:
    try:
        from robotdesc.server.lsp import serve
    except ImportError as error:
        raise UsageError(f"robotdesc server needs pygls ({error}); install it with "
                         "python -m pip install '.[lsp]' (from the clone)") from None
    from robotdesc.server.session import Session

    if ns.timeout <= 0:
        raise UsageError("--timeout must be positive")
    options = ExpandOptions(package_paths=tuple(os.path.abspath(p) for p in ns.package_path),
                            trusted=ns.trusted, use_cache=not ns.no_cache,
                            timeout_s=ns.timeout, env_allowlist=tuple(ns.env))
    log.info("robotdesc language server on stdio")
    serve(Session(options))
    return 0
