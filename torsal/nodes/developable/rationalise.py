"""developable.Rationalise: a freeform design as developable strips within a tolerance."""

from __future__ import annotations

from typing import Any

import numpy as np

from torsal.engine.node import LIST, In, Node, NodeError, NodeWarning, Out
from torsal.engine.types import BOOLEAN, INTEGER, NUMBER, POINT, TEXT, VECTOR
from torsal.engine.values import Point
from torsal.nodes.common.checks import tolerance as tolerance_input
from torsal.nodes.common.convert import sentence
from torsal.nodes.common.geometry_checks import parametric_surface as surface_input
from torsal.nodes.common.strip_outputs import WARP_HELP, strip_outputs
from torsal.nodes.common.values import CURVE, LINE, SURFACE
from torsal.nodes.geometry.curve_base import Curve
from torsal.nodes.geometry.developable.freeform import rationalise_freeform
from torsal.nodes.geometry.developable.kinds import fan_kinds
from torsal.nodes.geometry.developable.measure import within_tolerance
from torsal.nodes.geometry.developable.trimmed import rationalise_trimmed
from torsal.nodes.geometry.local_frame import LocalFrame
from torsal.nodes.geometry.surface_base import uv_grid
from torsal.nodes.geometry.trimmed_surface import TrimmedSurface
from torsal.nodes.geometry.watch import watched
from torsal.nodes.limits import MAX_RATIONALISE_CALLS

#: Share of a strip's area in creased fans above which the node warns.
CREASED = 0.1

#: How the node says that strips ringing the design's bumps were tried and not kept.
RINGS_TRIED = "strips ringing the design's bumps along lines of curvature were tried first and not kept"

#: The most rulings (MaxStrips × (Segments + 1)) one solve may make.
RULING_BUDGET = 6_000

#: The most strips one solve may make.
STRIP_LIMIT = 256

#: The most station rulings a strip may have, minus one.
SEGMENT_LIMIT = 1000


def _positive(name: str, value: Any) -> float:
    if value is None:
        raise NodeWarning(f"{name} is empty: give the largest distance from the design, in model units")
    x = float(value)
    if not (np.isfinite(x) and x > 0.0):
        raise NodeWarning(f"{name} must be a positive distance in model units, not {x:g}")
    return x


def _count(value: Any) -> int:
    if value is None:
        raise NodeWarning("MaxStrips is empty: give the largest number of strips, such as 40")
    n = int(value)
    if not 1 <= n <= STRIP_LIMIT:
        raise NodeWarning(f"MaxStrips is {n}: give a whole number from 1 to {STRIP_LIMIT}")
    return n


def _width(value: Any) -> float:
    if value is None:
        return 0.0
    x = float(value)
    if not (np.isfinite(x) and x >= 0.0):
        raise NodeWarning(f"MinWidth must be a width of 0 or more in model units, not {x:g}")
    return x


def _size(design: Any) -> float:
    """The design's extent (its diagonal), from a grid of its points."""
    u, v = uv_grid(17, 17)
    return float(np.linalg.norm(np.ptp(design.point_at(u, v), axis=0)))


def _direction(value: Any) -> np.ndarray | None:
    if value is None:
        return None
    d = np.asarray(value, dtype=float).ravel()
    if d.shape != (3,) or not np.isfinite(d).all() or not np.linalg.norm(d) > 0.0:
        raise NodeWarning("Direction must be a non-zero vector along which the strips should run")
    return d


class Rationalise(Node):
    """Cover a freeform design with developable strips, each within Tolerance of it.

    The strips run side by side across the design. Each is a developable sheet between
    two boundary curves running over the design, with straight torsal rulings from one to
    the other (flat triangles only where no torsal ruling exists), so it bends from a
    flat sheet without stretching. Neighbouring strips share their boundary curve
    exactly, so they meet without gaps or steps; how much they kink there is the
    Creases output (the fold angle along each inner boundary).

    Method. The rulings run where the design bends least and the boundaries across them:
    the boundaries are the design's parameter lines of the family the node picks from the
    surface's normal curvature (the square law: a strip w wide whose rulings bend with
    curvature k sags by about k·w²/8 under the design). Each boundary is lifted off the
    design by up to 0.8 × Tolerance against that sag, so a strip deviates to both sides
    of the design and may be about √1.8 as wide: about three quarters as many strips as
    with boundaries on the design (the issue's isocurve baseline).
    The rulings of a strip run in the direction conjugate to its boundaries (along lines
    of curvature, across them; at an angle where the boundaries cross the lines of
    curvature, as on a saddle turned to its outline). Where they cross the boundaries
    obliquely, the rulings near the design's edge leave it on one boundary before the
    other: such a strip is run on past the edge (the design continued by its Taylor
    expansion) and cut by it, as the D-strip models of Pottmann et al. 2008 cut their
    strips by the outline — so its ends are torsal and follow the design's edge, instead
    of a cone that bends away from the design over a fifth of a saddle's area. A cut end
    deviates more than the cone it replaces (its rulings run on to the edge): where the
    rulings cross the boundaries at a small angle (a monkey saddle near its edges) strips
    as wide as their cones allow cannot be cut within the tolerance, so when more than 5 %
    of the strips' area would stay in cones the node marches them again with every trial
    strip cut at the edge — narrower strips, smooth to the edge (a 14 m monkey saddle at
    2 cm: 22 strips with 2 % of their area in fans, instead of 20 with 16 %). Where a
    boundary runs along an asymptotic direction of the design (the inflection of a wave)
    no torsal ruling joins it to its neighbour and the strip is closed with creasing
    triangles; the node then also tries the other family and keeps the one that creases
    less (then the one with fewer strips). It tries first the family whose lines cross
    the design's asymptotic directions (where the normal curvature along them changes
    sign while the surface twists) much less than the other's — on a monkey saddle the
    lines along its straight asymptotic line, not across it — and where only the other
    family crosses them, it does not try that one. Where both families cross them (a
    double bump with a valley between: every line from edge to edge crosses the bumps'
    inflection), the node first rings each bump with strips between traced lines of
    curvature, which no strip creases along (the D-strips of Pottmann et al. 2008): each
    bump's part of the design (the points nearer its top than any other's) is split in two
    halves and a cap round its top; the halves are marched with rings of curvature as
    boundaries and their strips cut where the halves meet (overlapping by twice the
    tolerance there), the cap with parameter lines. It keeps them when they are within the
    tolerance, cover the design's edge and keep at most 10 % of their area in fans, and
    falls back to parameter lines otherwise (the remark, or the warning when the
    parameter lines fall short too, says why the rings were not kept and where: the last
    Where point). Kept, the family reads "rings", and Boundaries
    and Creases go part by part, in the order of the strips: each cap's as a trimmed
    design reports them (below), then each half's rings (each cut to the half; the first,
    inside the cap, to the design), a half of n strips between its n + 1 rings (a strip
    the half's edge cuts in two becomes two between the same rings) with one crease per
    inner ring — the largest angle between the normals of the strips on either side, at
    points along it. Where two parts meet their strips overlap instead of sharing a
    boundary, so no crease is reported there. Elsewhere the boundaries are parameter lines:
    where they are far from the design's curvature lines and the strips crease, give
    Guides (or a Direction) along the lines of curvature.

    With Direction, the boundaries are the parameter lines running most nearly along it,
    on the design (not lifted).
    With Guides, the strips follow your curves instead: one boundary runs along each guide
    (projected onto the design) and the boundaries between two guides, or a guide and the
    design's edge, blend from one to the other, as Tween Curves do; they lie on the design.
    Guides must cross the design from edge to edge and stay apart.

    The tolerance is a guarantee. Starting from one edge (and from every guide), each
    strip is made as wide as the tolerance allows. A strip's Deviation is certified: its
    distance from the design is sampled and the grid refined where needed until the bound
    between samples (Taylor's remainder from the samples' second differences) is within
    1 % of the tolerance of the samples; it includes how far the design's edge at the
    strip's two ends is from it, so the strips cover the design to its edges.

    Kind tells each ruling what it is, recomputed from the strip's own rulings and edges
    (their one-sided tangents at the ruling): "torsal" (the solve's torsal rulings), "fan"
    where the strip is closed by flat triangles or cones through one point and the sheet's
    plane goes on across the ruling within WarpTolerance (the two triangles beside it lie
    in one plane, or it is inside a cone: several rulings through one point of a boundary
    are a smooth cone, not a fold), and "crease" where the triangles on its two sides are
    in different planes (a triangle through a point of one boundary beside one through a
    point of the other): the sheet folds there, by the angle given as its WarpAngles, and it
    is never Valid. A fan ruling is Valid when the sheet keeps one plane along it too. The
    remark counts the creases and gives the largest fold (docs/geometry.md, "Rationalise:
    fans and creases").

    Honest limits. When more than MaxStrips would be needed, or where the tolerance asks
    for strips narrower than MinWidth (a sharp bump), the node makes MaxStrips evenly
    spaced strips (or MinWidth-wide ones there) and gives one warning: where (the Where
    points), how far off, and what would help. An already developable design, such as a
    cylinder patch, comes back as one strip or a few. A closed design (a tube or a ring)
    is refused: cut it first. Mesh surfaces have no parameter lines and are refused.

    A trimmed design (a Rhino brep face read by Import3dm) is rationalised inside its trim:
    the strips are made over the box of the trim loops and each is cut to the trim along
    its own developable sheet, so it stays developable and ends on the trim (within the
    tolerance; its corners and ends become extra rulings). Deviation is certified on the
    kept part only, and the coverage is measured along the trim loops, not the untrimmed
    surface's edges. Boundaries then are the uncut boundary curves across the trim's box
    (a strip cut in two by a notch or a hole becomes two strips between the same two).
    """

    type_id = "developable.Rationalise"
    max_calls = MAX_RATIONALISE_CALLS  # a list of values multiplies the designs solved (limits.py)
    nickname, aliases = "Rat", ("rationalize", "developable strips", "panelise", "panelize")
    inputs = (
        In("Surface", SURFACE, "S", "The freeform design (a NURBS, loft or parametric surface)."),
        In("Tolerance", NUMBER, "T", "Largest distance of any strip from the design, model units.",
           default=0.02),
        In("MaxStrips", INTEGER, "M", "Largest number of strips to make.", default=40, min=1,
           max=STRIP_LIMIT),
        In("Direction", VECTOR, "D", "Optional: a vector the strips (their boundaries) should run "
           "along; without it the node chooses from the surface's curvature.", optional=True),
        In("Guides", CURVE, "G", "Optional: curves on the design, each from one edge to the opposite "
           "one, that the strips follow: a boundary runs along each guide and the boundaries between "
           "blend from one guide to the next (and to the design's edges). Direction is then unused.",
           access=LIST, optional=True),
        In("Segments", INTEGER, "N", "Station rulings per strip minus one.", default=24, min=1,
           max=SEGMENT_LIMIT),
        In("WarpTolerance", NUMBER, "W", "Largest warp angle (rad) a ruling may keep and count as valid "
           "(torsal rulings are solved to ~1e-14 rad).", default=1e-7),
        In("MinWidth", NUMBER, "MW", "Narrowest strip to make (its width across, between its two edges: "
           "the median distance from each edge to the other), model units: where the tolerance would need "
           "narrower strips they are made this wide and the node warns where and how far off they are; what "
           "is left at the end is merged into the strip before it or made this wide. 0.2 is 20 cm in metres "
           "(give 200 for a design in millimetres).",
           default=0.2),
    )
    outputs = (
        Out("Strips", SURFACE, "S", "The developable strips, in order across the design.", access=LIST),
        Out("Boundaries", CURVE, "B", "The boundary curves over the design (lifted off it by up to 0.8 × "
            "Tolerance; on it with Guides or Direction): strip i lies between boundaries i and i + 1, "
            "which it shares exactly with its neighbours. With rings round bumps: part by part (see the "
            "help), each part's n strips between its n + 1 boundaries.", access=LIST),
        Out("Rulings", LINE, "R", "Every strip's rulings, strip after strip.", access=LIST),
        Out("WarpAngles", NUMBER, "W", f"{WARP_HELP} Per ruling, as Rulings; recomputed from the "
            "rulings and the boundary curves' tangents. At a crease (Kind): the angle the sheet folds "
            "through across the ruling.", access=LIST),
        Out("Deviation", NUMBER, "E", "Largest distance of each strip from the design.", access=LIST),
        Out("Valid", BOOLEAN, "V", "Per ruling, as Rulings: a torsal ruling's recomputed warp is a number "
            "within WarpTolerance; a fan's sheet keeps one plane along and across it within WarpTolerance; "
            "a crease is never Valid.", access=LIST),
        Out("Kind", TEXT, "K", 'Per ruling, as Rulings: "torsal"; "fan" for a ruling of the flat triangles '
            "(or cones through one point) that close a strip where no torsal ruling exists, the sheet's "
            'plane going on across it within WarpTolerance; "crease" for such a ruling across which the '
            "sheet folds by more (its fold angle is its WarpAngles).", access=LIST),
        Out("Creases", NUMBER, "C", "Per inner boundary (boundary i + 1, between strips i and i + 1): the "
            "largest fold angle (rad) between the two strips along it — how much the sheets kink there. "
            "With rings round bumps: part by part, as Boundaries, one per inner boundary of each part.",
            access=LIST),
        Out("Where", POINT, "P", "Where the tolerance is not met: each strip's farthest point when it is "
            "beyond Tolerance, and the design's edge point farthest from every strip when that is beyond it; "
            "last, when the warning says so, where the strips ringing the design's bumps (tried first) fell "
            "short (empty when all is within).", access=LIST),
    )

    def solve(
        self, surface: Any, tolerance: Any, max_strips: Any, direction: Any, guides: list[Any],
        segments: Any, warp_tolerance: Any, min_width: Any = 0.2,
    ) -> tuple[
        list[Any], list[Any], list[Any], list[float], list[float], list[bool], list[str], list[float],
        list[Any],
    ]:
        design = surface_input("Surface", surface)
        tol = _positive("Tolerance", tolerance)
        count = _count(max_strips)
        guide = _direction(direction)
        n = int(segments) if segments is not None else 24
        if not 1 <= n <= SEGMENT_LIMIT:
            raise NodeWarning(f"Segments is {n}: give a whole number from 1 to {SEGMENT_LIMIT}")
        warp_limit = tolerance_input("WarpTolerance", warp_tolerance)
        narrowest = _width(min_width)
        if count * (n + 1) > RULING_BUDGET:
            raise NodeError(f"MaxStrips {count} × (Segments {n} + 1) rulings is more than {RULING_BUDGET:,} "
                            "at once: lower MaxStrips or Segments")
        for i, g in enumerate(guides or []):  # numbered as in the list, empty items counted
            if g is not None and not isinstance(g, Curve):
                raise NodeWarning(f"Guides item {i + 1} is a {type(g).__name__}, not a curve")
        curves = [g for g in (guides or []) if g is not None]
        if curves and guide is not None:
            self.remark("Direction is not used: the strips follow the Guides")
        # solved in a frame at the design (at site coordinates its rulings, boundaries and
        # deviations then round as at the origin); the strips are moved back at the end
        frame = LocalFrame.around(design)
        size = _size(design)
        if tol >= size:
            raise NodeWarning(f"Tolerance {tol:g} is larger than the design itself ({size:.4g} across): give "
                              "the largest distance a strip may keep from the design, a small part of it")
        try:
            with watched(self.check_cancelled, self.progress):
                local = frame.to_local(design)
                solve = rationalise_trimmed if isinstance(local, TrimmedSurface) else rationalise_freeform
                result = solve(local, tol, count, None if curves else guide, segments=n,
                               warp_tolerance=warp_limit, progress=self.progress,
                               guides=[frame.to_local(g) for g in curves], min_width=narrowest)
        except ValueError as exc:
            about = "Guides" if curves and "guide" in str(exc) else "Surface"
            raise NodeWarning(f"{about}: {sentence(exc)}") from None
        rulings: list[Any] = []
        warp: list[float] = []
        valid: list[bool] = []
        kinds: list[str] = []
        fans = creased = 0
        worst_fold = 0.0
        for strip in result.strips:
            starts, ends = (frame.points_to_world(p) for p in (strip.result.starts, strip.result.ends))
            sheet = strip.surface
            judged = fan_kinds(sheet.curve_a, sheet.curve_b, sheet.ruling_parameters, strip.result.starts,
                               strip.result.ends, strip.result.fan, warp_limit, (starts, ends))
            w = np.where(judged.crease, judged.fold, strip.warp)  # (a crease's: its fold)
            lines = strip_outputs(starts, ends, warp=w)
            rulings.extend(lines.rulings)
            warp.extend(w.tolist())
            ok = np.where(strip.result.fan, judged.flat, within_tolerance(w, warp_limit, starts, ends))
            valid.extend(ok.tolist())
            fans += int(np.count_nonzero(strip.result.fan & ~judged.crease))
            creased += int(np.count_nonzero(judged.crease))
            worst_fold = float(np.fmax.reduce(judged.fold[judged.crease], initial=worst_fold))
            kinds.extend(judged.kind)
        deviation = [s.deviation for s in result.strips]
        worst = max(deviation)
        creases = [float(c) for c in result.creases]
        text = (f"{len(result.strips)} strips, deviation at most {worst:.4g} (certified; tolerance {tol:g}); "
                f"boundaries along {result.family}")
        if fans:
            text += f"; {fans} rulings in flat fans"
        if creased:
            text += (f"; {creased} rulings of flat triangles are creases (Kind \"crease\", not Valid): the "
                     f"sheet folds across them by up to {worst_fold:.3g} rad")
        if np.isfinite(creases).any():
            text += f"; creases up to {np.nanmax(creases):.3g} rad"
        where = self._limits(result, frame, tol, count, narrowest, text)
        if where is None:
            if result.rings_refused:  # and the parameter lines are good: said, no warning
                text += f"; {RINGS_TRIED}: {result.rings_refused}"
            self.remark(text)
            where = []
        # the remark counts the fans and the creases (never Valid); a torsal ruling that fails
        # is a warning
        torsal = np.asarray(kinds) == "torsal"
        bad = int(np.count_nonzero(~np.asarray(valid) & torsal))
        if bad:
            self.warn(f"{bad} of {int(torsal.sum())} torsal rulings have a recomputed warp that is undefined "
                      f"or above {warp_limit:g} rad (Valid = false)")
        strips = [frame.to_world(s.surface) for s in result.strips]
        boundaries = [frame.to_world(b) for b in result.boundaries]
        return strips, boundaries, rulings, warp, deviation, valid, kinds, creases, where

    def _limits(self, result: Any, frame: LocalFrame, tol: float, count: int, narrowest: float,
                text: str) -> list[Any] | None:
        """One warning when the strips are not all within the tolerance or leave part of the
        design's edge uncovered, or when most of a strip creases (where, how far, what would
        help), with the points it speaks of; None when there is nothing to warn about."""
        far = [i for i, s in enumerate(result.strips) if s.deviation > tol]
        points = [frame.points_to_world(result.strips[i].where[None])[0] for i in far]
        problems, help_ = [], []
        if far:
            worst = max(result.strips[i].deviation for i in far)
            shown = ", ".join(str(i + 1) for i in far[:8]) + (" …" if len(far) > 8 else "")
            problems.append(f"strips {shown} are up to {worst:.4g} from the design (Where)")
            if result.narrow:
                help_.append(f"the tolerance needs strips narrower than MinWidth {narrowest:g} there: lower "
                             "MinWidth, raise the tolerance or smooth that region")
            if not result.narrow or len(far) > len(result.narrow):
                help_.append(f"raise MaxStrips (now {count}) or the tolerance")
        if not result.covered:
            gap = int(np.argmax(result.edge_gaps))
            points.append(frame.points_to_world(result.edge_points[gap][None])[0])
            problems.append(f"the design's edge is {result.coverage:.4g} from the nearest strip (Where)")
            help_.append("more strips (a lower tolerance) narrow the gaps at the strips' ends")
        creased = [i + 1 for i, strip in enumerate(result.strips) if strip.result.creased_share > CREASED]
        if creased:
            shown = ", ".join(map(str, creased[:8])) + (" …" if len(creased) > 8 else "")
            problems.append(f"{len(creased)} of {len(result.strips)} strips are mostly flat triangles that "
                            f"crease the sheet (strips {shown}): no smooth torsal strip joins their"
                            " boundaries there")
            help_.append("a Direction or Guides along the design's lines of curvature")
        if not problems:
            return None
        if result.rings_refused:  # the better layout was tried: why it was not kept, and where
            shown = ""
            if result.rings_where is not None:
                points.append(frame.points_to_world(result.rings_where[None])[0])
                shown = " (the last Where point)"
            problems.append(f"{RINGS_TRIED}: {result.rings_refused}{shown}")
            help_.append("a larger Tolerance, at which the strips round the bumps may meet it")
        head = (f"Tolerance {tol:g} is not met everywhere" if far or not result.covered
                else "The strips are within the tolerance, but")
        self.warn(f"{head}: {'; '.join(problems)}. What would help: {'; '.join(help_)}. ({text})")
        return [Point(*map(float, p)) for p in points]
