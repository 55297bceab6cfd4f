"""Xacro rules (X): what the expansion shows about the xacro source."""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass

from robotdesc.diagnostics import Finding, Severity
from robotdesc.model.elements import Robot
from robotdesc.rules.registry import RuleContext, rule
from robotdesc.source import Provenance

FAMILY = "xacro"


@dataclass(frozen=True)
class MacroRecursionOptions:
    """Options of `deep-macro-recursion`.

    Attributes:
        max_depth: the deepest self-recursion of a macro that is accepted.
    """

    max_depth: int = 16


@rule("X101", "deep-macro-recursion", family=FAMILY, severity=Severity.WARNING,
      options=MacroRecursionOptions, needs=("expansion",))
def deep_macro_recursion(robot: Robot, ctx: RuleContext) -> Iterator[Finding]:
    """Finds a xacro macro that calls itself deeper than `max_depth` levels.

    Reported at the macro's definition. Typical source: a macro that emits one element and
    calls itself for the rest of a range (one wheel, then the other n-1 wheels).

    Why is this bad?
    Xacro's expansion time grows super-linearly with the recursion depth: each level opens
    a new property scope inside the previous one, and name lookups walk the enclosing
    scopes, so a linear recursion over a few hundred items takes seconds or more, and a
    deep enough one exhausts Python's recursion limit. A shallower form does the same
    work: split the range in halves at each level (depth log2(n)), or unroll it into a
    flat list of calls.

    Example
    ```xml
    <xacro:macro name="wheels" params="i n">
      <xacro:wheel index="${i}"/>
      <xacro:if value="${i + 1 &lt; n}">
        <xacro:wheels i="${i + 1}" n="${n}"/>
      </xacro:if>
    </xacro:macro>
    <xacro:wheels i="0" n="212"/>
    ```

    Use instead (depth log2(n)):
    ```xml
    <xacro:macro name="wheels" params="lo hi">
      <xacro:if value="${hi - lo == 1}"><xacro:wheel index="${lo}"/></xacro:if>
      <xacro:if value="${hi - lo &gt; 1}">
        <xacro:wheels lo="${lo}" hi="${(lo + hi) // 2}"/>
        <xacro:wheels lo="${(lo + hi) // 2}" hi="${hi}"/>
      </xacro:if>
    </xacro:macro>
    <xacro:wheels lo="0" hi="212"/>
    ```
    """
    limit = ctx.options_as(MacroRecursionOptions).max_depth
    for recursion in ctx.expansion.macro_recursion:
        if recursion.depth > limit:
            called = f" (called from {recursion.called_at})" if recursion.called_at else ""
            yield Finding(
                f"macro '{recursion.macro}' recurses {recursion.depth} levels deep "
                f"(limit {limit}){called}; xacro's expansion time grows super-linearly with "
                "recursion depth: use a shallower form, e.g. split the range in halves at "
                "each level (depth log2(n))",
                Provenance(recursion.defined_at), f"macro:{recursion.macro}")
