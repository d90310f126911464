"""Reading curves: divide, evaluate, measure, reverse and find the ends."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np

from torsal.engine.node import LIST, In, Node, NodeWarning, Out
from torsal.engine.types import INTEGER, NUMBER, POINT, VECTOR
from torsal.engine.values import Point, Vector
from torsal.nodes.common.checks import given, number, whole
from torsal.nodes.common.convert import point, points, vector, vectors
from torsal.nodes.common.values import CURVE
from torsal.nodes.geometry.curve_base import Curve
from torsal.nodes.geometry.curves import Arc, Circle, InterpolatedCurve, Line, NurbsCurve, Polyline
from torsal.nodes.limits import MAX_DIVISIONS


def _curve(value: Any) -> Curve:
    return given("Curve", value)


class DivideCurve(Node):
    """Divide a curve into Count segments of equal length along the curve.

    An open curve gives Count + 1 points, both ends included; a closed curve gives
    Count points (its end would repeat its start). The points are equally spaced by
    arc length, not by parameter: a circle divided by 6 gives the corners of a
    regular hexagon. Tangents are unit vectors in the curve's direction, and
    Parameters are the points' t values, from 0 to 1 like every curve in Torsal.
    """

    type_id = "curves.DivideCurve"
    nickname, aliases = "Divide", ("points on curve", "Divide Length")
    inputs = (
        In("Curve", CURVE, "C", "The curve to divide."),
        In("Count", INTEGER, "N", "How many equal segments to divide it into (1 or more).",
           default=10, min=1, max=MAX_DIVISIONS),
    )
    outputs = (
        Out("Points", POINT, "P", "The division points, from the start.", access=LIST),
        Out("Tangents", VECTOR, "T", "The unit tangent at each point.", access=LIST, preview=False),
        Out("Parameters", NUMBER, "t", "The curve parameter t of each point, 0 to 1.", access=LIST),
    )

    def solve(self, curve: Any, count: Any) -> tuple[list[Point], list[Vector], list[float]]:
        c = _curve(curve)
        n = whole("Count", count)  # 1 to MAX_DIVISIONS: the port's bounds, checked before solve
        if c.length == 0:
            raise NodeWarning("The curve has zero length, so it cannot be divided")
        t = c.divide_by_count(n)
        return points(c.point_at(t)), vectors(c.tangent_at(t)), t.tolist()


class EvaluateCurve(Node):
    """The point, tangent and curvature of a curve at a parameter t from 0 to 1.

    t = 0 is the curve's start and t = 1 its end (t is not proportional to length
    in general: use DivideCurve for equal spacing). Curvature κ is 1 / the radius
    of the circle that best fits the curve there: 1/r everywhere on a circle of
    radius r, 0 on a straight line. CurvatureVector points towards that circle's
    centre and is κ long.
    """

    type_id = "curves.EvaluateCurve"
    nickname, aliases = "Eval", ("point on curve", "Point On Curve", "curve tangent")
    inputs = (
        In("Curve", CURVE, "C", "The curve to evaluate."),
        In("Parameter", NUMBER, "t", "Where on the curve, from 0 (start) to 1 (end)."),
    )
    outputs = (
        Out("Point", POINT, "P", "The point at t."),
        Out("Tangent", VECTOR, "T", "The unit tangent at t, in the curve's direction.", preview=False),
        Out("Curvature", NUMBER, "K", "The curvature κ at t (1 / radius of curvature)."),
        Out("CurvatureVector", VECTOR, "Kv", "Towards the centre of curvature, κ long.", preview=False),
    )

    def solve(self, curve: Any, parameter: Any) -> tuple[Point, Vector, float, Vector]:
        c = _curve(curve)
        t = number("Parameter", parameter)
        if not -1e-12 <= t <= 1 + 1e-12:
            raise NodeWarning(f"Parameter must be from 0 to 1 (the curve's domain), not {t:g}")
        t = min(max(t, 0.0), 1.0)
        return (
            point(c.point_at(t)),
            vector(c.tangent_at(t)),
            float(c.curvature_at(t)),
            vector(c.curvature_vector_at(t)),
        )


    def solve_many(self, curves: Sequence[Any], parameters: Sequence[Any]) -> list[Any] | None:
        """Every call at once, one evaluation per curve of all its parameters: the values
        of :meth:`solve`, bit for bit, since the kinds of curve taken here evaluate each
        parameter on its own (a curve of another kind, or a parameter :meth:`solve` would
        refuse or clamp, leaves the calls to :meth:`solve`)."""
        rows_of: dict[int, list[int]] = {}
        for row, (curve, t) in enumerate(zip(curves, parameters, strict=True)):
            if type(curve) not in _ROW_BY_ROW or type(t) is not float or not 0.0 <= t <= 1.0:
                return None
            rows_of.setdefault(id(curve), []).append(row)
        results: list[Any] = [None] * len(parameters)
        token = self.token
        for rows_of_curve in rows_of.values():
            c = curves[rows_of_curve[0]]
            for start in range(0, len(rows_of_curve), _AT_ONCE):
                token.check()
                rows = rows_of_curve[start:start + _AT_ONCE]
                t = np.array([parameters[row] for row in rows])
                at = zip(Point.many(c.point_at(t).tolist()), Vector.many(c.tangent_at(t).tolist()),
                         c.curvature_at(t).tolist(), Vector.many(c.curvature_vector_at(t).tolist()),
                         strict=True)
                for row, values in zip(rows, at, strict=True):
                    results[row] = values
        return results


#: The kinds of curve whose evaluation at an array of parameters gives each one the very
#: bits it gets alone (de Boor per point, element-wise arithmetic): EvaluateCurve evaluates
#: them all at once. Not TransformedCurve: its (n, 3) @ (3, 3) product takes another BLAS
#: kernel for one row than for several, a last bit apart.
_ROW_BY_ROW = frozenset({NurbsCurve, InterpolatedCurve, Circle, Arc, Line, Polyline})
#: The most parameters of a curve evaluated at once (a few ms): the token is checked between.
_AT_ONCE = 4096


class CurveLength(Node):
    """The length of a curve, measured along it in model units.

    Lines, polylines, circles and arcs are measured exactly; other curves by
    adaptive Gauss–Legendre quadrature, to about 1e-13 relative.
    """

    type_id = "curves.CurveLength"
    nickname, aliases = "Len", ("Length", "Curve Length")
    inputs = (In("Curve", CURVE, "C", "The curve to measure."),)
    outputs = (Out("Length", NUMBER, "L", "The curve's length, in model units."),)

    def solve(self, curve: Any) -> float:
        return float(_curve(curve).length)


class Flip(Node):
    """Reverse a curve's direction: its start becomes its end.

    The shape is unchanged; parameter t on the flipped curve is 1 − t on the
    original, so tangents point the other way.
    """

    type_id = "curves.Flip"
    nickname, aliases = "Flip", ("Flip Curve", "reverse curve")
    inputs = (In("Curve", CURVE, "C", "The curve to reverse."),)
    outputs = (Out("Curve", CURVE, "C", "The same curve, run from end to start."),)

    def solve(self, curve: Any) -> Curve:
        return _curve(curve).reversed()


class EndPoints(Node):
    """The first and last points of a curve (the same point on a closed curve)."""

    type_id = "curves.EndPoints"
    nickname, aliases = "End", ("start point", "end point")
    inputs = (In("Curve", CURVE, "C", "The curve whose ends to find."),)
    outputs = (
        Out("Start", POINT, "S", "The point at t = 0."),
        Out("End", POINT, "E", "The point at t = 1."),
    )

    def solve(self, curve: Any) -> tuple[Point, Point]:
        c = _curve(curve)
        return point(np.asarray(c.start)), point(np.asarray(c.end))
