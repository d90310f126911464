"""developable.ParametricRuledSurface: S(u, v) = C(u) + v·a(u) from a directrix and directions."""

from __future__ import annotations

from typing import Any

import numpy as np

from torsal.engine.node import LIST, In, Node, NodeWarning, Out
from torsal.engine.types import BOOLEAN, GENERIC, INTEGER, NUMBER, VECTOR, describe
from torsal.engine.values import Domain
from torsal.nodes.common import checks as check
from torsal.nodes.common import geometry_checks
from torsal.nodes.common.checks import number
from torsal.nodes.common.strip_outputs import WARP_HELP, strip_outputs
from torsal.nodes.common.values import LINE, SURFACE
from torsal.nodes.geometry.curve_base import Curve
from torsal.nodes.geometry.curves.line import Line
from torsal.nodes.geometry.ruled import RuledSurface


def _directrix(values: list[Any]) -> Curve | np.ndarray:
    """One curve, or the points C(u) as an ``(n, 3)`` array."""
    if not values:
        raise NodeWarning("Directrix is empty: give the points C(u), or one curve")
    if isinstance(values[0], Curve):
        if len(values) > 1:
            raise NodeWarning(f"Directrix has {len(values)} curves: give one curve, or a list of points")
        return geometry_checks.curve("Directrix", values[0])
    rows = []
    for i, value in enumerate(values):
        if value is None:
            raise NodeWarning(f"Directrix point {i} is empty (null): remove it or fix what made it")
        try:
            row = np.asarray(value, dtype=float).reshape(3)
        except (TypeError, ValueError):
            raise NodeWarning(
                f"Directrix item {i} {describe(value)} is neither a point nor a curve"
            ) from None
        if not np.all(np.isfinite(row)):
            raise NodeWarning(f"Directrix point {i} has a coordinate that is not a finite number")
        rows.append(row)
    if len(rows) < 2:
        raise NodeWarning("Directrix has 1 point: give at least 2 points C(u), one per ruling")
    return np.array(rows)


def _directions(values: list[Any]) -> np.ndarray:
    """The vectors a(u) as an ``(k, 3)`` array; none may be zero or non-finite."""
    if not values:
        raise NodeWarning("Direction is empty: give one vector a(u) per Directrix point, or one for all")
    if any(v is None for v in values):
        i = next(i for i, v in enumerate(values) if v is None)
        raise NodeWarning(f"Direction {i} is empty (null): remove it or fix what made it")
    a = np.asarray(values, dtype=float).reshape(-1, 3)
    bad = ~np.all(np.isfinite(a), axis=1)
    if bad.any():
        raise NodeWarning(f"Direction {int(np.argmax(bad))} has a component that is not a finite number")
    zero = np.linalg.norm(a, axis=1) <= 1e-300
    if zero.any():
        raise NodeWarning(
            f"Direction {int(np.argmax(zero))} has zero length, so that ruling has no direction "
            f"({int(zero.sum())} such vectors)"
        )
    return a


def _extent(values: list[Any], two_sided: bool) -> tuple[float, float]:
    """The ruling extent (v0, v1) from a domain or numbers; two-sided it is (−m, m)."""
    if not values or any(v is None for v in values):
        raise NodeWarning("VValues is empty: give a domain v0 to v1, or numbers")
    if len(values) == 1 and isinstance(values[0], Domain):
        v0, v1 = number("VValues start", values[0].min), number("VValues end", values[0].max)
    elif all(isinstance(v, int | float) and not isinstance(v, bool) for v in values):
        v = [number(f"VValues {i}", x) for i, x in enumerate(values)]
        v0, v1 = (0.0, v[0]) if len(v) == 1 else (min(v), max(v))
    else:
        raise NodeWarning("VValues must be one domain (v0 to v1) or numbers (the extent runs from "
                          "the smallest to the largest; one number x means 0 to x)")
    if two_sided:
        m = max(abs(v0), abs(v1))
        v0, v1 = -m, m
    if v0 == v1:
        raise NodeWarning(f"VValues runs from {v0:g} to {v1:g}: the rulings would have no length; "
                          "give an interval")
    return v0, v1


class ParametricRuledSurface(Node):
    """A ruled surface from its textbook equation S(u, v) = C(u) + v·a(u).

    Give the directrix C(u) as points — one per ruling, in order, typically made by
    Expression nodes from a list of u values (Range) and joined by a Point node —
    and the direction a(u) as vectors, one per point (or one for all: a cylinder).
    Ruling i runs from C(u_i) + v0·a(u_i) to C(u_i) + v1·a(u_i), with v0 to v1 the
    VValues extent, so v is measured in lengths of a(u). TwoSided extends every
    ruling to the negative side as well: v runs from −m to m, m the larger of |v0|
    and |v1|.

    A curve may be given as Directrix instead: the rulings then sit at evenly spaced
    parameters t from 0 to 1 — as many as there are Direction vectors, or
    Segments + 1 when one Direction serves all.

    Textbook examples (u from 0 to 2π): cylinder C = (cos u, sin u, 0), a = (0, 0, 1);
    helicoid C = (0, 0, c·u), a = (cos u, sin u, 0), two-sided; Möbius strip
    C = (cos u, sin u, 0), a = (cos(u/2)·cos u, cos(u/2)·sin u, sin(u/2)), two-sided.

    A ruled surface is developable only where its rulings are torsal, so the
    WarpAngles output matters here: 0 on a cylinder, but a helicoid twists by the
    same angle along every ruling. The warp angle is the angle between the sheet's
    normals at a ruling's two ends, 0 to π: on the hyperbolic paraboloid z = xy
    (C = (u, 0, 0), a = (0, 1, u), two-sided to v = ±L) it is 2·atan(L) on every
    ruling. Warp uses the edge tangents of the ruling end points (central
    differences), since only points are known; it is NaN where a ruling has no tangent
    plane (zero length, or along an edge).
    """

    type_id = "developable.ParametricRuledSurface"
    nickname, aliases = "PRuled", ("ruled surface equation",)
    inputs = (
        In("Directrix", GENERIC, "C", "Points C(u), one per ruling, in order — or one curve.",
           access=LIST),
        In("Direction", VECTOR, "a", "Vectors a(u), one per Directrix point, or one for all.",
           access=LIST),
        In("VValues", GENERIC, "V",
           "Ruling extent v0 to v1 in lengths of a(u): a domain, or numbers (one number x = 0 to x).",
           default=Domain(0.0, 1.0), access=LIST),
        In("TwoSided", BOOLEAN, "2", "Extend every ruling to the negative side too (v from −m to m).",
           default=False),
        In("Segments", INTEGER, "S",
           "Rulings minus one, only for a curve Directrix with one Direction.", default=24),
    )
    outputs = (
        Out("Surface", SURFACE, "S", "The ruled surface through the rulings."),
        Out("Rulings", LINE, "R", "Ruling i from C(u_i) + v0·a(u_i) to C(u_i) + v1·a(u_i).",
            access=LIST),
        Out("WarpAngles", NUMBER, "W", f"{WARP_HELP} Edge tangents from the neighbouring rulings' "
            "ends.", access=LIST),
    )

    def solve(self, directrix: list[Any], direction: list[Any], v_values: list[Any], two_sided: Any,
              segments: Any) -> tuple[RuledSurface, list[Line], list[float]]:
        base = _directrix(directrix)
        a = _directions(direction)
        v0, v1 = _extent(v_values, bool(two_sided))
        if isinstance(base, Curve):
            count = len(a) if len(a) > 1 else check.segments(segments) + 1
            base = base.point_at(np.linspace(0.0, 1.0, count))
        elif len(a) not in (1, len(base)):
            raise NodeWarning(
                f"Give one Direction per Directrix point ({len(base)}) or one for all; got {len(a)}"
            )
        a = np.broadcast_to(a, base.shape)
        strip = strip_outputs(base + v0 * a, base + v1 * a)
        strip.report(self)
        return strip.as_tuple()
