"""Free-form curves: interpolated splines, NURBS curves from control points, and curves
from X, Y, Z expressions."""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np

from torsal.engine.node import LIST, In, Node, NodeWarning, Out
from torsal.engine.types import BOOLEAN, DOMAIN, INTEGER, NUMBER, POINT, TEXT, VECTOR
from torsal.engine.values import Domain, Vector
from torsal.nodes.common.checks import MAX_DEGREE, ZERO_LENGTH, number, point_list, xyz
from torsal.nodes.common.checks import degree as degree_input
from torsal.nodes.common.convert import kernel_errors
from torsal.nodes.common.formulas import formula
from torsal.nodes.common.values import CURVE
from torsal.nodes.geometry import curves as kernel
from torsal.nodes.geometry.curve_base import Curve

FREE_END = Vector(0.0, 0.0, 0.0)
"""Tangent input default: the zero vector leaves that end of the curve free."""

def _no_repeats(points: np.ndarray) -> None:
    """Refuse a vertex equal to the next one: no spline passes through a point twice in a row."""
    same = np.flatnonzero(np.all(points[1:] == points[:-1], axis=1))
    if len(same):
        i = int(same[0])
        raise NodeWarning(
            f"Vertices {i} and {i + 1} are the same point: the curve cannot pass through one "
            "point twice in a row (remove the duplicate)"
        )


def _free(value: Any) -> bool:
    """Whether an end tangent is the default free end (no arrays made)."""
    return value is None or (isinstance(value, tuple) and value == FREE_END)


def _tangent(name: str, value: Any) -> np.ndarray | None:
    """An end tangent, or None for a free end (the zero vector)."""
    if _free(value):
        return None
    array = xyz(name, value)
    return None if float(np.linalg.norm(array)) <= ZERO_LENGTH else array


class Interpolate(Node):
    """A smooth curve that passes exactly through every vertex, in order.

    The spline is cubic by default (Degree 3) and parameterised by chord length:
    vertex i sits at t = (distance along the vertices up to i) / (total). With
    Closed on, the curve joins back to its first vertex smoothly (C² across the
    seam). StartTangent and EndTangent fix the directions at the ends of an open
    curve (their lengths do not matter; the zero vector leaves an end free) and
    make the curve cubic. With fewer than Degree + 1 vertices the degree drops,
    with a warning: 2 vertices give a straight line, 3 a parabola.

    Two vertices in a row at the same place are refused, since no curve can pass
    through one point twice in a row. When all the vertices are one point the node
    warns and hands on a zero-length curve there, so the nodes it feeds say that their
    curve has zero length.
    """

    type_id = "curves.Interpolate"
    nickname, aliases = "IntCrv", ("Interpolate Curve", "spline through points")
    inputs = (
        In("Vertices", POINT, "V",
           "The points the curve passes through, in order.", access=LIST),
        In("Degree", INTEGER, "D", "Degree of the spline: 3 is cubic, 1 joins the points straight.",
           default=3),
        In("Closed", BOOLEAN, "C", "Whether the curve joins back smoothly to its first vertex.",
           default=False),
        In("StartTangent", VECTOR, "Ts", "Direction at the start; zero leaves the start free.",
           default=FREE_END),
        In("EndTangent", VECTOR, "Te", "Direction at the end; zero leaves the end free.",
           default=FREE_END),
    )
    outputs = (Out("Curve", CURVE, "C", "The spline through the vertices."),)

    def solve(
        self, vertices: list[Any], degree: Any, closed: bool, start: Any, end: Any
    ) -> kernel.InterpolatedCurve | kernel.Line:
        points = point_list("Vertices", vertices)
        k = degree_input("Degree", degree)
        start_tangent, end_tangent = _tangent("StartTangent", start), _tangent("EndTangent", end)
        tangents = start_tangent is not None or end_tangent is not None
        if closed and tangents:
            raise NodeWarning("A closed curve has no ends: leave StartTangent and EndTangent at zero")
        if len(points) > 1 and np.all(points == points[0]):
            # hand on a zero-length curve at that point, so the nodes downstream can say so
            self.warn("All the vertices are the same point, so the curve has zero length")
            return kernel.Line(points[0], points[0])
        _no_repeats(points)
        if closed:
            unique = points[:-1] if len(points) > 1 and np.array_equal(points[0], points[-1]) else points
            if len(unique) < 3:
                raise NodeWarning(f"A closed curve needs at least 3 different vertices; got {len(unique)}")
        elif len(points) < 2:
            raise NodeWarning(f"A curve needs at least 2 vertices; got {len(points)}")
        elif tangents and k != 3:
            self.remark(f"End tangents make the curve cubic: Degree {k} was not used")
        elif not tangents and len(points) < k + 1:
            self.warn(
                f"Degree {k} needs at least {k + 1} vertices; with {len(points)} the curve has "
                f"degree {len(points) - 1}"
            )
        with kernel_errors():
            return kernel.InterpolatedCurve(
                points, closed=bool(closed), start_tangent=start_tangent, end_tangent=end_tangent,
                degree=k,
            )


    def solve_many(self, vertices: Sequence[Any], degrees: Sequence[Any], closed: Sequence[Any],
                   starts: Sequence[Any], ends: Sequence[Any]) -> list[Any] | None:
        """Every call at once when all are open curves with free ends through as many
        vertices each: the vertices checked as one array (finite, no point twice in a row,
        enough for the degree), then a spline per call as :meth:`solve` makes it. Any call
        :meth:`solve` would warn about or make otherwise leaves them all to it."""
        count = len(vertices[0])
        if any(len(v) != count for v in vertices) or any(
                type(k) is not int or not 1 <= k <= min(MAX_DEGREE, count - 1) for k in degrees):
            return None
        if any(c is not False for c in closed) or not all(map(_free, starts)) or not all(map(_free, ends)):
            return None
        try:
            points = np.asarray(vertices, dtype=float)  # (calls, count, 3)
        except (TypeError, ValueError):  # a null among the points
            return None
        if points.shape[1:] != (count, 3) or not np.isfinite(points).all() or (
                points[:, 1:] == points[:, :-1]).all(axis=2).any():
            return None
        token = self.token
        token.check()
        if all(k >= count - 1 for k in degrees):  # one polynomial span each: all solved at once
            return kernel.InterpolatedCurve.beziers(points)
        curves = []
        try:
            for p, k in zip(points, degrees, strict=True):
                token.check()  # (a spline through many vertices takes a while)
                curves.append(kernel.InterpolatedCurve(
                    p, closed=False, start_tangent=None, end_tangent=None, degree=k))
        except ValueError:  # the kernel refuses one: solve says why
            return None
        return curves


class NurbsCurve(Node):
    """A NURBS curve pulled towards its control points (Vertices), not through them.

    A degree-d curve needs at least d + 1 vertices; its knots are uniform and
    clamped, so it starts at the first vertex and ends at the last. Weights, one per
    vertex, pull the curve harder towards the vertices with larger weights (all equal
    weights give the plain B-spline). With Periodic on the curve closes smoothly,
    looping past the last vertex back to the first.
    """

    type_id = "curves.NurbsCurve"
    nickname, aliases = "Nurbs", ("control point curve", "spline")
    inputs = (
        In("Vertices", POINT, "V",
           "The control points, in order.", access=LIST),
        In("Degree", INTEGER, "D", "Degree of the curve: at most the number of vertices minus 1.",
           default=3),
        In("Weights", NUMBER, "W", "One positive weight per vertex; leave empty for all 1.",
           access=LIST, optional=True),
        In("Periodic", BOOLEAN, "P", "Whether the curve closes smoothly on itself.", default=False),
    )
    outputs = (Out("Curve", CURVE, "C", "The NURBS curve."),)

    def solve(
        self, vertices: list[Any], degree: Any, weights: list[Any], periodic: bool
    ) -> kernel.NurbsCurve:
        points = point_list("Vertices", vertices)
        k = degree_input("Degree", degree)
        if len(points) < k + 1:
            raise NodeWarning(
                f"A degree-{k} curve needs at least {k + 1} vertices; got {len(points)} "
                f"(lower Degree to {max(len(points) - 1, 1)} or add vertices)"
            )
        w = None
        if weights:
            if len(weights) != len(points):
                raise NodeWarning(
                    f"Give one weight per vertex: there are {len(points)} vertices and {len(weights)} weights"
                )
            w = np.array([number(f"Weight {i}", x) for i, x in enumerate(weights)])
            bad = np.flatnonzero(w <= 0)
            if len(bad):
                raise NodeWarning(f"Weights must be positive; weight {bad[0]} is {w[bad[0]]:g}")
        with kernel_errors():
            return kernel.NurbsCurve(points, degree=k, weights=w, periodic=bool(periodic))


class ParametricCurve(Node):
    """A curve from three formulas in t: the point (X(t), Y(t), Z(t)) for t over a Domain.

    The formulas use the language of the Expression node (``sin cos sqrt pi`` ...,
    angles in radians). The defaults, X = ``cos(t)``, Y = ``sin(t)``, Z = ``0`` over
    0 to 2π, give the unit circle; Z = ``0.1 * t`` turns it into a helix. The output
    curve is reparameterised to 0 … 1 like every curve: its t = 0.5 is the middle of
    the Domain. A reversed Domain runs the curve backwards. Derivatives (tangents,
    curvature) are computed by high-order finite differences, good to about 1e-10.
    """

    type_id = "curves.ParametricCurve"
    nickname, aliases = "ParCrv", ("function curve",)
    inputs = (
        In("X", TEXT, "X", "Formula in t for the X coordinate.", default="cos(t)"),
        In("Y", TEXT, "Y", "Formula in t for the Y coordinate.", default="sin(t)"),
        In("Z", TEXT, "Z", "Formula in t for the Z coordinate.", default="0"),
        In("Domain", DOMAIN, "D", "The values of t the curve runs over.",
           default=Domain(0.0, 2 * math.pi)),
    )
    outputs = (Out("Curve", CURVE, "C", "The curve traced by (X, Y, Z) as t runs over the Domain."),)

    def solve(self, x: Any, y: Any, z: Any, domain: Any) -> Curve:
        formulas = [formula(name, text, ("t",)) for name, text in (("X", x), ("Y", y), ("Z", z))]
        if domain is None:
            raise NodeWarning("Domain is empty (null)")
        a, b = number("Domain start", domain.min), number("Domain end", domain.max)
        if a == b:
            raise NodeWarning(f"The Domain is empty ({a:g} to {b:g}): t must run over an interval")
        fx, fy, fz = formulas

        def function(t: np.ndarray) -> tuple[Any, Any, Any]:
            return fx(t=t), fy(t=t), fz(t=t)

        low, high = min(a, b), max(a, b)
        probe = np.linspace(low, high, 1001)
        values = np.column_stack([np.broadcast_to(np.asarray(v, dtype=float), probe.shape)
                                  for v in function(probe)])
        bad = ~np.all(np.isfinite(values), axis=1)
        if bad.any():
            raise NodeWarning(
                f"The formulas give no finite point at t = {probe[np.argmax(bad)]:g} "
                "(division by zero, or a square root of a negative number?)"
            )
        with kernel_errors():
            curve = kernel.ParametricCurve(function, (low, high))
        return curve if a < b else curve.reversed()
