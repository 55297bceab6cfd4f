"""Write a result: mesh files, a new URDF (and for xacro sources a xacro snippet and a patch
of the xacro files), and the manifest; atomically, and never over a file robotdesc did not
write.

Layout in the output folder DIR:

    DIR/meshes/<link>.stl            decimate / hull (one mesh per link)
    DIR/meshes/<link>_<i>.stl        coacd (one convex hull per file, several <collision>)
    DIR/<robot>.collision.urdf       the description with the new <collision> elements
    DIR/<robot>.collision.xacro      for xacro sources: one macro per link to paste in
    DIR/<robot>.collision.patch      for xacro sources: a unified diff swapping the links'
                                     <collision> elements in the xacro files (xacro_patch.py;
                                     its header names the root folder to apply it in, and
                                     the links it leaves to the snippet)
    DIR/robotdesc-collision.json     the manifest (see manifest.py)

Links that failed keep their original `<collision>` elements and get no files, unless an
earlier run made outputs for them: those stay, as do the outputs of links not selected this
time. The source files are only read, never written: every file goes through
`robotdesc.output.write_output`, which refuses the run's inputs and anything that would land
outside DIR (a symlink, a special file, a subfolder leading elsewhere). A manifest entry is
read, replaced or deleted only when `manifest.own_file` accepts it (a name robotdesc writes,
inside DIR); other entries are ignored with a warning.
"""

from __future__ import annotations

import logging
import os
import re
from collections.abc import Iterable
from dataclasses import dataclass

from lxml import etree

from robotdesc.collision.manifest import (
    MANIFEST_NAME,
    Manifest,
    own_file,
    read_manifest,
)
from robotdesc.collision.result import CollisionResult, MeshPart, PrimitivePart
from robotdesc.collision.stl import stl_bytes
from robotdesc.collision.xacro_patch import XacroPatch, build_patch
from robotdesc.digest import bytes_digest, file_digest
from robotdesc.errors import OutputConflict
from robotdesc.expansion.packages import enclosing_package
from robotdesc.model.elements import Box, Capsule, Cylinder, MeshRef, Sphere
from robotdesc.output import (
    NO_INPUTS,
    RunInputs,
    check_output,
    prepare_output_dir,
    write_output,
)
from robotdesc.source import Span, strip_provenance

log = logging.getLogger(__name__)

#: What a new `<collision>` element is made from: a part of this run, or the `MeshRef` of a
#: kept mesh element read back (only its file name is used).
ElementPart = MeshPart | PrimitivePart | MeshRef
#: Per link, its new `<collision>` elements as (file name, part); "" for a primitive.
References = dict[str, list[tuple[str, ElementPart]]]


@dataclass(frozen=True)
class Kept:
    """Earlier outputs that stay: per link its (file name, part) elements, and the files.

    A kept mesh element's part is the `MeshRef` read back (only its file name is used)."""

    references: References
    files: dict[str, bytes]


def earlier_outputs(out_dir: str, old: Manifest, links: list[str], base: str,
                    package: str | None) -> Kept:
    """The outputs an earlier run wrote for `links`, read back from its URDF and files.

    Raises:
        OutputConflict: that URDF or a file of these links is missing or was edited.
    """
    from robotdesc.model.parse import parse_urdf

    def current(name: str) -> bytes:
        path = own_file(out_dir, name) or os.path.join(out_dir, name)
        if own_file(out_dir, name) is None or name not in old.files \
                or file_digest(path, follow_symlinks=False) != old.files[name]:
            raise OutputConflict(
                f"the earlier outputs of {', '.join(links)} (not made in this run) cannot be "
                f"kept: {name} is missing or was edited; nothing was written. Make those links "
                f"too, or write to another --out", Span(path), (name,))
        with open(path, "rb") as stream:
            return stream.read()

    urdf_name = f"{base}.collision.urdf"
    earlier = parse_urdf(current(urdf_name), os.path.join(out_dir, urdf_name))
    references: References = {}
    files: dict[str, bytes] = {}
    for name in links:
        link = earlier.link(name)
        elements: list[tuple[str, ElementPart]] = []
        for collision in link.collisions if link is not None else ():
            geometry = collision.geometry
            if isinstance(geometry, MeshRef):
                relative = geometry.filename
                if package and relative.startswith(package):
                    relative = relative[len(package):]
                files[relative] = current(relative)
                elements.append((relative, geometry))
            elif geometry is not None:
                elements.append(("", PrimitivePart(geometry, collision.origin)))
        references[name] = elements
    return Kept(references, files)


def planned_files(result: CollisionResult, urdf_xml: bytes, out_dir: str,
                  from_xacro: bool, kept: Kept | None = None) -> dict[str, bytes]:
    """Every output file (relative path -> bytes), manifest excluded. Writes nothing; for
    xacro sources it reads the source files the patch is made against.

    Args:
        kept: links whose earlier outputs stay (see `earlier_outputs`), as their elements
            and files.
    """
    files: dict[str, bytes] = dict(kept.files) if kept else {}
    found: References = dict(kept.references) if kept else {}
    for outcome in result.outcomes:
        if not outcome.written:
            continue
        stem = _safe(outcome.report.link)
        meshes = [p for p in outcome.parts if isinstance(p, MeshPart)]
        elements: list[tuple[str, ElementPart]] = []
        for index, part in enumerate(outcome.parts):
            if isinstance(part, MeshPart):
                name = f"meshes/{stem}.stl" if len(meshes) == 1 else f"meshes/{stem}_{index}.stl"
                files[name] = stl_bytes(part)
                elements.append((name, part))
            else:
                elements.append(("", part))
        found[outcome.report.link] = elements
    references = {link.name: found[link.name] for link in result.robot.links
                  if link.name in found}  # in the description's order
    base = _safe(result.robot.name or "robot")
    package = _package_prefix(out_dir)
    files[f"{base}.collision.urdf"] = _new_urdf(urdf_xml, references, package)
    if from_xacro:
        patch_name = f"{base}.collision.patch"
        patch = _xacro_patch(result, references, package, out_dir, patch_name)
        files[patch_name] = patch.text
        files[f"{base}.collision.xacro"] = _xacro_snippet(result, references, package,
                                                          out_dir, patch, patch_name)
    return files


def write_outputs(result: CollisionResult, urdf_xml: bytes, out_dir: str, *,
                  from_xacro: bool, source_dirs: tuple[str, ...] = (),
                  allow_source_dir: bool = False,
                  inputs: RunInputs = NO_INPUTS) -> list[str]:
    """Write the planned files and the manifest into `out_dir`; returns the paths written.

    Args:
        inputs: the files the run read (description, includes, meshes); none is written.

    Raises:
        OutputError: `out_dir` is a file or read-only, or an output would replace an input
            or leave `out_dir`.
        OutputConflict: `out_dir` holds the source meshes (without `allow_source_dir`), a
            planned file exists that robotdesc did not write (or that was edited since), or
            the earlier outputs of a link not made now (it failed, or was not selected) were
            edited, so they cannot be kept. Nothing is written then.

    Links with outputs from an earlier run that are not made now keep them (their files,
    elements and manifest entry: `--check` still says whether they are current).
    """
    out_dir = os.path.abspath(out_dir)
    real = os.path.realpath(out_dir)
    if not allow_source_dir and any(os.path.realpath(d) == real or
                                    os.path.realpath(d).startswith(real + os.sep)
                                    for d in source_dirs):
        raise OutputConflict("the output folder holds source meshes; choose another --out "
                             "(or pass --into-source-dir)", Span(out_dir))
    prepare_output_dir(out_dir)
    old = read_manifest(out_dir) or Manifest()
    for name in old.files:
        if own_file(out_dir, name) is None:
            log.warning("%s: ignoring the manifest entry '%s': not a file robotdesc writes "
                        "inside %s", os.path.join(out_dir, MANIFEST_NAME), name, out_dir)
    written_links = {o.report.link for o in result.outcomes if o.written}
    keep = [link.name for link in result.robot.links
            if link.name in old.links and link.name not in written_links]
    kept = earlier_outputs(out_dir, old, keep, _safe(result.robot.name or "robot"),
                           _package_prefix(out_dir)) if keep else None
    files = planned_files(result, urdf_xml, out_dir, from_xacro, kept)
    conflicts = []
    for name, data in files.items():
        path = os.path.join(out_dir, name)
        if not os.path.exists(path):
            continue
        current = file_digest(path, follow_symlinks=False)
        if current != bytes_digest(data) and old.files.get(name) != current:
            conflicts.append(name)
    if os.path.exists(os.path.join(out_dir, MANIFEST_NAME)) and not old.files \
            and read_manifest(out_dir) is None:
        conflicts.append(MANIFEST_NAME)
    if conflicts:
        raise OutputConflict(f"refusing to overwrite {len(conflicts)} file(s) robotdesc did "
                             f"not write (or that were edited): {', '.join(sorted(conflicts))}",
                             Span(out_dir), tuple(sorted(conflicts)))
    inputs = _not_own(inputs, out_dir, old)
    for name in [*files, MANIFEST_NAME]:  # all refused before anything is written
        check_output(os.path.join(out_dir, name), inputs, within=out_dir)
    written = []
    for name, data in sorted(files.items()):
        path = os.path.join(out_dir, name)
        if file_digest(path, follow_symlinks=False) != bytes_digest(data):
            write_output(path, data, inputs, within=out_dir)
            written.append(path)
    for name, digest in old.files.items():  # our own files that are no longer produced
        stale = own_file(out_dir, name)
        if stale is not None and name not in files \
                and file_digest(stale, follow_symlinks=False) == digest \
                and inputs.match(stale) is None:
            os.unlink(stale)
    manifest = Manifest(
        files={name: bytes_digest(data) for name, data in files.items()},
        links={**{name: old.links[name] for name in keep},
               **{o.report.link: {"key": o.key, "status": o.report.status,
                                  "method": o.report.method}
                  for o in result.outcomes if o.written}},
        source=os.path.relpath(result.robot.source, out_dir) if result.robot.source else "",
        parameters=result.options.key_fields())
    write_output(os.path.join(out_dir, MANIFEST_NAME), manifest.to_json(), inputs,
                 within=out_dir)
    return written


def _not_own(inputs: RunInputs, out_dir: str, old: Manifest) -> RunInputs:
    """The inputs less the files an earlier run wrote here, unedited (a description that
    includes the generated snippet or uses the generated meshes reads them; this run may
    rewrite them)."""
    own = set()
    for name, digest in old.files.items():
        path = own_file(out_dir, name)
        if path is not None and file_digest(path, follow_symlinks=False) == digest:
            own.add(os.path.realpath(path))
    return RunInputs(tuple(item for item in inputs.items if item.path not in own))


def _new_urdf(urdf_xml: bytes, references: References, package: str | None) -> bytes:
    parser = etree.XMLParser(resolve_entities=False, no_network=True, remove_blank_text=False)
    root = etree.fromstring(strip_provenance(urdf_xml), parser)
    for link in root.findall("link"):
        elements = references.get(link.get("name", ""))
        if elements is None:
            continue
        old = link.findall("collision")
        anchor = link.index(old[0]) if old else len(link)
        tail = old[0].tail if old else "\n    "
        for element in old:
            link.remove(element)
        for offset, (name, part) in enumerate(elements):
            new = _collision_element(link.get("name", ""), offset, name, part, package)
            new.tail = tail
            link.insert(anchor + offset, new)
    text: bytes = etree.tostring(root, xml_declaration=True, encoding="utf-8")
    return text + b"\n"


def _collision_element(link: str, index: int, filename: str, part: ElementPart,
                       package: str | None) -> etree._Element:
    element = etree.Element("collision", name=f"{link}_collision_{index}")
    origin = etree.SubElement(element, "origin")
    geometry = etree.SubElement(element, "geometry")
    if isinstance(part, PrimitivePart):
        origin.set("xyz", _vec(part.origin.xyz))
        origin.set("rpy", _vec(part.origin.rpy))
        shape = part.geometry
        if isinstance(shape, Box):
            etree.SubElement(geometry, "box", size=_vec(shape.size))
        elif isinstance(shape, Sphere):
            etree.SubElement(geometry, "sphere", radius=_num(shape.radius))
        elif isinstance(shape, (Cylinder, Capsule)):
            tag = "cylinder" if isinstance(shape, Cylinder) else "capsule"
            etree.SubElement(geometry, tag, radius=_num(shape.radius),
                             length=_num(shape.length))
    else:
        origin.set("xyz", "0 0 0")
        origin.set("rpy", "0 0 0")
        etree.SubElement(geometry, "mesh", filename=f"{package}{filename}" if package
                         else filename)
    return element


def _xacro_patch(result: CollisionResult, references: References, package: str | None,
                 out_dir: str, patch_name: str) -> XacroPatch:
    """The patch for the xacro sources; relative mesh paths are taken from each patched file."""
    out_dir = os.path.abspath(out_dir)

    def render(link: str, folder: str) -> list[etree._Element]:
        elements = []
        for offset, (name, part) in enumerate(references[link]):
            if name and package is None:
                name = os.path.relpath(os.path.realpath(os.path.join(out_dir, name)),
                                       os.path.realpath(folder)).replace(os.sep, "/")
            elements.append(_collision_element(link, offset, name, part, package))
        return elements

    return build_patch(result.robot, list(references), render, out_dir, patch_name,
                       relative_meshes=package is None)


def _xacro_snippet(result: CollisionResult, references: References, package: str | None,
                   out_dir: str, patch: XacroPatch, patch_name: str) -> bytes:
    skipped = {s.link: s.reason for s in patch.skipped}
    lines = ['<?xml version="1.0" encoding="utf-8"?>',
             "<!-- Generated by `robotdesc collision`. In each link, replace its <collision>",
             "     elements (where listed) by a call <xacro:NAME_collision/>.",
             f"     {patch_name} does this for the links marked so; the others need it by",
             "     hand. -->",
             '<robot xmlns:xacro="http://www.ros.org/wiki/xacro">']
    for link_name, elements in references.items():
        link = result.robot.link(link_name)
        where = [f"{os.path.relpath(c.where.span.path, out_dir)}:{c.where.span.line}"
                 for c in (link.collisions if link else ()) if c.where]  # portable paths
        status = (f"not in {patch_name}: {skipped[link_name]}" if link_name in skipped
                  else f"done by {patch_name}")
        lines.append(_comment(f"{link_name}: replaces the <collision> at "
                              f"{', '.join(where) or '(none: add the call to the link)'}; "
                              f"{status}", "  "))
        lines.append(f'  <xacro:macro name="{_safe(link_name)}_collision">')
        for offset, (name, part) in enumerate(elements):
            text = etree.tostring(_collision_element(link_name, offset, name, part, package),
                                  encoding="unicode")
            lines.append(f"    {text}")
        lines.append("  </xacro:macro>")
    lines.append("</robot>")
    return ("\n".join(lines) + "\n").encode()


def _package_prefix(out_dir: str) -> str | None:
    """`package://pkg/rel/` when the folder is inside a ROS package, else None (relative)."""
    found = enclosing_package(out_dir)
    if found is None:
        return None
    name, root = found
    relative = os.path.relpath(os.path.realpath(out_dir), os.path.realpath(root))
    relative = "" if relative == "." else relative.replace(os.sep, "/") + "/"
    return f"package://{name}/{relative}"


def _comment(text: str, indent: str) -> str:
    """An XML comment holding `text` (a "--", not allowed in comments, is split)."""
    text = re.sub(r"-(?=-)", "- ", " ".join(text.split()))
    return f"{indent}<!-- {text} -->"


def _safe(name: str) -> str:
    return re.sub(r"[^A-Za-z0-9_.-]", "_", name) or "link"


def _num(value: float) -> str:
    return f"{float(value):.9g}"


def _vec(values: Iterable[float]) -> str:
    return " ".join(_num(v) for v in values)
