"""Hooks into the xacro package: source lines, macro call chains, package resolution.

Only the worker process installs these (they patch the `xacro` module's globals).

How provenance works: every element gets a private attribute (`PROVENANCE_ATTR`) with its
file index and line when a file is parsed. The attribute is cloned with macro bodies, so an
element expanded from a macro still knows its line in the macro body; while a macro is being
expanded, the current chain of call sites is appended to the attribute of every element
evaluated. Macro call tags and xacro directives lose the attribute (xacro would reject it).
"""

from __future__ import annotations

import builtins
import os
import re
import sys
import xml.dom
import xml.dom.expatbuilder
import xml.dom.minidom
import xml.parsers.expat
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Callable, NoReturn, cast
from xml.dom.minidom import Attr, Document, Element, Node, _append_child  # type: ignore[attr-defined]

from robotdesc.expansion.install_layout import source_of_installed
from robotdesc.expansion.packages import split_package_uri
from robotdesc.source import PASSED_SEPARATOR, PROVENANCE_ATTR, compress_chain, encode_passed

if TYPE_CHECKING:
    from typing import Protocol

    from xacro import Table  # xacro ships no types: its macro and symbol tables

    class _Linked(Protocol):
        """The links of a minidom node that `splice_replace_node` rewrites (typeshed types
        them per node kind; the splice treats every kind alike)."""

        parentNode: _Linked | None
        previousSibling: _Linked | None
        nextSibling: _Linked | None
        childNodes: list[_Linked]

        def removeChild(self, oldChild: _Linked) -> object: ...

    class _Attributed(Protocol):
        """An element's attribute tables (minidom's, not in its stubs)."""

        _attrs: dict[str, Attr] | None
        _attrsNS: dict[tuple[str | None, str], Attr] | None

_ELEMENT = xml.dom.Node.ELEMENT_NODE

#: A `${...}` expression, and a name inside one (macro parameters are plain names).
_EXPRESSION = re.compile(r"\$\{([^}]*)\}")
_NAME = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")
#: Tags and attributes whose names can be written in the passed part (no ":", ".", "@").
_PLAIN_NAME = re.compile(r"[A-Za-z_][A-Za-z0-9_\-]*")


def _site(value: str) -> str:
    """The element's own "FILE:LINE" from a provenance value (chain and passed part cut)."""
    return value.split(";", 1)[0].split(PASSED_SEPARATOR, 1)[0]


def _names(text: str) -> list[str]:
    """The names used in the `${...}` expressions of an attribute's text."""
    if "${" not in text:
        return []
    return [name for expression in _EXPRESSION.findall(text) for name in _NAME.findall(expression)]


class DoctypeRefused(Exception):
    """A DOCTYPE was found (entities can expand without bound or read local files)."""

    def __init__(self, path: str, line: int, col: int) -> None:
        super().__init__("DOCTYPE declarations are not allowed (entity expansion is refused)")
        self.path, self.line, self.col = path, line, col


class RecordingArgs(dict[str, str]):
    """The xacro arguments passed (`name:=value`), remembering which names were read.

    xacro reads an argument by indexing this mapping (`$(arg name)`, `xacro.arg('name')`);
    a name passed but never declared by `<xacro:arg>` may still be read that way, which
    xacro allows, so it is no unknown argument.
    """

    def __init__(self, passed: dict[str, str]) -> None:
        super().__init__(passed)
        self.read: set[str] = set()

    def __getitem__(self, name: str) -> str:
        value = super().__getitem__(name)
        self.read.add(name)
        return value


class IncludeCycle(Exception):
    """A file includes itself, directly or through other files."""


class MacroTooDeep(Exception):
    """Macro calls nested beyond the configured limit."""


@dataclass
class ExpansionState:
    """What the hooks learn while xacro runs.

    Attributes:
        files: the file table (index -> absolute path).
        call_stack: the active macro call sites, outermost first, as (file, line) and macro name.
        last_src: the provenance value of the node most recently touched (for error locations).
        error_src: the location captured when an error first passed through a hook.
        recursion: per macro, (max depth, definition src, outermost call src).
        declared_args: every `<xacro:arg>` evaluated, name -> its src.
        env_defaults: `$(optenv NAME default)` lookups of a variable that was not passed,
            as (name, default used, src); the parent knows whether NAME was set.
        frames: per macro body being evaluated, innermost last: parameter -> the call site
            ("FILE:LINE") that wrote its value as text.
        pending_frames: the frames of calls whose body has not started yet (their blocks are
            evaluated first, in the caller's frame).
    """

    max_macro_depth: int
    files: list[str] = field(default_factory=list)
    call_stack: list[tuple[str, str]] = field(default_factory=list)
    last_src: str = ""
    error_src: tuple[str, tuple[str, ...]] | None = None
    recursion: dict[str, tuple[int, str, str]] = field(default_factory=dict)
    declared_args: dict[str, str] = field(default_factory=dict)
    env_defaults: list[tuple[str, str, str]] = field(default_factory=list)
    frames: list[dict[str, str]] = field(default_factory=list)
    pending_frames: list[dict[str, str]] = field(default_factory=list)
    _depth: dict[str, int] = field(default_factory=dict)
    _chain: str | None = None  # `chain()` of the current call stack, until it changes

    def chain(self) -> str:
        """The active call sites, innermost first, compressed (`compress_chain`): computed
        once per macro call, not once per element of its body."""
        if self._chain is None:
            self._chain = compress_chain([src for src, _ in reversed(self.call_stack)])
        return self._chain

    def push_call(self, src: str, name: str) -> None:
        self.call_stack.append((src, name))
        self._chain = None

    def pop_call(self) -> None:
        self.call_stack.pop()
        self._chain = None

    def file_index(self, path: str) -> int:
        if path not in self.files:
            self.files.append(path)
        return self.files.index(path)

    def capture_error(self) -> None:
        if self.error_src is None:
            chain = tuple(src for src, _ in reversed(self.call_stack))
            self.error_src = (self.last_src, chain)


class _TaggingBuilder(xml.dom.expatbuilder.ExpatBuilderNS):
    """minidom's builder, tagging each element with its "FILE_INDEX:LINE" and refusing a
    DOCTYPE (one class for every file: the file is the instance's)."""

    _parser: xml.parsers.expat.XMLParserType  # set by ExpatBuilder (not in its stubs)

    def __init__(self, path: str, index: int) -> None:
        super().__init__()
        self._path = path
        self._index = f"{index}:"

    def start_element_handler(self, name: str,  # noqa: D401 (expat callback)
                              attributes: list[str]) -> None:
        # the tag as one more attribute of the element expat read (`ordered_attributes`:
        # name, value, ...), set by the builder as it sets the others: last, or in its
        # place, with this value, when the file writes one itself
        attributes += (PROVENANCE_ATTR, f"{self._index}{self._parser.CurrentLineNumber}")
        super().start_element_handler(name, attributes)

    def start_doctype_decl_handler(self, *args: object) -> NoReturn:
        raise DoctypeRefused(self._path, self._parser.CurrentLineNumber,
                             self._parser.CurrentColumnNumber + 1)

    def entity_decl_handler(self, *args: object) -> NoReturn:
        raise DoctypeRefused(self._path, self._parser.CurrentLineNumber,
                             self._parser.CurrentColumnNumber + 1)


def _make_builder(state: ExpansionState, path: str) -> xml.dom.expatbuilder.ExpatBuilderNS:
    return _TaggingBuilder(path, state.file_index(path))


def splice_replace_node(node: Node, by: Node | list[Node] | None,
                        content_only: bool = False) -> None:
    """xacro's `replace_node` in linear time: the same result, one splice of the child list.

    xacro moves each expanded node with minidom's `insertBefore`, which searches the parent's
    child list every time: expanding n macro calls into one parent costs O(n^2) (the cause of
    xacro's super-linear time on long robots). This computes the new nodes once, detaches them,
    and splices them in place of `node`, fixing parent and sibling links.
    """
    target = cast("_Linked", node)
    parent = cast("_Linked", node.parentNode)  # xacro replaces nodes inside the tree
    moved: list[_Linked] = []
    for source in cast("list[_Linked]",
                       [] if by is None else by if isinstance(by, list) else [by]):
        if content_only:
            children = list(source.childNodes)
            source.childNodes[:] = []
            moved.extend(children)
        else:
            if source.parentNode is not None and source is not target:
                source.parentNode.removeChild(source)
            moved.append(source)
    index = parent.childNodes.index(target)
    parent.childNodes[index:index + 1] = moved
    before = parent.childNodes[index - 1] if index > 0 else None
    after_index = index + len(moved)
    after = parent.childNodes[after_index] if after_index < len(parent.childNodes) else None
    previous = before
    for child in moved:
        child.parentNode = parent
        child.previousSibling = previous
        if previous is not None:
            previous.nextSibling = child
        previous = child
    if previous is not None:
        previous.nextSibling = after
    if after is not None:
        after.previousSibling = previous
    target.parentNode = target.previousSibling = target.nextSibling = None


_DECLARED_ENCODING = re.compile(rb"""^\s*<\?xml[^>]*\bencoding\s*=\s*["']([A-Za-z0-9._-]+)["']""")


def _as_xacro_reads(data: bytes, path: str) -> str | bytes:
    """The file's text as xacro reads it: UTF-8 whatever the XML declaration says (xacro
    opens files as text in a UTF-8 locale and expat then ignores the declaration). A file
    that is not UTF-8 is left to its declaration (bytes), where xacro would fail. A
    declaration that disagrees with UTF-8 bytes is said on stderr (logged by the parent)."""
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError:
        return data
    declared = _DECLARED_ENCODING.match(data)
    name = declared.group(1).decode("ascii").lower().replace("_", "-") if declared else "utf-8"
    if name not in ("utf-8", "utf8") and not text.isascii():
        print(f"{path}: the XML declaration says encoding=\"{name}\" but the file is UTF-8; "
              "read as UTF-8, as xacro does (fix the declaration)", file=sys.stderr)
    return text


def plain_text_first(eval_text: Callable[[str, Table], object]) -> Callable[[str, Table], object]:
    """xacro's `eval_text`, answering a text without "$" (most texts, and every provenance
    value) at once: xacro's lexer reads such a text as one plain token and returns it
    unchanged, after building a lexer and trying its four patterns."""

    def evaluate(text: str, symbols: Table) -> object:
        if type(text) is str and "$" not in text:
            return text
        return eval_text(text, symbols)

    return evaluate


def fast_clone(original: Callable[[Node, bool, Document], Node]
               ) -> Callable[[Node, bool, Document], Node]:
    """minidom's `_clone_node` (what `cloneNode` calls: xacro copies a macro's body at each
    call) for elements, texts and comments, without its per-attribute and per-child calls:
    the same nodes, attributes (same order, names, namespaces, `specified`) and links. Other
    nodes, user data and an element whose attributes would collide go to `original`."""
    element_node, text_node, comment_node = Node.ELEMENT_NODE, Node.TEXT_NODE, Node.COMMENT_NODE

    def clone(node: Node, deep: bool, document: Document) -> Node:
        kind = node.nodeType
        if hasattr(node, "_user_data"):
            return original(node, deep, document)
        if kind == text_node:
            return document.createTextNode(cast(xml.dom.minidom.Text, node).data)
        if kind == comment_node:
            return document.createComment(cast(xml.dom.minidom.Comment, node).data)
        if kind != element_node:
            return original(node, deep, document)
        source = cast(Element, node)
        name = source.nodeName
        copy = Element(name, source.namespaceURI, name.split(":", 1)[0] if ":" in name else None)
        copy.ownerDocument = document
        linked = cast("_Attributed", source)
        if linked._attrs:
            attrs: dict[str, Attr] = {}
            attrs_ns: dict[tuple[str | None, str], Attr] = {}
            for attr in linked._attrs.values():
                namespace, qname = attr.namespaceURI, attr.nodeName
                prefix, local = qname.split(":", 1) if ":" in qname else (None, qname)
                if (namespace, local) in attrs_ns or attr.localName != local:
                    return original(node, deep, document)
                made = Attr(qname, namespace, local, prefix)
                made.value = attr.value
                made.ownerDocument = document
                made.ownerElement = copy
                made.specified = attr.specified
                attrs[qname] = made
                attrs_ns[(namespace, local)] = made
            copied = cast("_Attributed", copy)
            copied._attrs, copied._attrsNS = attrs, attrs_ns
        if deep:
            for child in source.childNodes:
                made_child = clone(child, True, document)
                _append_child(copy, made_child)
                made_child.nextSibling = None
        return copy

    return clone


#: The most expressions whose compiled code `compiling_once` keeps.
MAX_COMPILED = 10_000


def compiling_once(compile_: Callable[..., object]) -> Callable[..., object]:
    """`compile` for xacro's `safe_eval`, keeping the code of each expression text: a macro's
    expressions are compiled again at each call (TIAGo: 1,804 compiles of 286 texts). A
    code object is immutable, and each evaluation still gets its own symbols; a text that
    does not compile is compiled (and fails) every time, as before."""
    compiled: dict[tuple[object, ...], object] = {}

    def compile_cached(source: object, filename: object, mode: object, *args: object,
                       **kwargs: object) -> object:
        key = (source, filename, mode)
        if args or kwargs or not all(type(part) is str for part in key):
            return compile_(source, filename, mode, *args, **kwargs)
        code = compiled.get(key)
        if code is None:
            code = compile_(source, filename, mode)
            if len(compiled) < MAX_COMPILED:
                compiled[key] = code
        return code

    return compile_cached


def install(state: ExpansionState, find_package: Callable[[str], str],
            check_file: Callable[[str], None]) -> None:
    """Patch the xacro module so that expansion records provenance into `state`.

    Args:
        state: collects files, call chains, recursion depths and error locations.
        find_package: package name -> its folder; raises when unknown.
        check_file: called with every file xacro is about to parse; raises to refuse it.
    """
    import xacro
    import xacro.substitution_args as subst

    original_eval_all: Callable[[Element, Table, Table], None] = xacro.eval_all
    original_macro_call: Callable[[Element, Table, Table], bool] = xacro.handle_macro_call
    original_check_attrs: Callable[[Element, list[str], list[str]], list[str | None]] = \
        xacro.check_attrs
    original_abs_filename: Callable[[object], str] = xacro.abs_filename_spec

    found_packages: dict[str, str] = {}  # name -> folder, as `$(find)` answered

    def find(package: str) -> str:
        folder = find_package(package)
        found_packages[package] = folder
        return folder

    def parse(inp: str | bytes | Document | None, filename: str | None = None) -> Document:
        if inp is not None:
            return inp if not isinstance(inp, (str, bytes)) else _parse_text(inp)
        # xacro reads a file by name only: parse(None, filename)
        path = os.path.abspath(os.path.join(xacro.root_dir, cast(str, filename)))
        if not os.path.exists(path):
            path = _installed_source(path) or path
        check_file(path)
        including = [os.path.abspath(f) for f in (xacro.filestack or [])[:-1] if f]
        if path in including:
            cycle = " -> ".join(os.path.basename(f) for f in including[including.index(path):] + [path])
            raise IncludeCycle(f"include cycle: {cycle}")
        try:
            with open(path, "rb") as stream:
                data = stream.read()
            return _make_builder(state, path).parseString(_as_xacro_reads(data, path))
        except OSError as exc:
            xacro.filestack.pop()
            raise xacro.XacroException(f"{exc.strerror}: {filename}", exc=exc)
        except xml.parsers.expat.ExpatError as exc:
            setattr(exc, "robotdesc_path", path)  # read by the worker
            raise

    def _installed_source(path: str) -> str | None:
        """The source file of a path that exists only in a package's installed layout."""
        for package, folder in found_packages.items():
            root = os.path.join(os.path.abspath(folder), "")
            if path.startswith(root):
                return source_of_installed(root.rstrip(os.sep), package, path[len(root):])
        return None

    def _parse_text(text: str | bytes) -> Document:
        return _make_builder(state, "<string>").parseString(text)

    def eval_all(node: Element, macros: Table, symbols: Table) -> None:
        previous = state.last_src
        body = node.nodeType == _ELEMENT and node.tagName == "xacro:macro" and state.pending_frames
        if body:
            state.frames.append(state.pending_frames.pop())
        if node.nodeType == _ELEMENT:
            own = node.getAttribute(PROVENANCE_ATTR)
            if own:
                if state.call_stack and ";" not in own:
                    chain = state.chain()
                    passed = _passed_values(node) if state.frames and not body else {}
                    suffix = f"{PASSED_SEPARATOR}{encode_passed(passed)}" if passed else ""
                    node.setAttribute(PROVENANCE_ATTR, f"{own};{chain}{suffix}")
                state.last_src = _site(own)
        try:
            original_eval_all(node, macros, symbols)
        except BaseException:
            state.capture_error()
            raise
        finally:
            if body:
                state.frames.pop()
        state.last_src = previous

    def _passed_values(node: Element) -> dict[str, str]:
        """Attribute -> call site, for the attributes whose text uses a macro parameter."""
        frame = state.frames[-1]
        passed: dict[str, str] = {}
        tag = node.tagName
        if not _PLAIN_NAME.fullmatch(tag):
            return passed
        for name, text in node.attributes.items():
            if name == PROVENANCE_ATTR or not _PLAIN_NAME.fullmatch(name):
                continue
            site = next((frame[used] for used in _names(text) if used in frame), None)
            if site is not None:
                passed[f"{tag}.{name}"] = site
        return passed

    def _call_frame(node: Element, own: str) -> dict[str, str]:
        """Parameter -> where its value was written, for a macro call about to run."""
        outer = state.frames[-1] if state.frames else {}
        frame: dict[str, str] = {}
        for name, text in node.attributes.items():
            if name == PROVENANCE_ATTR:
                continue
            frame[name] = next((outer[used] for used in _names(text) if used in outer), own)
        return frame

    def handle_macro_call(node: Element, macros: Table, symbols: Table) -> bool:
        if node.tagName == "xacro:call" or not node.tagName.startswith("xacro:"):
            return original_macro_call(node, macros, symbols)
        own = _site(node.getAttribute(PROVENANCE_ATTR))
        if node.hasAttribute(PROVENANCE_ATTR):
            node.removeAttribute(PROVENANCE_ATTR)
        name = node.tagName[len("xacro:"):]
        state.last_src = own or state.last_src
        _enter_macro(name, own, macros, symbols)
        pending = len(state.pending_frames)
        state.pending_frames.append(_call_frame(node, own))
        try:
            return original_macro_call(node, macros, symbols)
        except BaseException:
            state.capture_error()
            raise
        finally:
            del state.pending_frames[pending:]
            state.pop_call()
            state._depth[name] -= 1

    def _enter_macro(name: str, own: str, macros: Table, symbols: Table) -> None:
        if len(state.call_stack) >= state.max_macro_depth:
            state.capture_error()
            raise MacroTooDeep(
                f"macro calls nested deeper than {state.max_macro_depth} levels "
                f"(macro '{name}'; infinite recursion?)")
        state.push_call(own, name)
        depth = state._depth.get(name, 0) + 1
        state._depth[name] = depth
        best = state.recursion.get(name)
        if depth > 1 and (best is None or depth > best[0]):
            try:
                _, _, macro = xacro.resolve_macro(name, macros, symbols)
                defined = _site(macro.body.getAttribute(PROVENANCE_ATTR))
            except (KeyError, AttributeError):
                defined = ""
            outermost = next(src for src, called in state.call_stack if called == name)
            state.recursion[name] = (depth, defined, outermost)

    def check_attrs(tag: Element, required: list[str],
                    optional: list[str]) -> list[str | None]:
        src = tag.getAttribute(PROVENANCE_ATTR)
        state.last_src = _site(src) or state.last_src
        if tag.tagName == "xacro:arg" and tag.hasAttribute("name"):
            state.declared_args.setdefault(tag.getAttribute("name"), state.last_src)
        if not src:
            return original_check_attrs(tag, required, optional)
        tag.removeAttribute(PROVENANCE_ATTR)
        try:
            return original_check_attrs(tag, required, optional)
        finally:
            if tag.tagName == "xacro:macro":  # keep the definition line with the macro body
                tag.setAttribute(PROVENANCE_ATTR, src)

    def abs_filename_spec(filename_spec: object) -> str:
        if isinstance(filename_spec, str) and filename_spec.startswith("package://"):
            # never None for a "package://" string
            package, rel, _ = cast("tuple[str, str, bool]", split_package_uri(filename_spec))
            return os.path.join(find(package), rel)
        return original_abs_filename(filename_spec)

    def eval_find(package: str) -> str:
        return find(package)

    xacro.parse = parse
    xacro.replace_node = splice_replace_node
    xacro.eval_all = eval_all
    xacro.eval_text = plain_text_first(xacro.eval_text)
    xacro.compile = compiling_once(builtins.compile)  # a global of xacro's: its safe_eval's
    xml.dom.minidom._clone_node = fast_clone(xml.dom.minidom._clone_node)  # type: ignore[attr-defined]
    xacro.handle_macro_call = handle_macro_call
    xacro.check_attrs = check_attrs
    xacro.abs_filename_spec = abs_filename_spec
    subst._eval_find = eval_find
    subst._eval_dict["find"] = eval_find
    xacro._global_symbols.setdefault("find", eval_find)  # ${find('pkg')}, as ROS 2 files use

    def xacro_arg(name: str) -> str:  # ${xacro.arg('name')}: the same error as $(arg name)
        try:
            passed: dict[str, str] = xacro.substitution_args_context["arg"]
            return passed[name]
        except KeyError:
            raise subst.ArgException(name) from None

    namespace = xacro._global_symbols.get("xacro")
    if isinstance(namespace, dict):
        namespace["arg"] = xacro_arg


def install_environment(env: dict[str, str], safe: bool, state: ExpansionState,
                        set_names: frozenset[str] = frozenset()) -> None:
    """Make `$(env)`/`$(optenv)` see only `env` (the allowlisted variables in safe mode).

    Args:
        env: the variables the expansion may read.
        safe: the sandbox is on (the error message names --env).
        state: records the optenv defaults used for variables that were not passed.
        set_names: names (never values) of the variables set in the caller's environment.
    """
    import xacro.substitution_args as subst

    def eval_env(name: str) -> str:
        if name in env:
            return env[name]
        if safe and name in set_names:
            raise subst.SubstitutionException(
                f"{name} is set in your environment but was not passed (safe mode passes "
                f"only the allowlist); add --env {name}")
        hint = " (not in the safe-mode allowlist; add it with --env NAME or use --trusted)" if safe else ""
        raise subst.SubstitutionException(f"environment variable {name} is not set{hint}")

    def eval_optenv(name: str, default: str = "") -> str:
        if name in env:
            return env[name]
        state.env_defaults.append((name, default, state.last_src))
        return default

    subst._eval_env = eval_env
    subst._eval_optenv = eval_optenv
    subst._eval_dict["env"] = eval_env
    subst._eval_dict["optenv"] = eval_optenv
