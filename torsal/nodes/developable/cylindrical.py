"""developable.CylindricalSurface: any curve extruded along one direction."""

from __future__ import annotations

from typing import Any

from torsal.engine.node import LIST, In, Node, Out
from torsal.engine.types import INTEGER, NUMBER, VECTOR
from torsal.engine.values import UNIT_Z
from torsal.nodes.common import checks as check
from torsal.nodes.common import geometry_checks
from torsal.nodes.common.checks import direction
from torsal.nodes.common.convert import kernel_errors
from torsal.nodes.common.stations import along_tangent, first_where
from torsal.nodes.common.strip_outputs import WARP_HELP, strip_outputs
from torsal.nodes.common.values import CURVE, LINE, SURFACE
from torsal.nodes.geometry.curves.line import Line
from torsal.nodes.geometry.developable.direct import cylinder_rulings
from torsal.nodes.geometry.ruled import RuledSurface
from torsal.nodes.limits import MAX_SEGMENTS


class CylindricalSurface(Node):
    """Extrude any curve along one direction: the simplest developable.

    Every ruling starts on the Curve and runs Height along Direction, so all rulings
    are parallel and the surface unrolls to a strip as wide as the curve is long.
    The Curve may be planar or not, open or closed (a closed curve gives a closed
    tube: its last ruling repeats the first). Rulings are spaced evenly along the
    curve by arc length, as Divide Curve would.

    Direction (0, 0, 1) with Height 3 on a circle of radius 2 gives an upright
    cylinder 3 high; a negative Height extrudes the other way. Both edges of every
    ruling share the curve's tangent, so every WarpAngle is 0 (to rounding) — NaN
    where Direction is parallel to the curve (no tangent plane there).

    Warns where Direction is parallel to the curve: the strip has no width there —
    tilt Direction away from the curve.
    """

    type_id = "developable.CylindricalSurface"
    nickname, aliases = "CylS", ("Extrude", "Extrude Curve", "developable cylinder")
    inputs = (
        In("Curve", CURVE, "C", "The section curve the rulings start from, planar or not."),
        In("Direction", VECTOR, "D", "Direction of the rulings (only its direction counts).",
           default=UNIT_Z),
        In("Height", NUMBER, "H",
           "Length of every ruling, in model units; negative extrudes against Direction.",
           default=1.0),
        In("Segments", INTEGER, "S", "Number of rulings minus one (1 or more).", default=24,
           min=1, max=MAX_SEGMENTS),
    )
    outputs = (
        Out("Surface", SURFACE, "S", "The cylinder: the ruled surface through the rulings."),
        Out("Rulings", LINE, "R", "The straight generators, parallel, each Height long.",
            access=LIST),
        Out("WarpAngles", NUMBER, "W", f"{WARP_HELP} Measured with the curve's exact tangents.", access=LIST),
    )

    def solve(self, curve: Any, direction_: Any, height: Any, segments: Any
              ) -> tuple[RuledSurface, list[Line], list[float]]:
        c = geometry_checks.curve("Curve", curve)
        d = direction("Direction", direction_)
        h = check.length("Height", height)
        n = check.segments(segments)
        with kernel_errors():
            r = cylinder_rulings(c, d, h, n)
        flat = along_tangent(r.ends - r.starts, r.start_tangents)
        if flat.any():
            self.warn(
                f"Direction is parallel to the curve at {first_where(flat, r.parameters)}: "
                "the surface has no width there (no tangent plane: its WarpAngles are NaN); tilt "
                "Direction away from the curve"
            )
        strip = strip_outputs(r.starts, r.ends, r.start_tangents, r.end_tangents)
        strip.report(self, explained=flat)
        return strip.as_tuple()
