"""The expression language of ``maths.Expression`` against numpy: random expressions give
numpy's values, item by item."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

from torsal.nodes.expressions import (
    ExpressionError,
    compile_expression,
)

# ------------------------------------------------------------------ property: vs numpy

X = np.array([-7.5, -2.0, -0.5, 0.0, 0.25, 1.0, 3.0, 1e3])
Y = np.array([2.0, -3.0, 0.5, 0.0, -0.25, 4.0, 3.0, -1e-3])
Reference = Callable[[], Any]
Term = tuple[str, Reference]

_BINARY = [
    ("+", np.add),
    ("-", np.subtract),
    ("*", np.multiply),
    ("/", np.true_divide),
    ("//", np.floor_divide),
    ("%", np.remainder),
    ("**", np.power),
]
_UNARY = [
    ("sin", np.sin),
    ("cos", np.cos),
    ("atan", np.arctan),
    ("sqrt", np.sqrt),
    ("exp", np.exp),
    ("log", np.log),
    ("abs", np.abs),
    ("floor", np.floor),
    ("round", np.round),
    ("tanh", np.tanh),
]
_COMPARE = [("<", np.less), ("<=", np.less_equal), (">", np.greater), ("==", np.equal)]


def _literal(value: float) -> Term:
    return repr(value), lambda: np.float64(value)


_leaves: st.SearchStrategy[Term] = st.one_of(
    st.just(("x", lambda: X)),
    st.just(("y", lambda: Y)),
    st.sampled_from([("pi", lambda: np.float64(np.pi)), ("e", lambda: np.float64(np.e))]),
    st.integers(0, 100).map(lambda i: (str(i), lambda: np.float64(i))),
    st.floats(0, 1e6, allow_nan=False, allow_infinity=False).map(_literal),
)


def _binary(a: Term, op: tuple[str, np.ufunc], b: Term) -> Term:
    return f"({a[0]} {op[0]} {b[0]})", lambda: op[1](a[1](), b[1]())


def _function(f: tuple[str, np.ufunc], a: Term) -> Term:
    return f"{f[0]}({a[0]})", lambda: f[1](a[1]())


def _negate(a: Term) -> Term:
    return f"(-{a[0]})", lambda: np.negative(a[1]())


def _choose(a: Term, c1: Term, op: tuple[str, np.ufunc], c2: Term, b: Term) -> Term:
    return (
        f"({a[0]} if {c1[0]} {op[0]} {c2[0]} else {b[0]})",
        lambda: np.where(op[1](c1[1](), c2[1]()), a[1](), b[1]()),
    )


def _extremum(name: str, a: Term, b: Term) -> Term:
    ufunc = np.minimum if name == "min" else np.maximum
    return f"{name}({a[0]}, {b[0]})", lambda: ufunc(a[1](), b[1]())


def _logic(a: Term, op: str, b: Term) -> Term:
    ufunc = np.logical_and if op == "and" else np.logical_or
    return (
        f"(({a[0]}) {op} ({b[0]}))",
        lambda: ufunc(np.not_equal(a[1](), 0), np.not_equal(b[1](), 0)).astype(np.float64),
    )


def _extend(terms: st.SearchStrategy[Term]) -> st.SearchStrategy[Term]:
    return st.one_of(
        st.builds(_binary, terms, st.sampled_from(_BINARY), terms),
        st.builds(_function, st.sampled_from(_UNARY), terms),
        st.builds(_negate, terms),
        st.builds(_choose, terms, terms, st.sampled_from(_COMPARE), terms, terms),
        st.builds(_extremum, st.sampled_from(["min", "max"]), terms, terms),
        st.builds(_logic, terms, st.sampled_from(["and", "or"]), terms),
    )


@settings(max_examples=400, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.recursive(_leaves, _extend, max_leaves=16))
def test_random_expressions_match_numpy(term: Term) -> None:
    text, reference = term
    try:
        f = compile_expression(text)
    except ExpressionError as error:  # a rare draw beyond the size limits
        assume("too deeply" not in str(error) and "too big" not in str(error))
        raise
    with np.errstate(all="ignore"):
        expected = np.broadcast_to(reference(), X.shape)
    np.testing.assert_array_equal(f(x=X, y=Y), expected)
