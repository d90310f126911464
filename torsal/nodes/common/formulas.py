"""Formulas given as text inputs: ParametricCurve's X, Y and Z in t, ParametricSurface's in u and v.

A formula that cannot be read is one refused value like any other (the rule in
:mod:`torsal.nodes.common.checks`): a warning naming the input ("Y: Unknown name 'w' (variables
are u and v)"), that call of ``solve`` skipped, the node's other items solved. Each text
is compiled once and kept (the same text in the next solve costs a lookup).
"""

from __future__ import annotations

from functools import lru_cache
from typing import Any

from torsal.engine.node import NodeWarning
from torsal.nodes.expressions import CompiledExpression, ExpressionError, compile_expression


@lru_cache(maxsize=256)
def _compiled(text: str, variables: tuple[str, ...]) -> CompiledExpression:
    return compile_expression(text, variables)  # an ExpressionError is not cached: it is raised again


def formula(name: str, text: Any, variables: tuple[str, ...]) -> CompiledExpression:
    """The input ``name``'s formula in ``variables``, compiled, or a warning naming the input
    when it is empty or cannot be read."""
    if text is None or not str(text).strip():
        raise NodeWarning(f"{name} is empty: write a formula in {' and '.join(variables)}, such as 0")
    try:
        return _compiled(str(text), variables)
    except ExpressionError as exc:
        raise NodeWarning(f"{name}: {exc}") from None
