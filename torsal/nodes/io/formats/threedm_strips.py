"""Developable strips as Rhino geometry that follows their own rulings, in few control points.

A strip made of rulings (a :class:`~torsal.nodes.geometry.ruled.RuledSurface` with
``ruling_lines``, as Rationalise and the strip nodes make) goes to a ``.3dm`` as faces:

- each run of torsal rulings (consecutive rulings that do not share an end) is one ruled
  NURBS face, degree 1 across: its two rails are the strip's own rails over that run,
  fitted *together* (one knot vector, parameter u of the strip) by least squares on
  scipy's B-spline basis: double knots at the rulings (the rails' pace is piecewise
  cubic between them, C1 at them), a knot where a rail crosses a knot of the design it
  runs on (or another break of its curve), a triple knot where the rails' speed jumps
  between rulings (a cut strip's edges at a ramp's end, where a cone's apex comes to rest
  on A as it sweeps B: :class:`~torsal.nodes.geometry.developable.cut_pace.Paced`, the
  fit's samples split there), then knots inserted where the fit is worst
  until both rails are within :data:`FIT` of the strip's size, and as few control points
  as that takes (not one per sample). The face's isocurve at each ruling's u is that
  ruling and its rails' tangents there are the strip's own, exactly
  (:mod:`.threedm_held`: the two control points at each double knot, the two at each
  end; the least squares fit the others given those), so the face's normals at the
  node's torsal rulings are the strip's; a rail that stands still next to a fan stands
  still in the face too, its second derivative there held as well (the face's normal at
  that corner). Where the strip's own pairing of the rails between rulings twists (more
  than :data:`DEVELOPABLE`), the face pairs the rails developably instead: both rails at
  an even pace along their curves between the rulings (:class:`~.threedm_rails.Paced`),
  each point of rail A with its developable partner on rail B
  (:mod:`torsal.nodes.geometry.torsal_pairing`, smoothed:
  :func:`~.threedm_rails.smooth_partners`), fitted within FIT, then its control points
  moved until its normals agree along its lines across (:mod:`.threedm_untwist`: the
  fit's tangents are not exact, and a fit 30 times closer would cost several times the
  control points), judged on samples in every span of its knots (between sparser ones a
  face waves where the fit clustered its knots). So the face follows the node's rulings
  and is developable between them. An interval where that face still twists (more than
  :data:`TWISTED`) is fitted as a face of its own, and if it still twists goes out as
  cones (below); so does one whose face would cost more than :data:`COSTLIER` times the
  control points of its cones (the file stays within a fifth of the one-surface form);
- where no developable pairing joins two rulings (the torsal condition has no root between
  them, or a rail comes to rest at one of them, next to a fan: the partner would move like
  a square root) and the strip's own pairing twists there, the interval goes out as two
  cones meeting on its shorter diagonal (rail A to the diagonal's end on B, then that end
  of A to rail B): a cone is developable whatever its rail does, so its rail is fitted at
  an even pace along the rail's curve between the two rulings (from an end where that
  curve stands still, at a square root's pace: :mod:`.threedm_unstall`); where one of the two
  rulings is a point and a rail runs from it straight (within FIT), one cone from that
  rail's other end over the other rail instead, a face of its own (:func:`_tip_cone`);
- consecutive ruled faces and cone pairs are one face: their rails' splines end to end,
  joined at the ruling they share by a triple knot (each keeps its shape; fewer faces, a
  smaller file). Where a rail turns a corner (a strip cut to a trim) the faces meet there;
- each fan (consecutive rulings, each sharing an end with the next) is one face of degree
  1 both ways through its rulings, whose every span is one flat triangle (a lone triangle,
  or a fan whose triangles all meet at one point, is a trimmed plane through its corners);
- faces next to each other share their ruling edge exactly (the same two points); a
  degenerate piece (a ruling or triangle of no length or area) is left out, never written
  as a zero-length curve.

The faces of one strip are separate single-face breps in one Rhino group named for the
strip (rhino3dm cannot join breps); their shared edges coincide, so Rhino's Join makes
them one polysurface.
"""

from __future__ import annotations

import warnings
from collections.abc import Callable
from dataclasses import dataclass, replace

import numpy as np
import rhino3dm as rh
from scipy.interpolate import BSpline
from scipy.sparse.linalg import MatrixRankWarning, spsolve

from torsal.nodes.geometry.curve_base import Curve
from torsal.nodes.geometry.curve_rail import CurveRail
from torsal.nodes.geometry.ruled import RuledSurface
from torsal.nodes.geometry.torsal_pairing import CONE, switches, torsal_partners
from torsal.nodes.io.formats.threedm_held import end_bends, pinned, slopes_at
from torsal.nodes.io.formats.threedm_native import rhino_net
from torsal.nodes.io.formats.threedm_rails import AtRest, Paced, Rails, between, smooth_partners
from torsal.nodes.io.formats.threedm_triangles import SAME_POINT, fan_run, fan_triangle
from torsal.nodes.io.formats.threedm_unstall import Unstalled, unstalled
from torsal.nodes.io.formats.threedm_untwist import untwisted

#: How close the fitted rails stay to the strip's own, relative to its size.
FIT = 1e-6

#: A face whose normals turn less than this along every ruling counts as developable (rad).
DEVELOPABLE = 1e-7

#: A face still twisting more than this (rad) after both pairings has its twisting
#: intervals fitted alone, and one that still twists alone made cones (the bar, read back
#: by Rhino, is 1e-6; the untwist aims at 0.8 of this).
TWISTED = 8e-7

#: An interval whose torsal face costs more than this times the control points of its
#: cones goes out as cones (:func:`_costly`).
COSTLIER = 4.5


#: Samples of the rails per ruling interval, to fit on (and twice as many to check).
SAMPLES = 12

#: Samples per span between a fitted face's knots that its untwist is judged on.
SPAN_SAMPLES = 8

#: The densest sampling tried (per ruling interval) before a fit settles for what it reached
#: (192 left the double bump's cone pairs beside its fans at 1.1e-6 of the size).
LARGEST_SAMPLING = 384

#: A rail whose tangent turns more than this (rad) at a ruling has a corner there.
CORNER = 1e-3



@dataclass(frozen=True)
class Piece:
    """One face of a strip: a rhino3dm brep, its kind and the rulings it spans."""

    brep: rh.Brep | None  #: None until the face is final (:func:`strip_pieces` builds it once)
    kind: str  #: "torsal" (a ruled face), "fan" (a planar triangle) or "cone" (one rail at rest)
    first: int  #: index of its first ruling in the strip
    last: int  #: index of its last ruling
    deviation: float  #: largest distance of the face's rails from the strip's (0 for a fan)
    controls: int  #: control points per rail (3 for a fan's corners)
    rails: BSpline | None = None  #: a ruled face's two rails, (x, y, z) side by side


def is_strip(value: object) -> bool:
    """Whether ``value`` is a strip made of rulings between two curves (exported face by face):
    a ruled surface whose rails run on given curves at the rulings' pace (Rationalise's and
    the strip nodes' strips). A ruled surface lofted through rulings has B-spline rails already
    and is written exactly as one surface."""
    return isinstance(value, RuledSurface) and value.ruling_lines is not None and \
        value.ruling_parameters is not None and len(value.ruling_lines) >= 2 and \
        isinstance(value.curve_a, CurveRail) and isinstance(value.curve_b, CurveRail)


def strip_pieces(strip: RuledSurface) -> list[Piece]:
    """The faces of ``strip`` in order along it (see the module)."""
    lines = np.asarray(strip.ruling_lines, dtype=float)
    u = np.asarray(strip.ruling_parameters, dtype=float)
    size = float(np.ptp(lines.reshape(-1, 3), axis=0).max()) or 1.0
    same = SAME_POINT * size
    shared = (np.abs(lines[1:, 0] - lines[:-1, 0]).max(axis=1) <= same) | (
        np.abs(lines[1:, 1] - lines[:-1, 1]).max(axis=1) <= same)
    corner = _corners(strip, u)
    conical = _conical(strip, u, shared)
    # next to a ruling of no length (a strip cut to a point at the design's edge) both rails
    # run into one point: no pairing of them is developable there, a cone from it is
    tip = np.linalg.norm(lines[:, 1] - lines[:, 0], axis=1) <= same
    conical |= (tip[:-1] | tip[1:]) & ~shared
    pieces: list[Piece] = []
    k = 0
    n = len(lines)
    alone = np.zeros(n, dtype=bool)  # rulings a run of torsal rulings stops at (a twisting interval's)
    made_cones: dict[int, list[Piece]] = {}  # the cone pairs fitted so far, per interval
    while k < n - 1:
        if shared[k]:
            end = k + 1
            while end < n - 1 and shared[end]:
                end += 1
            run = fan_run(lines[k:end + 1]) if end - k > 1 else None
            if run is not None:  # one face of flat triangles, degree 1 both ways
                pieces.append(Piece(run, "fan", k, end, 0.0, end - k + 1))
                k = end
                continue
            triangle = fan_triangle(lines[k], lines[k + 1], size)
            if triangle is not None:
                pieces.append(Piece(triangle, "fan", k, k + 1, 0.0, 3))
            k += 1
            continue
        if conical[k]:  # no developable pairing: two cones meeting on a diagonal
            cone = _tip_cone(strip, u, lines, k, size, bool(tip[k])) if tip[k] != tip[k + 1] else None
            if cone is not None:  # one cone from the end of a rail straight to the fit
                pieces.append(cone)
                k += 1
                continue
            cones = made_cones[k] if k in made_cones else _cones(strip, u, lines, k, size)
            if tip[k] or tip[k + 1]:  # a face of its own: one of its lines is a point
                cones = [replace(piece, brep=_brep(piece.rails), rails=None) for piece in cones]
            pieces += cones
            k += 1
            continue
        end = k + 1
        while end < n - 1 and not shared[end] and not corner[end] and not conical[end] and not alone[end]:
            end += 1
        piece, twist, paired = _ruled(strip, u, lines, k, end, size)
        if twist > TWISTED:  # still twisted: its twisted intervals each a face of its own, and
            bad = _interval_twists(piece.rails, u[k:end + 1]) > TWISTED  # again; one that
            if not bad.any():  # twists alone goes out as cones
                own = [_own_twist(strip, u[i:i + 2], 17) for i in range(k, end)]
                bad[int(np.argmax(own))] = max(own) > TWISTED
            if bad.any():
                if end - k == 1:
                    conical[k] = True
                else:
                    alone[k + np.flatnonzero(bad)] = alone[k + 1 + np.flatnonzero(bad)] = True
                continue
        if paired:  # where a torsal face costs much more than cones would, cones
            costly = _costly(strip, u, lines, k, piece.rails, size, made_cones)
            if costly.any():
                conical[k + np.flatnonzero(costly)] = True
                continue
        pieces.append(piece)
        k = end
    return [replace(p, brep=_brep(p.rails)) if p.brep is None else p for p in _joined(pieces)]


def _costly(strip: RuledSurface, u: np.ndarray, lines: np.ndarray, first: int, rails: BSpline, size: float,
            made_cones: dict[int, list[Piece]]) -> np.ndarray:
    """Per interval of a face fitted to the developable pairing from ruling ``first``:
    whether its control points there (its knots inside the interval, and the double knot at
    the ruling that begins it) are more than :data:`COSTLIER` times those of the interval's
    two cones (their knots but the four at either end; ``made_cones`` keeps the cones per
    interval). Those intervals go out as cones: the file stays small."""
    knots = np.asarray(rails.t)
    stations = u[first:first + int(np.searchsorted(u[first:], knots[-1]) + 1)]
    inner = knots[4:-4]
    own = np.histogram(inner[inner > stations[0]], bins=stations)[0].astype(float)
    own[0] += 2.0  # the first interval's share of the face's ends
    costs = np.full(len(stations) - 1, 3.0)
    # a cone pair has 7 control points at least (two cubics of 4 sharing one), so costs 3:
    # an interval cheaper than COSTLIER times that can cost no more than its cones
    for i in np.flatnonzero(own > 3.0 * COSTLIER):
        k = first + int(i)
        if k not in made_cones:
            made_cones[k] = _cones(strip, u, lines, k, size)
        costs[i] = made_cones[k][0].controls - 4
    return own > COSTLIER * np.maximum(costs, 1.0)


def _joined(pieces: list[Piece]) -> list[Piece]:
    """Consecutive ruled faces (torsal runs and cone pairs) as one face each: their rails'
    splines end to end, joined at the ruling they share (a triple knot, so each keeps its
    own shape): fewer faces, a smaller file."""
    out: list[Piece] = []
    for piece in pieces:
        before = out[-1] if out else None
        if before is None or before.rails is None or piece.rails is None or before.last != piece.first:
            out.append(piece)
            continue
        one, two = before.rails, piece.rails
        n1, n2 = len(one.t) - 4, len(two.t) - 4
        knots = np.concatenate([one.t[:-1], two.t[4:]])
        controls = np.concatenate([np.asarray(one.c)[:n1], np.asarray(two.c)[1:n2]])
        spline = BSpline(knots, controls, 3)
        worst = max(before.deviation, piece.deviation)
        out[-1] = Piece(None, "torsal", before.first, piece.last, worst, len(knots) - 4, spline)
    return out


def _conical(strip: RuledSurface, u: np.ndarray, shared: np.ndarray) -> np.ndarray:
    """Per interval between rulings: whether the strip's own pairing twists there (more than
    :data:`DEVELOPABLE`) and no developable pairing joins its two rulings (the torsal
    condition has no root for some point of rail A, or a rail is at rest at one of the two
    rulings: next to a fan). All intervals are judged in one evaluation of the strip and one
    partner search."""
    flags = np.zeros(len(u) - 1, dtype=bool)
    speeds = [np.linalg.norm(rail.derivatives(u, 1)[1], axis=1) for rail in (strip.curve_a, strip.curve_b)]
    resting = np.zeros(len(u), dtype=bool)
    for speed in speeds:
        resting |= speed <= 1e-6 * max(float(speed.max()), 1e-300)
    todo = np.flatnonzero(~shared)
    if not len(todo):
        return flags
    twisted = todo[_own_twists(strip, u[todo], u[todo + 1], 17) > DEVELOPABLE]
    at_rest = resting[twisted] | resting[twisted + 1]  # a partner moving like a square root:
    flags[twisted[at_rest]] = True  # no fit follows it
    check = twisted[~at_rest]
    if len(check):
        lo, hi = u[check], u[check + 1]
        at = _spaced(lo, hi, 9)[:, 1:-1]
        steps = np.repeat(1e-5 * (hi - lo), at.shape[1])  # each span's own, as alone
        kind = torsal_partners(strip.curve_a, strip.curve_b, u, at.ravel(), steps)[1]
        flags[check] = (kind.reshape(at.shape) == CONE).any(axis=1)
    return flags


def _spaced(lo: np.ndarray, hi: np.ndarray, count: int) -> np.ndarray:
    """``count`` evenly spaced parameters from each ``lo`` to its ``hi`` (rows), computed as
    ``np.linspace(lo, hi, count)`` computes them."""
    steps = (hi - lo) / (count - 1)
    out = np.arange(count)[None, :] * steps[:, None] + lo[:, None]
    out[:, -1] = hi
    return out


def _own_twists(strip: RuledSurface, lo: np.ndarray, hi: np.ndarray, count: int) -> np.ndarray:
    """:func:`_own_twist` of each interval ``lo`` … ``hi``, in one evaluation of the strip."""
    u = _spaced(lo, hi, count).ravel()
    near = np.cross(*strip.derivatives(u, np.full(len(u), 0.01))[1:3])
    far = np.cross(*strip.derivatives(u, np.full(len(u), 0.99))[1:3])
    angle = np.arctan2(np.linalg.norm(np.cross(near, far), axis=1),
                       np.einsum("ij,ij->i", near, far)).reshape(len(lo), count)
    worst = np.fmax.reduce(angle, axis=1)  # NaN (a line of no length) left out, as nanmax does
    return np.where(np.isfinite(worst), worst, np.inf)


def _cones(strip: RuledSurface, u: np.ndarray, lines: np.ndarray, k: int, size: float) -> list[Piece]:
    """The interval after ruling ``k`` as two cones meeting on its shorter diagonal, one
    face: rail A to the diagonal's end on B, then that end of A to rail B (or the other way
    round). A cone is developable whatever its rail does (every line through its apex), so
    the face's normals are constant along its lines; its edges still run on the rails."""
    span = u[k:k + 2]
    paced_a, paced_b = (unstalled(Paced(rail, span), span) for rail in (strip.curve_a, strip.curve_b))
    # where a cut strip's edges sweep round a fan in a sliver of the interval (a ramp of
    # its pace, where their speeds jump) a triple knot at each jump, at the strip's own u
    jumps = _pace_jumps(strip, span)
    if len(jumps):
        paced_a, paced_b = (Paced(rail, span) for rail in (strip.curve_a, strip.curve_b))
    return _cone_pair(strip, u, lines, k, size, paced_a, paced_b, jumps)


def _cone_pair(strip: RuledSurface, u: np.ndarray, lines: np.ndarray, k: int, size: float, paced_a: Curve,
               paced_b: Curve, jumps: np.ndarray | None = None) -> list[Piece]:
    """:func:`_cones` with its rails at the given paces."""
    (a_lo, b_lo), (a_hi, b_hi) = lines[k], lines[k + 1]
    span = u[k:k + 2]
    if np.linalg.norm(a_hi - b_lo) <= np.linalg.norm(a_lo - b_hi):
        middle = np.array([a_hi, b_lo])
        rails = [Rails(paced_a, AtRest(b_lo)), Rails(AtRest(a_hi), paced_b)]
    else:
        middle = np.array([a_lo, b_hi])
        rails = [Rails(AtRest(a_lo), paced_b), Rails(paced_a, AtRest(b_hi))]
    fits = [_fit(pair, span, np.array(ends), FIT * size, lambda at: at,
                 np.empty(0) if jumps is None else jumps)  # type: ignore[arg-type]
            for pair, ends in zip(rails, ([lines[k], middle], [middle, lines[k + 1]]), strict=True)]
    # each apex exactly (the least squares leave its control points a rounding apart)
    fits = [(d, t, _apex_exactly(c, int(isinstance(pair.curve_b, AtRest)), rest.point))
            for (d, t, c), pair in zip(fits, rails, strict=True)
            for rest in [pair.curve_b if isinstance(pair.curve_b, AtRest) else pair.curve_a]]
    # one face: the first cone on the first half of the span, the second on the other half,
    # joined at the diagonal (a triple knot: the face folds there)
    lo, hi = float(span[0]), float(span[1])
    half = 0.5 * (lo + hi)
    (_, first, one), (_, second, two) = fits
    knots = np.concatenate([lo + (first[:-1] - lo) * 0.5, half + (second[4:] - lo) * 0.5])
    controls = np.concatenate([np.asarray(one.c)[:len(first) - 4], np.asarray(two.c)[1:len(second) - 4]])
    spline = BSpline(knots, controls, 3)
    return [Piece(None, "cone", k, k + 1, max(fits[0][0], fits[1][0]), len(knots) - 4, spline)]


def _tip_cone(strip: RuledSurface, u: np.ndarray, lines: np.ndarray, k: int, size: float,
              first: bool) -> Piece | None:
    """The interval after ruling ``k`` where one of its rulings is a point P (ruling k when
    ``first``, else ruling k + 1: the strip cut to a point at the design's edge) as one
    cone, a face of its own, when one of its rails runs from P straight to its other end
    (within :data:`FIT` of the size, as along a straight edge of the design): the cone
    from that end (its apex, exactly) over the other rail, its line at P the straight
    rail's chord. Every line across it has a length and passes through the apex, so its
    normals agree along them. Two cones on the interval's diagonal made the one from P
    over the straight rail a sliver as wide as the rail's sag, its lines along the rail
    (Rhino, finding its tangents parallel there, turned its normals by up to π). None
    when both rails bend more than that."""
    span = u[k:k + 2]
    at = np.linspace(span[0], span[1], 4 * SAMPLES + 1)
    sags = []
    for rail in (strip.curve_a, strip.curve_b):
        points = rail.point_at(at)
        chord = points[-1] - points[0]
        length = float(np.linalg.norm(chord))
        if length <= SAME_POINT * size:
            return None
        offset = points - points[0]
        sags.append(float(np.linalg.norm(np.cross(offset, chord / length), axis=1).max()))
    straight = int(np.argmin(sags))
    if sags[straight] > FIT * size:
        return None
    apex = lines[k + 1 if first else k, straight]
    ends = lines[k:k + 2].copy()
    ends[:, straight] = apex
    moving = unstalled(Paced(strip.curve_b if straight == 0 else strip.curve_a, span), span)
    rails = Rails(AtRest(apex), moving) if straight == 0 else Rails(moving, AtRest(apex))
    deviation, knots, spline = _fit(rails, span, ends, FIT * size, lambda x: x, np.empty(0))  # type: ignore[arg-type]
    spline = _apex_exactly(spline, straight, apex)
    return Piece(_brep(spline), "cone", k, k + 1, max(deviation, sags[straight]), len(knots) - 4)


def _apex_exactly(spline: BSpline, side: int, apex: np.ndarray) -> BSpline:
    """A fitted cone's rails with the rail at rest (``side`` 0: A, 1: B) the apex exactly
    (the least squares leave its control points a rounding apart)."""
    controls = np.array(spline.c, dtype=float)
    controls[:, 3 * side:3 * side + 3] = apex
    return BSpline(spline.t, controls, 3)


def _brep(spline: BSpline) -> rh.Brep:
    """A fitted pair of rails (x, y, z side by side) as one ruled NURBS face, degree 3 along
    and 1 across (made once per final face: rhino3dm takes its control points one by one)."""
    knots = np.asarray(spline.t, dtype=float)
    count = len(knots) - 4
    knots = (knots - knots[3]) / (knots[count] - knots[3])  # on [0, 1], as the kernel's surfaces
    controls = np.asarray(spline.c)[:count]
    net = np.stack([controls[:, :3], controls[:, 3:]], axis=1)
    across = np.array([0.0, 0.0, 1.0, 1.0])
    return rh.Brep.CreateFromSurface(rhino_net(net, np.ones((count, 2)), knots, across, (3, 1), False))


def _corners(strip: RuledSurface, u: np.ndarray) -> np.ndarray:
    """Per ruling: whether a rail turns a corner there (its tangents just before and just
    after it differ by more than :data:`CORNER`), as a strip cut to a trim does where its
    edge leaves a boundary for the trim, or changes its speed there (by more than CORNER of
    it: a rail joined from pieces each run at its own pace, as the canopy's, whose double
    knot at the ruling cannot follow it): the faces on either side meet at that ruling."""
    corner = np.zeros(len(u), dtype=bool)
    if len(u) < 3:
        return corner
    step = 1e-7 * float(u[-1] - u[0])
    inner = u[1:-1]
    for rail in (strip.curve_a, strip.curve_b):
        before = rail.derivatives(inner - step, 1)[1]
        after = rail.derivatives(inner + step, 1)[1]
        with np.errstate(invalid="ignore"):
            angle = np.arctan2(np.linalg.norm(np.cross(before, after), axis=1),
                               np.einsum("ij,ij->i", before, after))
        corner[1:-1] |= np.nan_to_num(angle) > CORNER
        speed = np.linalg.norm(before, axis=1), np.linalg.norm(after, axis=1)
        with np.errstate(invalid="ignore", divide="ignore"):
            jump = np.abs(speed[1] - speed[0]) / np.maximum(speed[0], speed[1])
        corner[1:-1] |= np.nan_to_num(jump) > CORNER
    return corner


def _ruled(strip: RuledSurface, u: np.ndarray, lines: np.ndarray, first: int, last: int,
           size: float) -> tuple[Piece, float, bool]:
    """The ruled face over rulings ``first`` … ``last``: between the rulings, each point of
    rail A paired with its developable partner on rail B (:mod:`~torsal.nodes.geometry.
    torsal_pairing`) where that fits within :data:`FIT`, else with the strip's own pairing;
    the rails fitted with inserted knots; how much it still twists (:func:`_twist`); and
    whether it is the developable pairing's."""
    span = u[first:last + 1]
    tolerance = FIT * size
    sampled = 0.0  # the untwisted face's largest twist on the untwist's samples
    jumps = _pace_jumps(strip, span)
    own = _fit(strip, span, lines[first:last + 1], tolerance, lambda at: at, jumps)
    fit = own
    paired_fit = False
    if _twist(own) > DEVELOPABLE and _own_twist(strip, span) <= DEVELOPABLE:
        # the strip's own pairing is developable (as a strip cut to a trim is) but its short
        # rulings magnify the fit's error into a twist: closer fits, as close as that takes
        for _ in range(3):
            tighter = _fit(strip, span, lines[first:last + 1], 0.1 * fit[0], lambda at: at, jumps)
            fit = tighter if _twist(tighter) < _twist(fit) else fit
            if _twist(fit) <= DEVELOPABLE:
                break
    elif _twist(own) > DEVELOPABLE:  # the strip twists between its rulings: pair them developably
        # both rails at an even pace along their curves between the rulings (a third fewer
        # control points than at the strip's own pace), B paired with A developably
        rails = Rails(Paced(strip.curve_a, span), Paced(strip.curve_b, span))
        kinks = switches(rails.curve_a, rails.curve_b, span)
        paired = smooth_partners(rails, span, kinks)
        developable = _fit(rails, span, lines[first:last + 1], tolerance, paired, kinks)  # type: ignore[arg-type]
        if developable[0] <= tolerance and _twist(developable) > DEVELOPABLE:
            # its tangents are not exact: its control points moved until it is developable
            # (:mod:`.threedm_untwist`), on samples of the pairing as dense as its knots, and
            # in every span of its knots (where the fit clustered them too: between sparser
            # samples it would wave)
            per = max(8 * SAMPLES, 16 * -(-(len(developable[1]) - 4) // max(len(span) - 1, 1)))
            at = np.unique(np.concatenate([between(np.unique(np.concatenate([span, kinks])), per),
                                           between(np.unique(developable[1]), SPAN_SAMPLES)]))
            data = np.hstack([rails.curve_a.point_at(at), rails.curve_b.point_at(paired(at))])
            bent = np.isfinite(end_bends(rails, span, paired, slopes_at(rails, span, paired))).all(axis=2)
            moved, distance, angle = untwisted(developable[2], at, data, tolerance, 0.8 * TWISTED,
                                               span[1:-1], bent)
            if distance <= tolerance:
                developable = (distance, np.asarray(moved.t), moved)
                sampled = angle  # on its own samples, denser than _twist's
        if developable[0] <= tolerance and _twist(developable) < _twist(own):
            fit, paired_fit = developable, True
    piece = Piece(None, "torsal", first, last, fit[0], len(fit[1]) - 4, fit[2])
    return piece, max(_twist(fit), sampled if paired_fit else 0.0), paired_fit


def _own_twist(strip: RuledSurface, span: np.ndarray, count: int = 257) -> float:
    """The largest angle between the strip's own normals 1 % in from either end of its lines
    across (isocurves) at ``count`` of them over ``span``."""
    u = np.linspace(span[0], span[-1], count)
    near = np.cross(*strip.derivatives(u, np.full(count, 0.01))[1:3])
    far = np.cross(*strip.derivatives(u, np.full(count, 0.99))[1:3])
    angle = np.arctan2(np.linalg.norm(np.cross(near, far), axis=1), np.einsum("ij,ij->i", near, far))
    return float(np.nanmax(angle)) if np.isfinite(angle).any() else float("inf")


def _interval_twists(spline: BSpline | None, span: np.ndarray, count: int = 129) -> np.ndarray:
    """Per interval of ``span``: the largest angle between a fitted face's normals 1 % in
    from either end of its lines across, at ``count`` of them in the interval."""
    if spline is None:
        return np.zeros(len(span) - 1)
    steps = np.linspace(0.0, 1.0, count)
    u = (span[:-1, None] + (span[1:] - span[:-1])[:, None] * steps).ravel()
    return _normal_angles(spline(u), spline.derivative()(u)).reshape(len(span) - 1, count).max(axis=1)


def _normal_angles(points: np.ndarray, slopes: np.ndarray) -> np.ndarray:
    """The angle between a ruled face's normals 1 % in from either end of its lines across,
    from its rails' points and slopes side by side (n, 6); 0 where undefined."""
    ruling = points[:, 3:] - points[:, :3]
    near = np.cross(0.99 * slopes[:, :3] + 0.01 * slopes[:, 3:], ruling)
    far = np.cross(0.01 * slopes[:, :3] + 0.99 * slopes[:, 3:], ruling)
    angle = np.arctan2(np.linalg.norm(np.cross(near, far), axis=1), np.einsum("ij,ij->i", near, far))
    return np.nan_to_num(angle)


def _twist(fit: tuple[float, np.ndarray, BSpline], count: int = 257) -> float:
    """The largest angle between a fitted face's normals 1 % in from either end of its
    rulings (isocurves across), at ``count`` of them."""
    _, knots, spline = fit
    if spline is None:
        return float("inf")
    lo, hi = knots[0], knots[-1]
    u = np.linspace(lo, hi, count)
    points, slopes = spline(u), spline.derivative()(u)
    ruling = points[:, 3:] - points[:, :3]
    near = np.cross(0.99 * slopes[:, :3] + 0.01 * slopes[:, 3:], ruling)
    far = np.cross(0.01 * slopes[:, :3] + 0.99 * slopes[:, 3:], ruling)
    angle = np.arctan2(np.linalg.norm(np.cross(near, far), axis=1), np.einsum("ij,ij->i", near, far))
    return float(np.nanmax(angle)) if np.isfinite(angle).any() else float("inf")


def _fit(strip: RuledSurface, span: np.ndarray, lines: np.ndarray, tolerance: float,
         partner: Callable[[np.ndarray], np.ndarray], kinks: np.ndarray) -> tuple[float, np.ndarray, BSpline]:
    """Both rails, rail B at ``partner`` of rail A's parameter, fitted on one knot vector
    (double knots at the rulings, triple at ``kinks``, one at each break of a rail, more
    inserted where the fit is worst until within ``tolerance``): (largest distance, knots,
    spline)."""
    # the rails' pace is piecewise cubic between rulings (C1 at them), the developable
    # pairing has kinks where it changes kind: knots there from the start, else the fit
    # converges slowly round them
    lo, hi = float(span[0]), float(span[-1])
    fixed = [*np.repeat(span[1:-1], 2).tolist(), *np.repeat(kinks, 3).tolist()]
    # the rails' own breaks between rulings (where a rail's pace crosses a breakpoint of its
    # curve: a knot of the design it runs on, a joint) are where the fit's error is: a knot
    # at each from the start (bisection converges on them only slowly)
    start = [float(b) for b in _rail_breaks(strip, span, partner) if b not in kinks]
    slopes = slopes_at(strip, span, partner)
    rulings = lines.reshape(-1, 6)
    # where a rail stands still at an end (next to a fan) the face's normal at that corner is
    # its edge's direction, the rail's second derivative, × the ruling: that held too (one
    # more control point, a knot in the end interval keeping it apart from the ruling's)
    bends = end_bends(strip, span, partner, slopes)  # (end, rail, xyz)
    still = np.isfinite(bends).all(axis=2)
    fixed += [0.5 * float(span[0] + span[1])] * bool(still[0].any()) + \
        [0.5 * float(span[-2] + span[-1])] * bool(still[1].any())
    per = SAMPLES
    best: tuple[float, np.ndarray, BSpline] = (np.inf, np.empty(0), None)  # type: ignore[assignment]
    interior = list(start)
    if still.any():  # a held bend takes a control point of its own beside an end's two and
        # the held rulings' (seven at least): a face over one interval gets the knots for it
        interior += np.linspace(lo, hi, max(3 - len(fixed) - len(interior), 0) + 2)[1:-1].tolist()

    def attempt(inner: list[float]) -> tuple[float, np.ndarray, BSpline, np.ndarray] | None:
        """The fit on knots ``fixed`` and ``inner``: (largest distance, knots, spline, the
        distances at the check's samples), None when the samples cannot carry it."""
        knots = np.concatenate([[lo] * 4, sorted(fixed + inner), [hi] * 4])
        n = len(knots) - 4
        if n < 4 or n > len(fine):
            return None
        # clamped: the end control points are the end rulings' ends, exactly (shared edges),
        # and the next ones give the rails' own end tangents (a rail that stands still there,
        # next to a fan, stands still in the face too: its normals stay the strip's); the
        # others fitted by least squares given those four
        controls = np.zeros((n, 6))
        controls[0], controls[n - 1] = data[0], data[-1]
        controls[1] = controls[0] + (knots[4] - lo) / 3.0 * slopes[0]
        controls[n - 2] = controls[n - 1] - (hi - knots[n - 1]) / 3.0 * slopes[-1]
        ends = np.array([2, n - 3])
        scale = ((knots[4] - lo) * (knots[5] - lo) / 6.0, (hi - knots[n - 1]) * (hi - knots[n - 2]) / 6.0)
        for end, rail in zip(*np.nonzero(still), strict=True):
            part = slice(3 * rail, 3 * rail + 3)
            controls[ends[end], part] = controls[(1, n - 2)[end], part] + scale[end] * bends[end, rail]
        # at a ruling inside the face (a double knot) the two control points there make the
        # ruling and the rails' own tangents, exactly: the face's normals there are the
        # strip's, torsal (a least-squares fit missed them by up to 5e-7 rad)
        held = pinned(knots, span[1:-1], rulings[1:-1], slopes[1:-1])
        if held is None or (still.any() and (n < 7 or np.isin(held[0], ends[still.any(axis=1)]).any())):
            return None
        columns, values = held
        controls[columns] = values
        basis = BSpline.design_matrix(fine, knots, 3).tocsc()
        for rails in ((0, 1),) if not still.any() else ((0,), (1,)):  # (rails that share the fixed)
            part = np.concatenate([np.arange(3 * rail, 3 * rail + 3) for rail in rails])
            kept = np.unique(np.concatenate([[0, 1, n - 2, n - 1], columns, ends[still[:, rails[0]]]]))
            others = np.setdiff1d(np.arange(n), kept)
            if not len(others):
                continue
            free = basis[:, others]
            rest = data[:, part] - basis[:, kept] @ controls[np.ix_(kept, part)]
            try:
                with warnings.catch_warnings():
                    warnings.simplefilter("error", MatrixRankWarning)
                    solved = spsolve((free.T @ free).tocsc(), free.T @ rest)
                controls[np.ix_(others, part)] = np.asarray(solved).reshape(len(others), len(part))
            except (MatrixRankWarning, RuntimeError):  # a span without samples
                return None
        spline = BSpline(knots, controls, 3)
        with np.errstate(over="ignore", invalid="ignore"):  # an ill-posed fit: judged by the caller
            fitted = spline(check)
            error = np.maximum(np.linalg.norm(fitted[:, :3] - truth[:, :3], axis=1),
                               np.linalg.norm(fitted[:, 3:] - truth[:, 3:], axis=1))
        return float(error.max()), knots, spline, error

    while True:
        # the fit's samples are every other one of the check's: rail B's partners found once
        # (sampled between the kinks too: every span between two knots has samples)
        check, truth = _samples(strip, np.unique(np.concatenate([span, kinks])), 2 * per, partner)
        fine, data = check[::2], truth[::2].copy()
        data[np.searchsorted(fine, span)] = lines.reshape(-1, 6)  # the node's rulings exactly
        breaks_fixed = np.unique(np.concatenate([span, kinks]))
        while True:
            result = attempt(interior)
            if result is None:
                break
            worst, knots, spline, error = result
            if not np.isfinite(worst) or worst > 1e3 * best[0]:  # ill-posed (a span without
                break  # enough samples): the previous fit stands
            if worst < best[0]:
                best = (worst, knots, spline)
            if worst <= tolerance or len(knots) - 4 >= len(fine) // 3:
                break
            breaks = np.unique(np.concatenate([breaks_fixed, interior]))
            where = np.searchsorted(breaks, check[error > tolerance]) - 1
            bad = np.unique(np.clip(where, 0, len(breaks) - 2))
            grown = sorted({*interior, *((breaks[bad] + breaks[bad + 1]) / 2).tolist()})
            if len(grown) == len(interior):  # nothing left to split: the samples are the limit
                break
            interior = grown
        if best[0] <= tolerance or per >= LARGEST_SAMPLING:
            return best
        per *= 2  # more knots are needed than these samples can carry


def _pace_jumps(strip: RuledSurface, span: np.ndarray) -> np.ndarray:
    """Where a rail's pace is only C0 strictly between the rulings of ``span`` (a cut strip's
    edges at a ramp's ends, :class:`~torsal.nodes.geometry.developable.cut_pace.Paced`): a
    triple knot each, the fit's samples split there."""
    found = [rail.crossings(np.asarray(rail.curve.jumps, dtype=float))
             for rail in (strip.curve_a, strip.curve_b)
             if isinstance(rail, CurveRail) and len(getattr(rail.curve, "jumps", ()))]
    marks = np.unique(np.concatenate(found)) if found else np.empty(0)
    near = 1e-6 * (span[-1] - span[0])  # (a ramp that starts at a ruling: at the ruling)
    return marks[(np.abs(marks[:, None] - span[None, :]).min(axis=1) > near) & (marks > span[0])
                 & (marks < span[-1])] if len(marks) else marks


def _rail_breaks(strip: RuledSurface, span: np.ndarray,
                 partner: Callable[[np.ndarray], np.ndarray]) -> np.ndarray:
    """The parameters (of rail A) strictly between the rulings of ``span`` where either
    rail has a break (:meth:`CurveRail._breakpoints`): rail A's own, and rail B's mapped
    back through ``partner`` (monotone: interpolated on a grid, then two secant steps)."""
    lo, hi = float(span[0]), float(span[-1])
    near = 1e-6 * (hi - lo)
    found = []
    for rail, own in ((strip.curve_a, True), (strip.curve_b, False)):
        if isinstance(rail, (Paced, Unstalled)):
            marks = rail.breaks()
        elif isinstance(rail, CurveRail):
            marks = rail._breakpoints()  # the rulings, and where it crosses its curve's breaks
        else:
            continue
        marks = marks[(marks > lo + near) & (marks < hi - near)]
        if not len(marks):
            continue
        if not own:
            grid = between(span, 16)
            paired = partner(grid)
            if not np.array_equal(paired, grid):
                marks = marks[(marks > paired[0]) & (marks < paired[-1])]
                at = np.interp(marks, paired, grid)
                for _ in range(2):
                    slope = np.interp(at, grid[1:], np.diff(paired) / np.diff(grid))
                    with np.errstate(divide="ignore", invalid="ignore"):
                        step = (partner(at) - marks) / slope
                    at = np.clip(at - np.where(np.isfinite(step), step, 0.0), lo, hi)
                marks = at
        found.append(marks)
    if not found:
        return np.empty(0)
    marks = np.unique(np.concatenate(found))
    # none next to a ruling (its double knot is there) or to another break
    gap = np.abs(span[np.clip(np.searchsorted(span, marks), 1, len(span) - 1)[:, None]
                      - np.array([[1, 0]])] - marks[:, None]).min(axis=1)
    marks = marks[gap > near]
    return marks[np.concatenate([[True], np.diff(marks) > near])] if len(marks) else marks


def _samples(strip: RuledSurface, span: np.ndarray, per: int,
             partner: Callable[[np.ndarray], np.ndarray], lines: np.ndarray | None = None
             ) -> tuple[np.ndarray, np.ndarray]:
    """Parameters ``per`` to a ruling interval, and both rails there side by side (n, 6),
    rail B at the partner parameters; with ``lines``, the rulings' own ends stand at their
    parameters (the node's lines exactly)."""
    at = between(span, per)
    data = np.hstack([strip.curve_a.point_at(at), strip.curve_b.point_at(partner(at))])
    if lines is not None:
        data[np.searchsorted(at, span)] = lines.reshape(-1, 6)
    return at, data
