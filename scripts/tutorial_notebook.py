"""Write docs/tutorial.ipynb from docs/tutorial.py (the percent format: `# %%` starts a code
cell, `# %% [markdown]` a markdown cell whose lines lose their `# `), without outputs, so
that the notebook in the repository stays small and in step with the script.

    python scripts/tutorial_notebook.py          # rewrite docs/tutorial.ipynb
    python scripts/tutorial_notebook.py --check  # exit 1 when it is not in step

Plain JSON (nbformat 4.5): neither jupytext nor nbformat is needed to run it;
tests/test_tutorial.py validates the result with nbformat.
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SCRIPT = ROOT / "docs" / "tutorial.py"
NOTEBOOK = ROOT / "docs" / "tutorial.ipynb"

KERNEL = {"display_name": "Python 3", "language": "python", "name": "python3"}


def percent_cells(text: str) -> list[tuple[str, str]]:
    """The cells of a percent-format script as (kind, source); the header before the first
    cell marker (jupytext's metadata) is dropped."""
    cells: list[tuple[str, list[str]]] = []
    for line in text.splitlines():
        if line.startswith("# %%"):
            cells.append(("markdown" if "[markdown]" in line else "code", []))
        elif cells:
            cells[-1][1].append(line)
    found = []
    for kind, lines in cells:
        if kind == "markdown":
            lines = [line[2:] if line.startswith("# ") else line.lstrip("#") for line in lines]
        source = "\n".join(lines).strip("\n")
        if source:
            found.append((kind, source))
    return found


def notebook_json(text: str) -> str:
    """The notebook (JSON text ending with a newline) of a percent-format script."""
    cells = []
    for number, (kind, source) in enumerate(percent_cells(text)):
        lines = source.splitlines(keepends=True)
        cell: dict[str, object] = {"cell_type": kind, "id": f"cell-{number}", "metadata": {},
                                   "source": lines}
        if kind == "code":
            cell.update(execution_count=None, outputs=[])
        cells.append(cell)
    document = {"cells": cells,
                "metadata": {"kernelspec": KERNEL,
                             "language_info": {"name": "python"}},
                "nbformat": 4, "nbformat_minor": 5}
    return json.dumps(document, indent=1, ensure_ascii=False) + "\n"


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--check", action="store_true",
                        help="only say whether docs/tutorial.ipynb is in step (exit 1 if not)")
    check = parser.parse_args().check
    wanted = notebook_json(SCRIPT.read_text(encoding="utf-8"))
    current = NOTEBOOK.read_text(encoding="utf-8") if NOTEBOOK.is_file() else None
    if check:
        if current != wanted:
            sys.stderr.write(f"{NOTEBOOK} is not in step with {SCRIPT}: run "
                             "python scripts/tutorial_notebook.py\n")
            return 1
        return 0
    if current != wanted:
        NOTEBOOK.write_text(wanted, encoding="utf-8")
        sys.stderr.write(f"wrote {NOTEBOOK}\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
