"""The worker's speed-ups of xacro (`robotdesc.expansion.hooks`) answer as xacro does."""

from __future__ import annotations

import xml.dom.minidom

import pytest
import xacro

from robotdesc.expansion import hooks

@pytest.mark.parametrize("text", ["", "plain", "a b\n  c", "$", "$$", "x$", "$x", "${1+2}",
                                  "$(arg a)", "$${x}", "a ${1} b", "$$(x)",
                                  "0:12;1:3*2|link.name@0:4"])
def test_the_eval_text_shortcut_answers_as_xacro_does(text):
    symbols = xacro.Table()
    quick = hooks.plain_text_first(xacro.eval_text)
    try:
        expected = xacro.eval_text(text, symbols)
    except Exception as exc:  # noqa: BLE001 -- the same failure either way
        with pytest.raises(type(exc)):
            quick(text, symbols)
        return
    assert quick(text, symbols) == expected
    assert type(quick(text, symbols)) is type(expected)


def test_an_expression_compiled_once_evaluates_with_each_call_s_symbols():
    compile_ = hooks.compiling_once(compile)
    first = compile_("a + 1", "<expression>", "eval")
    assert compile_("a + 1", "<expression>", "eval") is first
    assert eval(first, {"a": 1}) == 2 and eval(first, {"a": 41}) == 42
    with pytest.raises(SyntaxError):
        compile_("a +", "<expression>", "eval")
    with pytest.raises(SyntaxError):  # not kept: fails again
        compile_("a +", "<expression>", "eval")


DOCUMENT = """<?xml version="1.0"?>
<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro" xmlns:g="urn:g">
  <!-- a comment -->
  <xacro:macro name="m" params="p *b">
    <link name="${p}" g:kind="x" _rd_src="0:3" plain="1"><visual><![CDATA[raw <text>]]></visual>
      <?pi data?>text &amp; more<xacro:insert_block name="b"/></link>
  </xacro:macro>
  <joint name="j" type="fixed"/><empty/>
</robot>"""


def _shape(node):
    """Everything of a node and its subtree that a clone must reproduce."""
    attrs = None
    if node.nodeType == node.ELEMENT_NODE and node._attrs is not None:
        attrs = [(name, a.namespaceURI, a.prefix, a.localName, a.value, a.specified,
                  a.ownerElement is node, a.ownerDocument is node.ownerDocument,
                  node._attrsNS[(a.namespaceURI, a.localName)] is a)
                 for name, a in node._attrs.items()]
    children = list(node.childNodes)
    links = [(c.parentNode is node, c.previousSibling is (children[k - 1] if k else None),
              c.nextSibling is (children[k + 1] if k + 1 < len(children) else None))
             for k, c in enumerate(children)]
    return (node.nodeType, node.nodeName, getattr(node, "prefix", None),
            getattr(node, "namespaceURI", None), node.localName, node.nodeValue, attrs,
            node.ownerDocument, links, [_shape(c) for c in children])


@pytest.mark.parametrize("deep", [True, False])
def test_the_fast_clone_copies_every_node_as_minidom_does(deep):
    document = xml.dom.minidom.parseString(DOCUMENT)
    document.documentElement.setAttribute("added", "later")
    fast = hooks.fast_clone(xml.dom.minidom._clone_node)
    nodes = [document.documentElement]
    while nodes:
        node = nodes.pop()
        nodes.extend(node.childNodes)
        expected = xml.dom.minidom._clone_node(node, deep, document)
        got = fast(node, deep, document)
        assert _shape(got) == _shape(expected)
        assert got.parentNode is got.previousSibling is got.nextSibling is None
        assert got.toxml() == expected.toxml()
