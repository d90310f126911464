"""analysis.CurveOfRegression: the sharp edge every ruling of a developable touches."""

from __future__ import annotations

from typing import Any

import numpy as np

from torsal.engine.node import LIST, In, Node, NodeWarning, Out
from torsal.engine.types import INTEGER, NUMBER, POINT
from torsal.engine.values import Point
from torsal.nodes.common.checks import angle, whole
from torsal.nodes.common.convert import point, points, sentence
from torsal.nodes.common.geometry_checks import ruled_surface
from torsal.nodes.common.values import CURVE, SURFACE
from torsal.nodes.geometry.curve_base import Curve
from torsal.nodes.geometry.curves import InterpolatedCurve
from torsal.nodes.geometry.regression import curve_of_regression
from torsal.nodes.limits import MAX_ANALYSIS_SEGMENTS

#: Points of regression all within this share of the surface's size of one point make a
#: cone: a loft through a cone's rulings, sampled between them, misses its apex slightly.
APEX_SPREAD = 1e-4


def nearest_point_to_lines(starts: np.ndarray, ends: np.ndarray) -> np.ndarray:
    """The point with the least summed squared distance to the lines through the rulings."""
    d = ends - starts
    d /= np.linalg.norm(d, axis=1, keepdims=True)
    projector = np.eye(3)[None] - d[:, :, None] * d[:, None, :]  # onto each line's normal plane
    return np.linalg.solve(projector.sum(axis=0), np.einsum("kij,kj->i", projector, starts))


def looks_like_cone(points: np.ndarray, size: float) -> bool:
    """Whether the points of regression huddle within APEX_SPREAD of the size (a cone)."""
    finite = points[np.isfinite(points).all(axis=1)]
    if len(finite) < 2:
        return False
    return float(np.linalg.norm(finite - finite.mean(axis=0), axis=1).max()) <= APEX_SPREAD * size


def piece_curve(piece: np.ndarray) -> Curve | None:
    """The cubic spline through one valid run of points (repeated points dropped), or
    None when fewer than two distinct points are left."""
    size = float(np.ptp(piece, axis=0).max()) if len(piece) else 0.0
    if size == 0.0:
        return None
    keep = np.r_[True, np.linalg.norm(np.diff(piece, axis=0), axis=1) > 1e-12 * size]
    distinct = piece[keep]
    return InterpolatedCurve(distinct) if len(distinct) >= 2 else None


class CurveOfRegression(Node):
    """The curve of regression of a developable: the curve all its rulings touch.

    Every developable other than a plane, a cylinder or a cone is swept by the
    tangents of one space curve, its curve of regression (or edge of regression):
    the sharp cusp where the surface folds back on itself, usually outside the part
    you model. Knowing it tells you where a sheet cannot be bent to, and the
    tangent developable of it (TangentDevelopable) rebuilds the whole surface.

    Segments + 1 rulings are taken from the surface. For each pair of neighbours the
    points where their lines come closest are found; each ruling gets the midpoint
    of its two such points (the ends keep theirs), and a cubic spline through them
    is the curve. A stretch is kept only while the curve runs along the rulings, as
    a tangent must: a segment turning more than Deviation (rad) away from them ends
    a piece, so the output is a list of curves, split where the surface is not
    developable within Deviation. More Segments give a closer curve.

    A plane or a cylinder (parallel rulings) and a twisted ruled surface such as a
    hyperbolic paraboloid (rulings that never meet) have no curve of regression: the
    node warns. A cone has an apex instead, given as the only Point.
    """

    type_id = "analysis.CurveOfRegression"
    nickname, aliases = "CoR", ("edge of regression", "cuspidal edge", "striction curve")
    inputs = (
        In("Surface", SURFACE, "S", "The ruled surface, ideally developable."),
        In("Deviation", NUMBER, "D", "How far (rad) the curve may turn away from the rulings it "
           "touches and still count, e.g. 0.01.", default=0.01),
        In("Segments", INTEGER, "N", "How many strips between rulings to sample (rulings minus one).",
           default=100, min=1, max=MAX_ANALYSIS_SEGMENTS),
    )
    outputs = (
        Out("Curves", CURVE, "C", "The curve of regression, one curve per valid piece.", access=LIST),
        Out("Points", POINT, "P", "The points the curves interpolate, in order (a cone: its apex).",
            access=LIST),
    )

    def solve(self, surface: Any, deviation: Any, count: Any) -> tuple[list[Curve], list[Point]]:
        s = ruled_surface(surface, "CurveOfRegression")
        tolerance = angle("Deviation", deviation, "0.01")
        n = whole("Segments", count)  # 1 to MAX_ANALYSIS_SEGMENTS: the port's bounds
        rulings = s.rulings(n + 1)
        try:
            regression = curve_of_regression(rulings[:, 0], rulings[:, 1], tolerance)
        except ValueError as exc:
            raise NodeWarning(f"No curve of regression can be found: {sentence(exc)}") from None
        size = float(np.linalg.norm(np.ptp(rulings.reshape(-1, 3), axis=0)))
        if regression.kind == "apex" or (regression.kind in ("curve", "warped")
                                         and looks_like_cone(regression.points, size)):
            apex = nearest_point_to_lines(rulings[:, 0], rulings[:, 1])
            apex = np.where(np.abs(apex) <= 1e-12 * size, 0.0, apex)  # no −1.8e-17 in the message
            where = ", ".join(f"{x:.6g}" for x in apex)
            self.remark(f"The surface is a cone: every ruling passes through its apex ({where}), so it "
                        "has an apex, not a curve of regression; Points holds the apex")
            return [], [point(apex)]
        if not regression.has_curve:
            raise NodeWarning(regression.message[0].upper() + regression.message[1:])
        curves = [c for c in (piece_curve(p) for p in regression.curves) if c is not None]
        if len(curves) > 1 or not regression.valid.all():
            bad = int((~regression.valid).sum())
            self.warn(f"The curve of regression is split into {len(curves)} pieces: {bad} of "
                      f"{len(regression.valid)} segments turn more than Deviation away from the "
                      "rulings, so the surface is not developable there; raise Deviation or Segments "
                      "to accept them")
        return curves, points(np.vstack(regression.curves))
