"""developable.SplineApproximation: a double-curved ruled surface turned towards a
developable by rotating its rulings about one fixed edge."""

from __future__ import annotations

from dataclasses import replace
from typing import Any

import numpy as np

from torsal.engine.node import LIST, In, Node, NodeError, NodeWarning, Out
from torsal.engine.types import BOOLEAN, INTEGER, NUMBER, VECTOR
from torsal.nodes.common.checks import segments as segments_input
from torsal.nodes.common.convert import sentence, vectors
from torsal.nodes.common.geometry_checks import curve as curve_input
from torsal.nodes.common.geometry_checks import parametric_surface as surface_input
from torsal.nodes.common.strip_outputs import WARP_HELP, strip_outputs
from torsal.nodes.common.values import CURVE, LINE, SURFACE
from torsal.nodes.geometry.approximation import MAX_OPTIMISED, Approximation, approximate, station_rulings
from torsal.nodes.geometry.local_frame import LocalFrame
from torsal.nodes.limits import MAX_SPLINE_SEGMENTS, MAX_STRIP_SOLVES

#: Above this largest warp (rad) after optimising, the node says the strip is still warped.
STILL_WARPED = 0.01


def _angles(values: list[Any], rulings: int, fix_ends: bool) -> np.ndarray | None:
    """One angle per ruling from the Angles list: all of them, a single one for every
    ruling, or (with FixEnds) the inner ones only; None when the list is empty."""
    given = [v for v in values if v is not None]
    if not given:
        return None
    a = np.asarray([float(v) for v in given])
    if not np.all(np.isfinite(a)):
        raise NodeWarning("Angles contains a value that is not a finite number")
    if len(a) == rulings:
        return a
    if len(a) == 1:
        return np.full(rulings, a[0])
    if fix_ends and len(a) == rulings - 2:
        return np.concatenate([[0.0], a, [0.0]])
    inner = f", or {rulings - 2} for the inner rulings with FixEnds on" if rulings > 2 else ""
    raise NodeWarning(
        f"Angles has {len(a)} values: give one per ruling (Segments + 1 = {rulings}){inner}, "
        "or a single angle for all"
    )


class SplineApproximation(Node):
    """Approximate a double-curved ruled surface by a developable one that keeps one of
    its curved edges: each ruling is turned about that edge's tangent until the sheet no
    longer twists along it.

    The rulings start at Segments + 1 points spaced evenly along Curve (one of the
    Surface's two curved edges, or a piece of one). Each starts as the Surface's own
    straight ruling there and is rotated by its angle about the Curve's tangent
    (right-hand rule: thumb along the Curve's direction, positive turns
    anticlockwise seen from ahead); rulings keep their length. The result is the loft
    of the rotated rulings; its free edge is the spline through their new ends.
    NormalsA/NormalsB are the sheet's normals at the two ends of each ruling (ruling ×
    edge tangent); their angle is the ruling's warp — 0 to π, the turn of the tangent
    plane along the ruling (on the hyperbolic paraboloid z = xy between y = −L and L it
    is 2·atan(L)) — and Fitness is the sum of the warp angles. Where a normal has no
    direction (a ruling along an edge's tangent) the warp is NaN and the node warns.

    Manual mode (Optimise off): the rulings are turned by Angles, as in the thesis,
    where Galapagos drives the Angles sliders to minimise Fitness. Optimise on: the
    angles of least warp are found here, in milliseconds, starting from Angles (or
    from 0, the input's rulings, which keeps the result close to the input) and
    returned in BestAngles. The optimiser minimises the sum of *squared* warps, so
    any warp it cannot remove is spread thinly rather than piled onto a few rulings.
    FixEnds keeps the first and last rulings at their starting angles (the input's
    straight edges); as the thesis found, fixing both ends generally leaves the strip
    warped — fix none, or rotate only one end by hand.

    As in the thesis, the loft between the rulings is only close to developable: to
    finish, feed the fixed Curve and FreeEdge to RulingDevelopable.
    """

    type_id = "developable.SplineApproximation"
    max_calls = MAX_STRIP_SOLVES  # a list of values multiplies the strips solved (limits.py)
    nickname, aliases = "SpApx", ("approximate", "developable approximation")
    inputs = (
        In("Surface", SURFACE, "S", "The double-curved ruled surface to approximate."),
        In("Curve", CURVE, "C", "The curved edge of Surface that stays where it is (open)."),
        In("Angles", NUMBER, "A",
           "Rotation of each ruling about the edge tangent, rad: one per ruling (Segments + 1), "
           "a single value for all, or with FixEnds the inner ones. Empty: all 0. When "
           "optimising, the starting angles.", access=LIST, optional=True),
        In("Segments", INTEGER, "N", "Number of rulings minus one (1 or more).", default=20,
           min=1, max=MAX_SPLINE_SEGMENTS),
        In("Optimise", BOOLEAN, "O", "Find the angles of least summed warp (returned in BestAngles).",
           default=False),
        In("FixEnds", BOOLEAN, "F", "Keep the first and last rulings at their starting angles.",
           default=False),
    )
    outputs = (
        Out("Surface", SURFACE, "S", "The loft of the rotated rulings."),
        Out("Rulings", LINE, "R", "The rotated rulings, from Curve to the free edge.", access=LIST),
        Out("NormalsA", VECTOR, "NA", "Unit normal of the sheet at each ruling's start (on Curve).",
            access=LIST, preview=False),
        Out("NormalsB", VECTOR, "NB", "Unit normal of the sheet at each ruling's free end.", access=LIST,
            preview=False),
        Out("Tangents", VECTOR, "T", "Unit tangent of Curve at each ruling: the rotation axes.",
            access=LIST, preview=False),
        Out("Fitness", NUMBER, "F", "Sum of the warp angles, rad (0 = developable at every ruling; "
            "NaN if a warp is undefined)."),
        Out("WarpAngles", NUMBER, "W", f"{WARP_HELP} The angle between NormalsA and NormalsB.",
            access=LIST),
        Out("BestAngles", NUMBER, "BA",
            "The angles used, rad: the optimised ones with Optimise on, else Angles.", access=LIST),
        Out("FreeEdge", CURVE, "E", "The new free edge: the spline through the rulings' ends."),
    )

    def solve(
        self, surface: Any, curve: Any, angles: list[Any], segments: Any, optimise: Any, fix_ends: Any
    ) -> tuple[Any, ...]:
        s = surface_input("Surface", surface)
        c = curve_input("Curve", curve)
        n = segments_input(segments, limit=MAX_SPLINE_SEGMENTS)  # the fit is dense: (n + 1)² numbers
        optimise, fix_ends = bool(optimise), bool(fix_ends)
        if optimise and n + 1 > MAX_OPTIMISED:
            raise NodeError(f"Segments is {n}: optimising takes at most {MAX_OPTIMISED - 1} segments")
        # solved in a frame at the surface (site coordinates round there as at the origin);
        # only the rulings' ends are moved back
        frame = LocalFrame.around(s)
        try:
            stations = station_rulings(frame.to_local(s), frame.to_local(c), n)
        except ValueError as exc:
            raise NodeWarning(sentence(exc)) from None
        start = _angles(angles or [], n + 1, fix_ends)
        result = approximate(
            stations, start, optimise, fix_ends, check=self.check_cancelled, progress=self.progress
        )
        if not frame.is_world:
            result = replace(result, starts=frame.points_to_world(result.starts),
                             ends=frame.points_to_world(result.ends))
        if optimise:
            self._report(result, fix_ends)
        strip = strip_outputs(result.starts, result.ends, warp=result.warp)
        strip.report(self)
        return (
            strip.surface,
            strip.rulings,
            vectors(result.normals_a),
            vectors(result.normals_b),
            vectors(result.tangents_a),
            result.fitness,
            result.warp.tolist(),
            result.angles.tolist(),
            strip.surface.curve_b,
        )

    def _report(self, result: Approximation, fix_ends: bool) -> None:
        before, after = result.initial_fitness, result.fitness
        factor = ""
        if after > 0 and before > after:
            ratio = before / after
            factor = f" ({ratio:,.0f}× less)" if ratio >= 100 else f" ({ratio:.3g}× less)"
        self.remark(f"Summed warp {before:.3g} → {after:.3g} rad{factor} in {result.evaluations} evaluations")
        worst = int(np.argmax(result.warp))
        if result.warp[worst] > STILL_WARPED:
            advice = (
                "with both end rulings fixed the strip cannot become developable: turn FixEnds off"
                if fix_ends
                else "try more Segments, or approximate from the other curved edge"
            )
            self.warn(
                f"Still warped after optimising: {result.warp[worst]:.3g} rad at ruling {worst}; {advice}"
            )
