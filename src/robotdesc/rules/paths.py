"""Path rules (P): mesh file names must resolve on every machine."""

from __future__ import annotations

import dataclasses
import os
import posixpath
import re
import urllib.parse
from collections.abc import Iterator

from robotdesc.diagnostics import Finding, Severity, ValueChange
from robotdesc.expansion.packages import enclosing_package
from robotdesc.model.elements import Collision, MeshRef, Robot, Visual
from robotdesc.rules.registry import RuleContext, rule

FAMILY = "paths"

_SCHEME = re.compile(r"^([A-Za-z][A-Za-z0-9+.-]*)://")
_WINDOWS_DRIVE = re.compile(r"^[A-Za-z]:[\\/]")


def _meshes(robot: Robot) -> Iterator[tuple[MeshRef, str]]:
    """Every mesh of every visual and collision, with its stable element name."""
    for link in robot.links:
        groups: tuple[tuple[str, tuple[Visual | Collision, ...]], ...] = (
            ("visual", link.visuals), ("collision", link.collisions))
        for kind, shapes in groups:
            for index, shape in enumerate(shapes):
                if isinstance(shape.geometry, MeshRef):
                    yield shape.geometry, f"link:{link.name}/{kind}[{index}]"


def _is_absolute(filename: str) -> bool:
    return filename.startswith("/") or bool(_WINDOWS_DRIVE.match(filename))


def made_by_find(filename: str, ctx: RuleContext) -> bool:
    """Whether an absolute path lies in a package folder that `$(find pkg)` resolved in this
    expansion: the source wrote `$(find pkg)/...` (portable); the expanded URDF, which holds
    this machine's path, is made where it is used."""
    if not ctx.expansion.from_xacro:
        return False
    path = posixpath.normpath("/" + filename[len("file://"):].lstrip("/")
                              if filename.lower().startswith("file://") else filename)
    return any(path == folder or path.startswith(folder.rstrip("/") + "/")
               for folder in ctx.expansion.package_folders)


def _with_package_fix(finding: Finding, filename: str) -> Finding:
    """P101/P102's finding with its fix: the absolute path or file:// URI `filename` as
    package://PACKAGE/PATH of the package that holds the file, or why there is none."""
    path = filename
    if filename.lower().startswith("file://"):
        path = urllib.parse.unquote(urllib.parse.urlparse(filename).path)
    if not os.path.isabs(path):
        return dataclasses.replace(finding, unfixable=f"'{filename}' is not an absolute path")
    found = enclosing_package(os.path.normpath(path))
    if found is None:
        return dataclasses.replace(
            finding, unfixable=f"'{path}' is in no ROS package (no package.xml above it)")
    name, root = found
    relative = os.path.relpath(os.path.realpath(path), root).replace(os.sep, "/")
    return dataclasses.replace(finding, changes=(ValueChange(
        f"{finding.element}/geometry/mesh", "filename", f"package://{name}/{relative}"),))


@rule("P101", "absolute-mesh-path", family=FAMILY, severity=Severity.WARNING)
def absolute_mesh_path(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a mesh whose filename is an absolute file system path.

    Why is this bad?
    The path exists only on the machine that wrote it; on a colleague's laptop, in CI or
    in a container the mesh is missing. Use `package://<package>/...` (resolved through
    the package, wherever it is installed) or a path relative to the URDF. A path that
    `$(find pkg)` made while expanding the xacro is not reported: the source is portable.

    Example
    ```xml
    <robot name="arm">
      <link name="base">
        <visual><geometry><mesh filename="/home/ana/arm/meshes/base.stl"/></geometry></visual>
      </link>
    </robot>
    ```

    Use instead:
    ```xml
    <robot name="arm">
      <link name="base">
        <visual><geometry><mesh filename="package://arm/meshes/base.stl"/></geometry></visual>
      </link>
    </robot>
    ```
    """
    for mesh, element in _meshes(robot):
        if _is_absolute(mesh.filename) and not made_by_find(mesh.filename, ctx):
            yield _with_package_fix(Finding(
                f"mesh filename '{mesh.filename}' is an absolute path", mesh.where, element),
                mesh.filename)


@rule("P102", "file-uri-mesh", family=FAMILY, severity=Severity.WARNING)
def file_uri_mesh(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a mesh whose filename is a `file://` URI.

    Why is this bad?
    A `file://` URI is an absolute path in disguise: it only resolves on the machine that
    wrote it. Use `package://<package>/...` or a path relative to the URDF. A URI that
    `file://$(find pkg)/...` made while expanding the xacro is not reported: the source is
    portable, and the expanded URDF is made on the machine that uses it (a common way to let
    Gazebo find meshes without a resource path).

    Example
    ```xml
    <robot name="arm">
      <link name="base">
        <visual><geometry><mesh filename="file:///opt/arm/meshes/base.stl"/></geometry></visual>
      </link>
    </robot>
    ```

    Use instead:
    ```xml
    <robot name="arm">
      <link name="base">
        <visual><geometry><mesh filename="package://arm/meshes/base.stl"/></geometry></visual>
      </link>
    </robot>
    ```
    """
    for mesh, element in _meshes(robot):
        if mesh.filename.lower().startswith("file://") and not made_by_find(mesh.filename, ctx):
            yield _with_package_fix(Finding(
                f"mesh filename '{mesh.filename}' is a file:// URI", mesh.where, element),
                mesh.filename)


@rule("P103", "non-portable-mesh-path", family=FAMILY, severity=Severity.WARNING)
def non_portable_mesh_path(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a mesh filename that is neither `package://` nor a plain relative path: another
    URI scheme (`model://`, `http://`, ...) or a path with backslashes.

    Absolute paths and `file://` URIs are reported by `absolute-mesh-path` and
    `file-uri-mesh`.

    Why is this bad?
    Only some consumers resolve other schemes (`model://` is Gazebo's, `http://` needs a
    network at load time), and backslashes are path separators on Windows only.

    Example
    ```xml
    <robot name="arm">
      <link name="base">
        <visual><geometry><mesh filename="meshes\\base.stl"/></geometry></visual>
      </link>
    </robot>
    ```

    Use instead:
    ```xml
    <robot name="arm">
      <link name="base">
        <visual><geometry><mesh filename="meshes/base.stl"/></geometry></visual>
      </link>
    </robot>
    ```
    """
    for mesh, element in _meshes(robot):
        filename = mesh.filename
        scheme = _SCHEME.match(filename)
        name = scheme.group(1).lower() if scheme else ""
        if name in ("package", "file") or (not scheme and _is_absolute(filename)):
            continue
        if scheme:
            yield Finding(f"mesh filename '{filename}' uses the {name}:// scheme, which not "
                          "every consumer resolves", mesh.where, element)
        elif "\\" in filename:
            yield Finding(f"mesh filename '{filename}' uses backslashes as separators",
                          mesh.where, element)


@rule("P104", "empty-package-name", family=FAMILY, severity=Severity.WARNING)
def empty_package_name(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a `package://` mesh URI without a package name (`package:///...`).

    Why is this bad?
    ROS resolves `package://NAME/path` by looking NAME up; with an empty name the lookup
    fails (resource_retriever, RViz, Gazebo). Some tools strip the prefix and search
    their package directories for the rest, so the file works in one tool and not in
    another.

    Example
    ```xml
    <robot name="arm">
      <link name="base">
        <visual><geometry><mesh filename="package:///arm/meshes/base.stl"/></geometry></visual>
      </link>
    </robot>
    ```

    Use instead:
    ```xml
    <robot name="arm">
      <link name="base">
        <visual><geometry><mesh filename="package://arm/meshes/base.stl"/></geometry></visual>
      </link>
    </robot>
    ```
    """
    for mesh, element in _meshes(robot):
        lowered = mesh.filename.lower()
        if lowered.startswith("package://") and (lowered == "package://"
                                                  or lowered.startswith("package:///")):
            yield Finding(f"mesh filename '{mesh.filename}' has no package name",
                          mesh.where, element)
