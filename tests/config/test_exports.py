"""`robotdesc.config` exports its names lazily (PEP 562): each listed name resolves to the
object of the module that defines it, and importing the package imports none of them."""

from __future__ import annotations

import subprocess
import sys

import robotdesc.config as config


def test_every_exported_name_resolves() -> None:
    assert sorted(config.__all__) == sorted(config._EXPORTS)
    for name in config.__all__:
        assert getattr(config, name) is not None


def test_importing_the_config_finder_loads_no_schema() -> None:
    probe = ("import sys, robotdesc.config.files; "
             "print(sorted(m for m in sys.modules if m.startswith('robotdesc.config')))")
    done = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True,
                          check=True)
    assert done.stdout.strip() == "['robotdesc.config', 'robotdesc.config.files', " \
                                  "'robotdesc.config.parse']"
