"""How results show in Jupyter: the renderers register themselves for the result types.

The results (`InertiaTable`, `CollisionResult`) know nothing of HTML; `register()` tells
IPython's display system to draw them with the report's own tables. `import robotdesc` calls it
when IPython is running, so a notebook shows a table where a script sees `repr()`.
"""

from __future__ import annotations

import sys

from robotdesc.report.html import collision_result_html, inertia_rows_html

#: (module, class name) -> the function that draws it as HTML.
RENDERERS = {
    ("robotdesc.inertia.table", "InertiaTable"): lambda table: inertia_rows_html(table.rows),
    ("robotdesc.collision.result", "CollisionResult"): collision_result_html,
}


def html_of(value: object) -> str | None:
    """The HTML a notebook shows for a result, or None when robotdesc does not draw it."""
    renderer = RENDERERS.get((type(value).__module__, type(value).__name__))
    return renderer(value) if renderer else None


def register() -> None:
    """Register the renderers with the running IPython shell (nothing without one)."""
    ipython_module = sys.modules.get("IPython")
    shell = ipython_module.get_ipython() if ipython_module else None
    if shell is None:
        return
    formatter = shell.display_formatter.formatters["text/html"]
    for (module, name), renderer in RENDERERS.items():
        formatter.for_type_by_name(module, name, renderer)
