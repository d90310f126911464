"""developable.ConicalSurface: any curve joined to one point, the apex."""

from __future__ import annotations

from typing import Any

import numpy as np

from torsal.engine.node import LIST, In, Node, NodeWarning, Out
from torsal.engine.types import INTEGER, NUMBER, POINT
from torsal.engine.values import Point
from torsal.nodes.common import checks as check
from torsal.nodes.common import geometry_checks
from torsal.nodes.common.checks import xyz
from torsal.nodes.common.convert import kernel_errors
from torsal.nodes.common.stations import COINCIDENT, along_tangent, first_where
from torsal.nodes.common.strip_outputs import WARP_HELP, strip_outputs
from torsal.nodes.common.values import CURVE, LINE, SURFACE
from torsal.nodes.geometry.curves.line import Line
from torsal.nodes.geometry.developable.direct import cone_rulings
from torsal.nodes.geometry.ruled import RuledSurface
from torsal.nodes.limits import MAX_SEGMENTS, MAX_STRIP_SOLVES


class ConicalSurface(Node):
    """Join any curve to one point, the Apex: a cone, always developable.

    Each ruling starts on the Curve and runs straight towards the Apex for Height
    (model units). A ruling that would pass the Apex stops there (clamped), so a
    Height at least the largest distance from the curve to the Apex gives the whole
    cone, rulings meeting at its tip; a smaller Height gives a ring, like one storey
    of the Guggenheim's spiral. A negative Height runs the rulings away from the
    Apex (the flaring part of the same cone). The Curve may be planar or not, open or
    closed; rulings are spaced evenly along it by arc length.

    The curve must not pass through the Apex (a ruling there would have no length):
    move the Apex off the curve. Warns where a ruling runs along the curve's own
    tangent (the surface has no width there; its WarpAngle is NaN). Rulings that reach
    the Apex are a fan of flat triangles there: their warp is measured in the
    triangles' plane, which holds the ruling and the curve's tangent, so it is 0.
    """

    type_id = "developable.ConicalSurface"
    max_calls = MAX_STRIP_SOLVES  # a list of values multiplies the strips solved (limits.py)
    nickname, aliases = "ConS", ("developable cone", "apex surface")
    inputs = (
        In("Curve", CURVE, "C", "The base curve the rulings start from, planar or not."),
        In("Apex", POINT, "A", "The cone's tip, where all rulings meet.", default=Point(0, 0, 1)),
        In("Height", NUMBER, "H",
           "Length of every ruling towards the Apex, model units; clamped at the Apex.",
           default=1.0),
        In("Segments", INTEGER, "S", "Number of rulings minus one (1 or more).", default=24,
           min=1, max=MAX_SEGMENTS),
    )
    outputs = (
        Out("Surface", SURFACE, "S", "The cone: the ruled surface through the rulings."),
        Out("Rulings", LINE, "R",
            "The straight generators, from the curve towards the Apex, Height long or ending at it.",
            access=LIST),
        Out("WarpAngles", NUMBER, "W", f"{WARP_HELP} Measured with the curve's exact tangents; a "
            "ruling ending at the Apex in the plane of its fan triangles.", access=LIST),
    )

    def solve(self, curve: Any, apex: Any, height: Any, segments: Any
              ) -> tuple[RuledSurface, list[Line], list[float]]:
        c = geometry_checks.curve("Curve", curve)
        p = xyz("Apex", apex)
        h = check.length("Height", height)
        n = check.segments(segments)
        with kernel_errors():
            r = cone_rulings(c, p, h, n)
        distance = np.linalg.norm(p - r.starts, axis=1)
        size = float(np.ptp(np.vstack([r.starts, p]), axis=0).max()) or 1.0
        through = distance <= COINCIDENT * size
        if through.any():
            raise NodeWarning(
                f"The curve passes through the Apex at {first_where(through, r.parameters)}: "
                "a ruling there would have no length; move the Apex off the curve"
            )
        flat = along_tangent(p - r.starts, r.start_tangents)
        if flat.any():
            self.warn(
                f"The Apex lies on the curve's tangent line at {first_where(flat, r.parameters)}: "
                "the surface has no width there (no tangent plane: its WarpAngles are NaN); move the Apex"
            )
        reach = (h >= distance) & (h > 0)
        if reach.any():
            self.remark(
                f"{int(reach.sum())} of {reach.size} rulings reach the Apex within Height and stop there"
            )
        strip = strip_outputs(r.starts, r.ends, r.start_tangents, r.end_tangents)
        strip.report(self, explained=flat)
        return strip.as_tuple()
