"""developable.SurfaceCoupling: a developable that joins two patches smoothly along
straight edges."""

from __future__ import annotations

from typing import Any

from torsal.engine.node import LIST, In, Node, Out
from torsal.engine.types import INTEGER, NUMBER
from torsal.nodes.common.checks import edge as edge_input
from torsal.nodes.common.checks import segments as segments_input
from torsal.nodes.common.convert import kernel_errors
from torsal.nodes.common.geometry_checks import parametric_surface as surface_input
from torsal.nodes.common.strip_outputs import WARP_HELP, curve_strip_outputs
from torsal.nodes.common.values import CURVE, LINE, SURFACE
from torsal.nodes.developable.ruling_developable import solve_strip
from torsal.nodes.geometry.coupling import couple
from torsal.nodes.limits import MAX_COUPLING_SEGMENTS

#: Warp tolerance (rad) for the connecting strip's rulings, as RulingDevelopable's default.
WARP_TOLERANCE = 0.01
#: An edge whose two end tangent planes differ by more than this (rad) is not torsal.
EDGE_WARP = 1e-6


class SurfaceCoupling(Node):
    """Join two surface patches with a third, developable one that continues both
    smoothly (G1: no crease) across their facing straight edges.

    Pick a straight edge on each patch — a ruling, e.g. the end of a cone or cylinder
    strip. Edges are numbered as everywhere in Torsal, around the (u, v) square:
    0 is v = 0 (u from 0 to 1), 1 is u = 1, 2 is v = 1, 3 is u = 0; a loft between two
    curves has its rulings at edges 1 and 3. The node draws two cubic space curves
    (CurveA from the start of EdgeA, CurveB from its end, both ending on the other
    patch's edge, each with four control points). Each leaves its patch exactly along
    the patch's boundary tangent, so it lies in the patch's tangent plane; the inner
    control points sit 2/3 of the way to where the two patches' tangent planes meet
    (the thesis's construction). Between the two curves the connecting developable is
    built as RulingDevelopable would, so Surface shares a ruling and a tangent plane
    with each patch.

    The join is exact for patches that admit one — e.g. two cones with a common apex
    cut by the same two parallel planes, or two cylinders with parallel rulings
    between the same two planes (the connector is then a cone or a cylinder too).
    Otherwise some rulings cannot be made torsal: the node warns with their count;
    then move or turn a patch so that its edge ruling and tangent plane suit the other.
    Both edges must be straight, and for a smooth join both should be torsal rulings
    of developable patches; a double-curved patch is warned about. A pair of patches that
    cannot be joined (a curved edge, edges that share a corner) is warned about and gets
    null outputs; the other pairs are still joined.
    """

    type_id = "developable.SurfaceCoupling"
    nickname, aliases = "Couple", ("Blend Surface", "blend", "join surfaces")
    inputs = (
        In("SurfaceA", SURFACE, "A", "The first patch."),
        In("SurfaceB", SURFACE, "B", "The second patch."),
        In("EdgeA", INTEGER, "EA",
           "Straight edge of SurfaceA to join: 0 (v = 0), 1 (u = 1), 2 (v = 1) or 3 (u = 0).", default=1),
        In("EdgeB", INTEGER, "EB",
           "Straight edge of SurfaceB to join: 0 (v = 0), 1 (u = 1), 2 (v = 1) or 3 (u = 0).", default=3),
        In("Segments", INTEGER, "S", "Number of rulings of the connecting surface minus one.", default=24,
           min=1, max=MAX_COUPLING_SEGMENTS),
    )
    outputs = (
        Out("CurveA", CURVE, "CA", "Connecting curve from the start of EdgeA to SurfaceB (cubic, 4 points)."),
        Out("CurveB", CURVE, "CB", "Connecting curve from the end of EdgeA to SurfaceB (cubic, 4 points)."),
        Out("Surface", SURFACE, "S", "The connecting developable between CurveA and CurveB."),
        Out("Rulings", LINE, "R", "Its rulings, from CurveA to CurveB.", access=LIST),
        Out("WarpAngles", NUMBER, "W", f"{WARP_HELP} Recomputed from the rulings and the curves' "
            "tangents.", access=LIST),
    )

    def solve(
        self, surface_a: Any, surface_b: Any, edge_a: Any, edge_b: Any, segments: Any
    ) -> tuple[Any, ...]:
        a, b = surface_input("SurfaceA", surface_a), surface_input("SurfaceB", surface_b)
        ea, eb = edge_input("EdgeA", edge_a), edge_input("EdgeB", edge_b)
        n = segments_input(segments, limit=MAX_COUPLING_SEGMENTS)
        with kernel_errors():  # a pair that cannot be coupled: a warning, and this pair's outputs are null
            coupling = couple(a, ea, b, eb)
        for name, edge, number in (("SurfaceA", coupling.edge_a, ea), ("SurfaceB", coupling.edge_b, eb)):
            if edge.warp > EDGE_WARP:
                self.warn(
                    f"Edge {number} of {name} is not a torsal ruling (its tangent planes at the two "
                    f"corners differ by {edge.warp:.3g} rad): the join is smooth only at its corners"
                )
        if coupling.capped:
            self.remark(
                f"{coupling.capped} of 4 handles were shortened: the patches' tangent planes are "
                "(nearly) parallel there"
            )
        result = solve_strip(coupling.curve_a, coupling.curve_b, n, WARP_TOLERANCE)
        if result.message:
            self.warn(f"Connecting surface: {result.message}")
        strip = curve_strip_outputs(
            coupling.curve_a, coupling.curve_b, result.s, result.t, result.starts, result.ends,
            WARP_TOLERANCE, result.valid, source="SurfaceA and SurfaceB",
        )
        strip.report(self)
        return coupling.curve_a, coupling.curve_b, strip.surface, strip.rulings, strip.warp
