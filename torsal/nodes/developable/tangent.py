"""developable.TangentDevelopable: the surface swept by a space curve's tangent lines."""

from __future__ import annotations

from typing import Any

import numpy as np

from torsal.engine.node import LIST, In, Node, NodeWarning, Out
from torsal.engine.types import BOOLEAN, INTEGER, NUMBER
from torsal.nodes.common import checks as check
from torsal.nodes.common import geometry_checks
from torsal.nodes.common.checks import number
from torsal.nodes.common.convert import kernel_errors
from torsal.nodes.common.stations import first_where
from torsal.nodes.common.strip_outputs import WARP_HELP, strip_outputs
from torsal.nodes.common.values import CURVE, LINE, SURFACE
from torsal.nodes.geometry.curves.line import Line
from torsal.nodes.geometry.developable.direct import tangent_developable_rulings
from torsal.nodes.geometry.developable.warp import warp_angles
from torsal.nodes.geometry.ruled import RuledSurface
from torsal.nodes.limits import MAX_SEGMENTS

#: Curvature × curve length below which the curve counts as straight at a station.
STRAIGHT = 1e-9


class TangentDevelopable(Node):
    """Sweep the tangent lines of a space curve: S(u, v) = C(u) + v·T(u).

    Every ruling lies on the curve's tangent at its station, so the surface is
    developable whatever the curve, and the curve becomes its edge of regression
    (the sharp crease where the surface folds back on itself). Tangents come from
    the curve's exact derivatives, not from neighbouring points.

    One-sided (default), each ruling runs along the unit tangent from
    v = CuttingLength to v = Length (model units, measured from the curve): a
    CuttingLength above 0 keeps the sheet clear of the crease. TwoSided, each ruling
    runs from v = −Length to v = Length, through the curve, so both sheets meeting
    at the crease are shown (CuttingLength is then not used). The CurveOfRegression
    node recovers the curve from the surface.

    WarpAngles measure the turn of the tangent plane along each ruling (0 to π). A
    ruling that starts on the curve (CuttingLength 0) starts on the edge of regression,
    where the sheet has no normal of its own; there, as at a cone's apex, the plane is
    the one along the rest of the ruling. A ruling that runs through the curve
    (TwoSided, or a negative CuttingLength) crosses the crease, where the sheet folds
    back and its normal flips: its warp is the larger of the two sheets' warps, not
    the flip (which would read π).

    A straight curve has a single tangent line: the surface degenerates to that line
    (the node warns; give the curve some bend).
    """

    type_id = "developable.TangentDevelopable"
    nickname, aliases = "TanDev", ("tangent surface", "tangent lines")
    inputs = (
        In("Curve", CURVE, "C", "The space curve whose tangents sweep the surface (its edge of regression)."),
        In("Segments", INTEGER, "S", "Number of rulings minus one (1 or more).", default=24,
           min=1, max=MAX_SEGMENTS),
        In("Length", NUMBER, "L",
           "Where each ruling ends, measured along the tangent from the curve, model units.",
           default=1.0),
        In("CuttingLength", NUMBER, "Cl",
           "Where each ruling starts along the tangent (0 = on the curve); less than Length.",
           default=0.0),
        In("TwoSided", BOOLEAN, "2",
           "Run each ruling from −Length to Length through the curve (both sheets).",
           default=False),
    )
    outputs = (
        Out("Surface", SURFACE, "S", "The tangent developable: the ruled surface through the rulings."),
        Out("Rulings", LINE, "R", "The tangent segments, one per station.", access=LIST),
        Out("WarpAngles", NUMBER, "W", f"{WARP_HELP} Measured with the curve's exact derivatives; a "
            "ruling through the curve on each sheet.", access=LIST),
    )

    def solve(self, curve: Any, segments: Any, length: Any, cutting_length: Any, two_sided: Any
              ) -> tuple[RuledSurface, list[Line], list[float]]:
        c = geometry_checks.curve("Curve", curve)
        n = check.segments(segments)
        far = number("Length", length)
        near = number("CuttingLength", cutting_length)
        if two_sided:
            if far <= 0:
                raise NodeWarning(
                    f"Length is {far:g}: two-sided rulings run from −Length to Length, so give a "
                    "positive Length"
                )
            if near != 0:
                self.remark("CuttingLength is not used when TwoSided is on: each ruling runs "
                            "from −Length to Length through the curve")
            near = -far
        elif far <= near:
            raise NodeWarning(
                f"Length ({far:g}) must be greater than CuttingLength ({near:g}): the ruling runs "
                "from CuttingLength to Length along the tangent"
            )
        with kernel_errors():
            r = tangent_developable_rulings(c, n, far, near)
        bend = c.curvature_at(r.parameters) * c.length
        straight = ~(bend > STRAIGHT)
        t = c.tangent_at(r.parameters)
        one_line = np.linalg.norm(np.cross(t, t[0]), axis=1).max() <= STRAIGHT
        if one_line:
            self.warn("The curve is straight, so all its tangents lie on one line: the tangent "
                      "developable degenerates to that line (no area, no tangent plane: WarpAngles NaN); "
                      "give the curve some bend")
        elif straight.all():
            self.warn("The curve has no bend at any station (straight pieces, as in a polyline): "
                      "neighbouring rulings lie on one line, so the surface has no area (WarpAngles NaN); "
                      "use a smooth curve, e.g. Interpolate")
        elif straight.any():
            self.remark(
                f"The curve is straight at {first_where(straight, r.parameters)}: the surface "
                "has no width there (neighbouring rulings lie on one line; no tangent plane: WarpAngle NaN)"
            )
        if near < 0 < far:
            warp = _two_sheet_warp(c, r.parameters, r.starts, r.ends, r.start_tangents, r.end_tangents)
            strip = strip_outputs(r.starts, r.ends, warp=warp)
        else:
            strip = strip_outputs(r.starts, r.ends, r.start_tangents, r.end_tangents,
                                  apex_a=near == 0, apex_b=far == 0)
        strip.report(self, explained=straight | one_line)
        return strip.as_tuple()


def _two_sheet_warp(curve, parameters, starts, ends, start_tangents, end_tangents) -> np.ndarray:
    """Warp of rulings that cross the curve (the edge of regression): the larger of the warps
    of the two halves, each measured from the curve (where it takes the other end's plane)."""
    points = curve.point_at(parameters)
    tangents = curve.tangent_at(parameters)
    back = warp_angles(starts, points, start_tangents, tangents, apex_b=True)
    ahead = warp_angles(points, ends, tangents, end_tangents, apex_a=True)
    return np.maximum(back, ahead)
