"""A package's public names imported on first use (PEP 562), for the packages whose
`__init__` must stay cheap to import (the xacro worker, a warm lint, `robotdesc --version`).

    __getattr__, __dir__ = lazy_exports(__name__, {"Name": "module", ...})

`module` is the defining module's name relative to the package ("cache") or absolute
("robotdesc.config.schema"). A name is imported once, then kept in the package's namespace.
"""

from __future__ import annotations

import importlib
import sys
from collections.abc import Callable, Mapping


def lazy_exports(package: str, exports: Mapping[str, str]
                 ) -> tuple[Callable[[str], object], Callable[[], list[str]]]:
    """The package's `__getattr__` and `__dir__`.

    Args:
        package: the package's `__name__`.
        exports: public name -> the module defining it.
    """

    def getattr_(name: str) -> object:
        module = exports.get(name)
        if module is None:
            raise AttributeError(f"module {package!r} has no attribute {name!r}")
        full = module if module.startswith("robotdesc.") else f"{package}.{module}"
        value = getattr(importlib.import_module(full), name)
        setattr(sys.modules[package], name, value)
        return value

    def dir_() -> list[str]:
        return sorted(set(vars(sys.modules[package])) | set(exports))

    return getattr_, dir_
