"""Joining curves end to end, exploding them into segments and splitting them at parameters."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from torsal.engine.node import LIST, In, Node, NodeWarning, Out
from torsal.engine.types import NUMBER, POINT
from torsal.engine.values import Point
from torsal.nodes.common.checks import given, number
from torsal.nodes.common.convert import points
from torsal.nodes.common.geometry_checks import has_no_length
from torsal.nodes.common.values import CURVE
from torsal.nodes.geometry.curve_base import Curve
from torsal.nodes.geometry.curves.pieces import explode, join, size_of, split
from torsal.nodes.limits import MAX_DIVISIONS

#: Ends closer than this share of the curves' overall size meet, when no Tolerance is given.
RELATIVE_GAP = 1e-6


class JoinCurves(Node):
    """Join curves whose ends meet into longer curves, as Rhino's Join does.

    Curves are chained in input order: each chain starts at the first curve not yet
    joined and grows at both ends, a curve running backwards being reversed to fit. Ends
    meet when they are within Tolerance of each other (model units; empty: a millionth
    of the size of all the curves together). Lines and polylines join into one polyline
    (its corners where they met); other curves into a poly-curve, parameterised by
    length. Curves that meet nothing come out as they went in.
    """

    type_id = "curves.JoinCurves"
    nickname, aliases = "Join", ("Join Curves", "join", "chain curves", "polycurve")
    inputs = (
        In("Curves", CURVE, "C", "The curves to join.", access=LIST),
        In("Tolerance", NUMBER, "T", "How far apart two ends may be and still meet, in model units.",
           optional=True),
    )
    outputs = (Out("Curves", CURVE, "C", "The joined curves, one per chain.", access=LIST),)

    def solve(self, curves: list[Any], tolerance: Any) -> list[Curve]:
        if any(c is None for c in curves):
            raise NodeWarning("Curves contains empty (null) items: remove them or fix what made them")
        if not curves:
            return []
        with_length = [c for c in curves if not has_no_length(c)]
        if len(with_length) < len(curves):
            self.remark(f"{len(curves) - len(with_length)} of the Curves have zero length and were left out")
        if not with_length:
            return []
        if tolerance is None:
            gap = RELATIVE_GAP * size_of(with_length)
        else:
            gap = number("Tolerance", tolerance)
            if gap < 0:
                raise NodeWarning(f"Tolerance must be 0 or more, not {gap:g}")
        return join(with_length, gap)


class Explode(Node):
    """Break a curve into its segments, with the points where they meet.

    A polyline gives its straight segments, a joined curve the curves it was joined
    from (each exploded in turn), a NURBS curve its pieces between kinks (corners where
    the tangent jumps); a smooth curve gives itself. Vertices are the segments' start
    points and the last one's end (not repeated on a closed curve).
    """

    type_id = "curves.Explode"
    nickname, aliases = "Explode", ("Explode Curve", "segments", "break curve", "polyline segments")
    inputs = (In("Curve", CURVE, "C", "The curve to break up."),)
    outputs = (
        Out("Segments", CURVE, "S", "The pieces, in order along the curve.", access=LIST),
        Out("Vertices", POINT, "V", "Where the pieces meet, and the two ends.", access=LIST),
    )

    def solve(self, curve: Any) -> tuple[list[Curve], list[Point]]:
        c = given("Curve", curve)
        pieces = explode(c)
        corners = [piece.end_points[0] for piece in pieces]
        if not c.closed:
            corners.append(pieces[-1].end_points[1])
        return pieces, points(np.asarray(corners))


class Shatter(Node):
    """Cut a curve at parameters t (0 to 1, as Evaluate Curve reads them) into pieces.

    Parameters at or past the ends, and repeats, cut nothing; a closed curve cut at one
    inner parameter gives two pieces. Lines and polylines give exact lines and
    polylines; other curves give the parts of themselves between the cuts. To cut at
    points, find their parameters with Curve Closest Point; to cut into equal lengths,
    use the parameters of Divide Curve.
    """

    type_id = "curves.Shatter"
    nickname, aliases = "Shatter", ("Split Curve", "split", "cut curve", "Split", "Shatter Curve")
    inputs = (
        In("Curve", CURVE, "C", "The curve to cut."),
        In("Parameters", NUMBER, "t", "Where to cut: curve parameters t from 0 to 1.", access=LIST),
    )
    outputs = (Out("Segments", CURVE, "S", "The pieces, in order along the curve.", access=LIST),)

    def solve(self, curve: Any, parameters: list[Any]) -> list[Curve]:
        c = given("Curve", curve)
        if any(t is None for t in parameters):
            raise NodeWarning("Parameters contains empty (null) items: remove them or fix what made them")
        t = np.asarray(parameters, dtype=float).reshape(-1)
        if not np.all(np.isfinite(t)):
            raise NodeWarning("Parameters contains a value that is not a finite number")
        if len(t) > MAX_DIVISIONS:
            raise NodeWarning(f"Parameters holds {len(t):,} cuts; at most {MAX_DIVISIONS:,}")
        outside = int(np.count_nonzero((t < 0) | (t > 1)))
        if outside:
            self.remark(f"{outside} of the Parameters lie outside 0 to 1 and cut nothing")
        pieces = split(c, t)
        if has_no_length(c) or not all(math.isfinite(p.length) for p in pieces):
            raise NodeWarning("Curve has zero length, so it cannot be cut")
        return pieces
