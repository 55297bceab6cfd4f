"""A seeded mutator of robot descriptions and meshes, for the fuzzing campaign.

Every mutation is a pure function of (input bytes, `random.Random`): the same seed gives the
same mutants. Description mutations work on the bytes (flips, truncation, encodings, comments)
or on the element tree (deleting or duplicating elements and attributes, extreme numbers, deep
nesting). Mesh mutations make the broken files users meet: empty, truncated, STL headers that
lie about their triangle count, NaN vertices, zero-byte and external-entity COLLADA, non-UTF-8
OBJ, a mesh file without an extension.
"""

from __future__ import annotations

import random
import re
import struct
from dataclasses import dataclass
from typing import Callable

from lxml import etree

#: Numbers that have made rules crash or lie: overflow, NaN, huge angles, subnormals.
EXTREME_NUMBERS = ("inf", "-inf", "nan", "NaN", "1e308", "1.8e308", "-1.8e308", "1e36",
                   "-1e36", "1e-320", "0", "-0", "1e400", "1e999999", "0x10", "1_0", "",
                   "1e19", "-1e19", "9" * 400, "3.4e38", "1e-30", "-1")

_NUMBER = re.compile(rb"-?\d+(?:\.\d*)?(?:[eE][-+]?\d+)?")
_ATTRIBUTE = re.compile(rb"""\s([A-Za-z_:][\w:.-]*)=("[^"]*"|'[^']*')""")
_START_TAG = re.compile(rb"<([A-Za-z_][\w:.-]*)")


@dataclass(frozen=True)
class Mutant:
    """One mutated description (and optionally one broken mesh it now references).

    Attributes:
        kind: the mutation's name.
        data: the description's bytes.
        mesh: (file name, bytes) of a broken mesh the description references, if any.
    """

    kind: str
    data: bytes
    mesh: tuple[str, bytes] | None = None


def byte_flip(data: bytes, rng: random.Random) -> bytes:
    out = bytearray(data)
    for _ in range(rng.randint(1, 8)):
        at = rng.randrange(len(out))
        out[at] = rng.randrange(256)
    return bytes(out)


def truncate(data: bytes, rng: random.Random) -> bytes:
    return data[:rng.randrange(len(data))]


def _tree_edit(data: bytes, rng: random.Random, edit: Callable[[list, random.Random], None]
               ) -> bytes:
    parser = etree.XMLParser(resolve_entities=False, no_network=True, load_dtd=False)
    try:
        root = etree.fromstring(data, parser)
    except etree.XMLSyntaxError:
        return byte_flip(data, rng)
    elements = [e for e in root.iter() if isinstance(e.tag, str)]
    edit(elements, rng)
    return etree.tostring(root, xml_declaration=True, encoding="utf-8")


def delete_element(data: bytes, rng: random.Random) -> bytes:
    def edit(elements: list, rng: random.Random) -> None:
        victim = rng.choice(elements[1:] or elements)
        if victim.getparent() is not None:
            victim.getparent().remove(victim)
    return _tree_edit(data, rng, edit)


def duplicate_element(data: bytes, rng: random.Random) -> bytes:
    import copy

    def edit(elements: list, rng: random.Random) -> None:
        victim = rng.choice(elements[1:] or elements)
        if victim.getparent() is not None:
            victim.addnext(copy.deepcopy(victim))
    return _tree_edit(data, rng, edit)


def delete_attribute(data: bytes, rng: random.Random) -> bytes:
    def edit(elements: list, rng: random.Random) -> None:
        owners = [e for e in elements if e.attrib]
        if owners:
            victim = rng.choice(owners)
            del victim.attrib[rng.choice(list(victim.attrib))]
    return _tree_edit(data, rng, edit)


def duplicate_attribute(data: bytes, rng: random.Random) -> bytes:
    """A redefined attribute (not well-formed XML): `a="1" a="1"`."""
    found = list(_ATTRIBUTE.finditer(data))
    if not found:
        return byte_flip(data, rng)
    match = rng.choice(found)
    return data[:match.end()] + match.group(0) + data[match.end():]


def extreme_number(data: bytes, rng: random.Random) -> bytes:
    found = list(_NUMBER.finditer(data))
    if not found:
        return byte_flip(data, rng)
    out = data
    for match in sorted(rng.sample(found, min(len(found), rng.randint(1, 3))),
                        key=lambda m: -m.start()):
        out = out[:match.start()] + rng.choice(EXTREME_NUMBERS).encode() + out[match.end():]
    return out


def bad_encoding(data: bytes, rng: random.Random) -> bytes:
    body = re.sub(rb"^<\?xml[^>]*\?>", b"", data).lstrip()
    choice = rng.randrange(6)
    if choice == 0:
        return b'<?xml version="1.0" encoding="EBCDIC-US"?>\n' + body
    if choice == 1:
        return b'<?xml version="1.0" encoding="utf-8"?>\n' + body.replace(b"name", b"n\xff\xfeme", 1)
    if choice == 2:
        return b'<?xml version="1.0" encoding="no-such-codec"?>\n' + body
    if choice == 3:
        return '<?xml version="1.0" encoding="utf-16"?>\n'.encode("utf-16") + body.decode(
            "utf-8", "replace").encode("utf-16")[2:]
    if choice == 4:
        return b"\xef\xbb\xbf\xef\xbb\xbf" + body
    return b'<?xml version="1.0" encoding="latin-1"?>\n' + body + b"<!-- \xe9\x80 -->"


def markup_damage(data: bytes, rng: random.Random) -> bytes:
    """Comments with `--`, unterminated comments or tags, a missing attribute value, a DOCTYPE."""
    at = rng.choice([m.start() for m in _START_TAG.finditer(data)] or [0])
    snippet = rng.choice([b"<!-- a -- b -->", b"<!-- never closed", b"<link name=",
                          b"<joint name=\"j\" type", b"<origin xyz=\"1 2 3\"",
                          b"</robot>", b"<![CDATA[ x", b"<?pi", b"&undefined;", b"&#0;",
                          b"<a:b:c/>", b"<link xmlns:x=\"\" x:y=\"1\"/>"])
    if rng.random() < 0.15:
        doctype = (b'<!DOCTYPE r [<!ENTITY e SYSTEM "file:///etc/passwd">]>\n'
                   if rng.random() < 0.5 else b'<!DOCTYPE robot [<!ENTITY a "aaaa">]>\n')
        root = _START_TAG.search(data)
        at = root.start() if root else 0
        return data[:at] + doctype + data[at:]
    return data[:at] + snippet + data[at:]


def deep_nesting(data: bytes, rng: random.Random) -> bytes:
    depth = rng.choice([100, 255, 257, 300, 1000, 5000])
    tag = rng.choice([b"link", b"visual", b"x", b"geometry", b"robot"])
    nest = (b"<" + tag + b">") * depth + (b"</" + tag + b">") * depth
    close = data.rfind(b"</robot>")
    if close < 0:
        return data + nest
    return data[:close] + nest + data[close:]


def suppression_flood(data: bytes, rng: random.Random) -> bytes:
    codes = rng.choice([b"J102", b"S001", b"X999", b"zz"])
    count = rng.choice([10, 1000, 20000])
    comment = b"<!-- robotdesc: ignore " + b",".join([codes] * count) + b" -->\n"
    at = data.find(b"<link")
    at = at if at >= 0 else 0
    return data[:at] + comment + data[at:]


def huge_values(data: bytes, rng: random.Random) -> bytes:
    found = list(_ATTRIBUTE.finditer(data))
    if not found:
        return byte_flip(data, rng)
    match = rng.choice(found)
    value = b'"' + rng.choice([b"x", b"1 ", b"&amp;"]) * rng.choice([1000, 100000]) + b'"'
    return data[:match.start(2)] + value + data[match.end(2):]


DESCRIPTION_MUTATIONS: dict[str, Callable[[bytes, random.Random], bytes]] = {
    "byte_flip": byte_flip, "truncate": truncate, "delete_element": delete_element,
    "duplicate_element": duplicate_element, "delete_attribute": delete_attribute,
    "duplicate_attribute": duplicate_attribute, "extreme_number": extreme_number,
    "bad_encoding": bad_encoding, "markup_damage": markup_damage,
    "deep_nesting": deep_nesting, "suppression_flood": suppression_flood,
    "huge_values": huge_values,
}

# --- meshes ---------------------------------------------------------------------------------


def _stl(triangles: list[tuple[float, ...]], declared: int | None = None) -> bytes:
    body = b"".join(struct.pack("<12fH", 0, 0, 0, *t, 0) for t in triangles)
    count = len(triangles) if declared is None else declared
    return b"\0" * 80 + struct.pack("<I", count) + body


_UNIT_TRIANGLES = [(0, 0, 0, 1, 0, 0, 0, 1, 0), (0, 0, 0, 0, 1, 0, 0, 0, 1),
                   (0, 0, 0, 0, 0, 1, 1, 0, 0), (1, 0, 0, 0, 1, 0, 0, 0, 1)]
_DAE = (b'<?xml version="1.0" encoding="utf-8"?>\n<COLLADA xmlns="http://www.collada.org/2005/11/'
        b'COLLADASchema" version="1.4.1"><asset><unit meter="1"/><up_axis>Z_UP</up_axis></asset>'
        b'<library_geometries/><scene/></COLLADA>\n')


def bad_mesh(rng: random.Random) -> tuple[str, bytes]:
    """A broken mesh file (name, bytes)."""
    nan = float("nan")
    choices: list[tuple[str, bytes]] = [
        ("empty.stl", b""),
        ("truncated.stl", _stl(_UNIT_TRIANGLES)[:rng.randint(1, 120)]),
        ("lying.stl", _stl(_UNIT_TRIANGLES, declared=rng.choice([0, 5, 10**9, 2**32 - 1]))),
        ("nan.stl", _stl([(nan,) * 9, *_UNIT_TRIANGLES])),
        ("inf.stl", _stl([(float("inf"), 0, 0, 1, 0, 0, 0, 3e38, 0), *_UNIT_TRIANGLES])),
        ("degenerate.stl", _stl([(0,) * 9] * 4)),
        ("ascii.stl", b"solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 nan\n"
                      b"vertex 1 0 0\nvertex 0 1\nendloop\nendfacet\nendsolid\n"),
        ("zero.dae", b""),
        ("entity.dae", b'<?xml version="1.0"?>\n<!DOCTYPE c [<!ENTITY x SYSTEM '
                       b'"file:///etc/passwd">]>\n<COLLADA>&x;</COLLADA>\n'),
        ("bad.dae", _DAE[:rng.randint(10, len(_DAE) - 1)]),
        ("empty_scene.dae", _DAE),
        ("deep.dae", b"<COLLADA>" + b"<node>" * 3000 + b"</node>" * 3000 + b"</COLLADA>"),
        ("latin1.obj", b"# \xe9\xe8 mod\xe8le\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"),
        ("nan.obj", b"v nan 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"),
        ("badindex.obj", b"v 0 0 0\nf 1 2 99\n"),
        ("noextension", _stl(_UNIT_TRIANGLES)),
        ("text.stl", b"not a mesh at all\n" * 10),
        ("random.ply", bytes(rng.randrange(256) for _ in range(200))),
    ]
    return rng.choice(choices)


_MESH_FILENAME = re.compile(rb'(<mesh\b[^>]*?filename=")([^"]*)(")')


def with_bad_mesh(data: bytes, rng: random.Random, package: str) -> Mutant:
    """Point one `<mesh filename>` at a broken mesh in package `package`."""
    name, mesh = bad_mesh(rng)
    found = list(_MESH_FILENAME.finditer(data))
    if not found:
        return Mutant("bad_mesh:none", data)
    match = rng.choice(found)
    target = f"package://{package}/meshes/{name}".encode()
    return Mutant(f"bad_mesh:{name}", data[:match.start(2)] + target + data[match.end(2):],
                  (name, mesh))


def mutate(data: bytes, rng: random.Random, package: str = "fuzzpkg") -> Mutant:
    """One mutant of a description: a description mutation (sometimes two) or a bad mesh."""
    if rng.random() < 0.2:
        return with_bad_mesh(data, rng, package)
    kind = rng.choice(sorted(DESCRIPTION_MUTATIONS))
    out = DESCRIPTION_MUTATIONS[kind](data, rng)
    if rng.random() < 0.15:
        second = rng.choice(sorted(DESCRIPTION_MUTATIONS))
        out = DESCRIPTION_MUTATIONS[second](out, rng) if out else out
        kind = f"{kind}+{second}"
    return Mutant(kind, out)
