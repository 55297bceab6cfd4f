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
from robotdesc.model.elements import MeshRef, Robot
from robotdesc.rules.registry import RuleContext, rule

FAMILY = "paths"

_SCHEME = re.compile(r"^([A-Za-z][A-Za-z0-9+.-]*)://")
_WINDOWS_DRIVE = re.compile(r"^[A-Za-z]:[\\/]")


def _meshes(robot: Robot) -> Iterator[tuple[MeshRef, str]]:
    """Every mesh of every visual and collision, with its stable element name."""
    for link in robot.links:
        for kind, index, shape in link.shapes():
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


#: A ROS install space's copy of a package: `<prefix>/install/<pkg>/share/<pkg>/` (colcon's
#: isolated layout), `<prefix>/install/share/<pkg>/` (merged, catkin) and
#: `/opt/ros/<distro>/share/<pkg>/`. ROS resolves `package://<pkg>/` to exactly this folder.
_INSTALL_SPACE = re.compile(
    r"^(?:.*/install/(?P<own>[^/]+)/share/(?P=own)"
    r"|.*/install/share/(?P<merged>[^/]+)"
    r"|/opt/ros/[^/]+/share/(?P<distro>[^/]+))/(?P<rest>.+)$")

#: Folders that two non-portable paths must share (`/home/ana`, `/opt/arm`, `C:/arm`) to be one
#: machine's path when no package holds them.
_SHARED_FOLDERS = 2

#: Grouped references listed by line in the fix text; more are counted.
_LISTED = 40


@dataclasses.dataclass(frozen=True)
class _Reference:
    """One non-portable mesh filename and where it points.

    Attributes:
        mesh, element: the mesh and its element name (`link:base/visual[0]`).
        folders: the folders of the path it names, from the top (`("home", "ana", "arm",
            "meshes")`; a Windows drive is the first).
        package, relative: the package's name and the file's path inside it.
        unfixable: why there is no package:// form (empty when there is).
    """

    mesh: MeshRef
    element: str
    folders: tuple[str, ...]
    package: str = ""
    relative: str = ""
    unfixable: str = ""

    @property
    def source(self) -> str:
        """The file the mesh is written in (a macro's file for a mesh a macro made)."""
        return self.mesh.where.span.path if self.mesh.where else ""

    @property
    def package_uri(self) -> str:
        return f"package://{self.package}/{self.relative}"


def _reference(mesh: MeshRef, element: str) -> _Reference:
    """Where the absolute path or file:// URI of `mesh` points: the package that holds the
    file on this machine (the nearest package.xml above it), else the ROS install space its
    path names (`.../install/<pkg>/share/<pkg>/...`: the machine that wrote it had the
    package there), else no package and why."""
    filename = mesh.filename
    path = filename
    if filename.lower().startswith("file://"):
        path = urllib.parse.unquote(urllib.parse.urlparse(filename).path)
    folders = tuple(part for part in re.split(r"[\\/]+", path) if part)[:-1]
    if not os.path.isabs(path):
        return _Reference(mesh, element, folders,
                          unfixable=f"'{filename}' is not an absolute path")
    found = enclosing_package(os.path.normpath(path))
    if found is not None:
        name, root = found
        relative = os.path.relpath(os.path.realpath(path), root).replace(os.sep, "/")
        return _Reference(mesh, element, folders, name, relative)
    installed = _INSTALL_SPACE.match(posixpath.normpath(path))
    if installed is not None:
        name = installed.group("own") or installed.group("merged") or installed.group("distro")
        return _Reference(mesh, element, folders, name, installed.group("rest"))
    return _Reference(mesh, element, folders,
                      unfixable=f"'{path}' is in no ROS package (no package.xml above it)")


def _folder_text(folders: tuple[str, ...]) -> str:
    joined = "/".join(folders)
    return joined if re.match(r"^[A-Za-z]:$", folders[0] if folders else "") else "/" + joined


def _groups(references: list[_Reference]) -> list[tuple[str, list[_Reference]]]:
    """The references as one group per source file and machine path, in order of their first
    reference, each with its longest common folder: references of one source file whose
    paths share at least `_SHARED_FOLDERS` folders from the top (`/home/ana`,
    `/root/c3pzero_ws`), those with a package:// form apart from those without."""
    groups: list[list[_Reference]] = []
    common: list[tuple[str, ...]] = []  # each group's longest common folder
    for reference in references:
        for index, group in enumerate(groups):
            shared = tuple(os.path.commonprefix([common[index], reference.folders]))
            if (group[0].source == reference.source and len(shared) >= _SHARED_FOLDERS
                    and bool(group[0].unfixable) == bool(reference.unfixable)):
                common[index] = shared
                group.append(reference)
                break
        else:
            common.append(reference.folders)
            groups.append([reference])
    return [(_folder_text(folders), group) for folders, group in zip(common, groups)]


def _path_findings(references: list[_Reference], problem: str) -> Iterator[Finding]:
    """One finding per group of `references` (`_groups`), at its first reference: "mesh
    filename 'F' PROBLEM", and for a group of several "..., and N more mesh references under
    'ROOT'"; its fix sets every reference of the group to its package:// form (the lines it
    rewrites are listed as the fix text), or says why there is none."""
    for root, group in _groups(references):
        first = group[0]
        message = f"mesh filename '{first.mesh.filename}' {problem}"
        if len(group) > 1:
            more = len(group) - 1
            message += (f", and {more} more mesh reference{'s' if more > 1 else ''} "
                        f"under '{root}'")
        finding = Finding(message, first.mesh.where, first.element)
        if first.unfixable:
            yield dataclasses.replace(finding, unfixable=first.unfixable)
            continue
        changes = tuple(ValueChange(f"{r.element}/geometry/mesh", "filename", r.package_uri)
                        for r in group)
        listed = "\n".join(f"line {r.mesh.where.span.line if r.mesh.where else '?'} "
                           f"({r.element}): {r.package_uri}" for r in group[:_LISTED])
        if len(group) > _LISTED:
            listed += f"\n... and {len(group) - _LISTED} more"
        yield dataclasses.replace(finding, changes=changes,
                                  fix=listed if len(group) > 1 else None)


@rule("P101", "absolute-mesh-path", family=FAMILY, severity=Severity.WARNING)
def absolute_mesh_path(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a mesh whose filename is an absolute file system path.

    Why is this bad?
    The path exists only on the machine that wrote it; on a colleague's laptop, in CI or
    in a container the mesh is missing. Use `package://<package>/...` (resolved through
    the package, wherever it is installed) or a path relative to the URDF. A path that
    `$(find pkg)` made while expanding the xacro is not reported: the source is portable.

    One machine's path is one problem: the paths of one source file that share at least
    their first two folders (`/home/ana`, `/opt/arm`, `/root/c3pzero_ws`) are one finding,
    at the first path, counting the others ("and 36 more mesh references under
    '/home/ana/ws/src'", their longest common folder); its fix rewrites them all to
    `package://` (each through the package that holds its file: the nearest `package.xml`
    above it, or the ROS install space its path names, `.../install/<pkg>/share/<pkg>/...`)
    and lists their lines. Paths in no package are a finding of their own.

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
    yield from _path_findings(
        [_reference(mesh, element) for mesh, element in _meshes(robot)
         if _is_absolute(mesh.filename) and not made_by_find(mesh.filename, ctx)],
        "is an absolute path")


@rule("P102", "file-uri-mesh", family=FAMILY, severity=Severity.WARNING)
def file_uri_mesh(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a mesh whose filename is a `file://` URI.

    Why is this bad?
    A `file://` URI is an absolute path in disguise: it only resolves on the machine that
    wrote it. Use `package://<package>/...` or a path relative to the URDF. A URI that
    `file://$(find pkg)/...` made while expanding the xacro is not reported: the source is
    portable, and the expanded URDF is made on the machine that uses it (a common way to let
    Gazebo find meshes without a resource path).

    One machine's path is one problem, grouped as `absolute-mesh-path` groups paths: the
    URIs of one source file that share their first two folders are one finding at the
    first, counting the others. Kinova's generated `gen3_2f85.urdf` holds 37 URIs under
    `file:///root/c3pzero_ws/install/<pkg>/share/<pkg>/` for three packages: one finding,
    whose fix rewrites all 37 to `package://<pkg>/...`.

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
    yield from _path_findings(
        [_reference(mesh, element) for mesh, element in _meshes(robot)
         if mesh.filename.lower().startswith("file://") and not made_by_find(mesh.filename, ctx)],
        "is a file:// URI")


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
