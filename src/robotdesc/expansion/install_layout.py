"""A package's installed layout, read from its CMakeLists.txt, for descriptions read from source.

`$(find pkg)` and `package://pkg/` name a package's *installed* share folder. Most description
packages install their folders as they are (`install(DIRECTORY urdf meshes DESTINATION
share/${PROJECT_NAME})`), so the source folder stands in for the installed one. Some move them:
ros2_control_demos installs `description/ros2_control` as `share/<pkg>/ros2_control`, and its
descriptions include `$(find pkg)/ros2_control/...`, a path that exists only after `colcon
build`. This module maps such a path back to the source file, from the package's own install
rules:

- `install(DIRECTORY a/b c/ ... DESTINATION share/${PROJECT_NAME}[/sub])` (catkin's
  `${CATKIN_PACKAGE_SHARE_DESTINATION}` too): `a/b` is installed as `[sub/]b`, the contents of
  `c/` directly under `[sub/]`;
- `install(FILES a/x.xacro DESTINATION share/${PROJECT_NAME}/urdf)`: `urdf/x.xacro`;
- `ament_auto_package(INSTALL_TO_SHARE a/b c)`: `b` and `c`.

Only text is read (no CMake is run); rules it cannot read are ignored.
"""

from __future__ import annotations

import functools
import os
import re
from dataclasses import dataclass

#: The largest CMakeLists.txt read (real ones are a few kB).
_MAX_BYTES = 1 << 20
_COMMENT = re.compile(r"#[^\n]*")
_CALL = re.compile(r"\b(install|ament_auto_package)\s*\(([^()]*)\)", re.IGNORECASE)
_SHARE = re.compile(r"^share/(?:\$\{PROJECT_NAME\}|(?P<name>[A-Za-z0-9_\-]+))(?:/(?P<sub>.*))?$|"
                    r"^\$\{CATKIN_PACKAGE_SHARE_DESTINATION\}(?:/(?P<catkin_sub>.*))?$")
_KEYWORDS = {"DESTINATION", "FILES_MATCHING", "PATTERN", "REGEX", "EXCLUDE", "PERMISSIONS",
             "USE_SOURCE_PERMISSIONS", "FILE_PERMISSIONS", "DIRECTORY_PERMISSIONS",
             "CONFIGURATIONS", "COMPONENT", "OPTIONAL", "MESSAGE_NEVER", "RENAME",
             "EXCLUDE_FROM_ALL", "TYPE", "INSTALL_TO_SHARE"}


@dataclass(frozen=True)
class InstallRule:
    """One installed path and where it comes from, both relative to the package folder.

    Attributes:
        installed: the path under `share/<pkg>/` ("ros2_control"; "" for the share root).
        source: the path in the source package ("description/ros2_control").
        directory: True for a folder (paths below it map too), False for one file.
    """

    installed: str
    source: str
    directory: bool


def _arguments(text: str) -> list[str]:
    return [token.strip('"') for token in text.split()]


def _share_subfolder(destination: str, package: str) -> str | None:
    """The folder under the package's share directory a DESTINATION names, or None."""
    match = _SHARE.match(destination.strip('"').rstrip("/"))
    if match is None or (match.group("name") and match.group("name") != package):
        return None
    return (match.group("sub") or match.group("catkin_sub") or "").strip("/")


def parse_install_rules(cmake_text: str, package: str) -> tuple[InstallRule, ...]:
    """The share-folder install rules of a CMakeLists.txt's text (see the module's doc)."""
    rules: list[InstallRule] = []
    for call, body in _CALL.findall(_COMMENT.sub("", cmake_text)):
        words = _arguments(body)
        if call.lower() == "ament_auto_package":
            if "INSTALL_TO_SHARE" in words:
                start = words.index("INSTALL_TO_SHARE") + 1
                for word in _until_keyword(words[start:]):
                    rules.append(_directory_rule(word, ""))
            continue
        if not words or words[0] not in ("DIRECTORY", "FILES") or "DESTINATION" not in words:
            continue
        sub = _share_subfolder(words[words.index("DESTINATION") + 1]
                               if words.index("DESTINATION") + 1 < len(words) else "", package)
        if sub is None:
            continue
        for word in _until_keyword(words[1:]):
            if "$" in word or os.path.isabs(word) or ".." in word.split("/"):
                continue
            if words[0] == "DIRECTORY":
                rules.append(_directory_rule(word, sub))
            else:
                rules.append(InstallRule(_join(sub, os.path.basename(word)), word, False))
    return tuple(rules)


def _until_keyword(words: list[str]) -> list[str]:
    taken: list[str] = []
    for word in words:
        if word in _KEYWORDS:
            break
        taken.append(word)
    return taken


def _directory_rule(word: str, sub: str) -> InstallRule:
    source = word.rstrip("/")
    installed = sub if word.endswith("/") else _join(sub, os.path.basename(source))
    return InstallRule(installed, source, True)


def _join(first: str, second: str) -> str:
    return f"{first}/{second}" if first and second else first or second


@functools.lru_cache(maxsize=64)
def install_rules(package_dir: str, package: str) -> tuple[InstallRule, ...]:
    """The install rules of the package in `package_dir` (none without a CMakeLists.txt)."""
    path = os.path.join(package_dir, "CMakeLists.txt")
    try:
        with open(path, "rb") as stream:
            data = stream.read(_MAX_BYTES)
    except OSError:
        return ()
    return parse_install_rules(data.decode("utf-8", "replace"), package)


def source_of_installed(package_dir: str, package: str, relative: str) -> str | None:
    """The source file that `share/<package>/<relative>` is installed from, when it exists
    and differs from `<package_dir>/<relative>`; None otherwise."""
    relative = relative.strip("/")
    for rule in install_rules(package_dir, package):
        if rule.directory:
            prefix = f"{rule.installed}/" if rule.installed else ""
            if not relative.startswith(prefix):
                continue
            candidate = os.path.join(package_dir, rule.source, relative[len(prefix):])
        elif relative == rule.installed:
            candidate = os.path.join(package_dir, rule.source)
        else:
            continue
        candidate = os.path.normpath(candidate)
        if candidate.startswith(os.path.join(package_dir, "")) and os.path.isfile(candidate):
            return candidate
    return None
