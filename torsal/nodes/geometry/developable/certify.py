"""How far Rationalise's strips are from the design, certified rather than sampled once.

A strip's deviation is the largest distance of its points from the design. Sampling a
fixed grid (the first version took 41 × 7 points) under-reports it: the largest distance
lies between samples. Here the distance d(u, v) of the strip's point S(u, v) from the
design is sampled on a grid, and between grid points it is bounded by Taylor's theorem:
on a cell of steps (h_u, h_v) a smooth d exceeds the largest of its corners by at most
(|d_uu| h_u² + |d_vv| h_v²)/8, the second derivatives estimated by the grid's second
differences at the cell's corners. d is smooth between the strip's rulings but not across
them: a strip's rails change pace at every ruling, and where flat fans meet the strip folds
(its parameterisation stands still there, S_u = 0), so d may peak on a ruling with a slope
that turns within a hair of it. The rulings are therefore samples (with one sample between
each two), and a cell's curvature is estimated only from a corner whose second difference
lies on one smooth piece; a cell between two rulings with no such corner is split until it
has one. (Sampled on a uniform grid, a monkey saddle's strip of fans peaked on a ruling at
2.017 cm between samples and was certified at 1.999 cm.) The grid is refined — the
intervals along the strip whose bound may lie above the samples halved, the samples across
doubled — until every cell's bound is within 1 % of the tolerance of the samples' maximum,
so the reported deviation (samples' maximum plus remainder) and the samples agree to 1 % of
it. Refinement stops early as soon as a sample alone is beyond the tolerance (the strip is
then too wide, whatever lies between samples), and at :data:`MOST_SAMPLES`, where the bound,
still the samples' maximum plus the remainder, is larger than the samples by more than 1 %
of the tolerance (and says so). The bound rests on second differences standing for the
second derivatives within a cell, an estimate that refinement makes good, not a proof.

Creases: :func:`crease_angle` measures how much two neighbouring strips fold against each
other along the boundary they share (the kink angle of Eigensatz et al. 2010, what
reflections show).

Coverage: points along the design's edges are covered when some strip passes within
the tolerance of them; :func:`uncovered` gives each edge sample's distance to the
nearest strip.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from scipy.spatial import cKDTree

from ..array_types import FloatArray
from ..curve_base import Curve
from ..surface_base import Surface
from ..vectors import angle_between
from .ruling import RulingResult

#: First grid of samples along × across a strip (along: at least; with the rulings, see the module).
FIRST_SAMPLES = (41, 9)
#: The most samples of one strip (the refinement stops there).
MOST_SAMPLES = 400_000
#: The remainder between samples is refined down to this share of the tolerance.
AGREE = 0.01


@dataclass(frozen=True)
class Deviation:
    """A strip's certified deviation from the design."""

    bound: float  #: the samples' largest distance plus the Taylor remainder between them
    sampled: float  #: the largest distance at a sample
    where: FloatArray  #: (3,) the sample farthest from the design
    samples: tuple[int, int]  #: the final grid

    @property
    def agrees(self) -> bool:
        return self.bound - self.sampled <= AGREE * max(self.bound, 1e-300) or self.bound <= 0.0


def _cell_bounds(u: FloatArray, d: FloatArray, kinks: np.ndarray) -> tuple[FloatArray, np.ndarray]:
    """Per interval of ``u`` (rows of d, the columns uniform across the strip): the largest
    corner distance plus the Taylor remainders along (from non-uniform second differences
    at the interval's ends) and across (from second differences of its two rows); and
    whether the interval's remainder along is unresolved.

    ``kinks`` marks the rows at the strip's rulings, where its rails' pace (and a fan's
    fold) may turn d's slope: a second difference through a kink measures the turn, not a
    curvature, so it is used for an interval only from an end that is not a kink. An
    interval with both ends at kinks (no second difference of its own piece yet) is
    unresolved: its bound, from the differences through the kinks, is a guess until it is
    split."""
    h = np.diff(u)
    curve = np.zeros_like(d)
    left, right = h[:-1, None], h[1:, None]
    curve[1:-1] = 2.0 * (d[2:] / (right * (left + right)) - d[1:-1] / (left * right)
                         + d[:-2] / (left * (left + right)))
    curve[0], curve[-1] = curve[min(1, len(u) - 1)], curve[max(len(u) - 2, 0)]
    along = np.abs(curve).max(axis=1)
    own = ~kinks.copy()  # a row's second difference lies on one smooth piece of d
    own[[0, -1]] = False
    lower, upper = own[:-1], own[1:]
    unresolved = ~(lower | upper)
    both = np.maximum(along[:-1], along[1:])  # through a kink where unresolved: a guess
    along_cells = np.where(lower & upper | unresolved, both, np.where(lower, along[:-1], along[1:]))
    across = np.zeros(len(u))
    if d.shape[1] > 2:
        across = np.abs(d[:, 2:] - 2.0 * d[:, 1:-1] + d[:, :-2]).max(axis=1)
    rows = d.max(axis=1)
    bound = (np.maximum(rows[:-1], rows[1:]) + along_cells * h * h / 8.0
             + np.maximum(across[:-1], across[1:]) / 8.0)
    return bound, unresolved


def certified_deviation(design: Surface, strip: Surface, tolerance: float) -> Deviation:
    """The strip's deviation from the design (see the module), refined against ``tolerance``:
    the intervals along the strip whose bound may exceed the samples' maximum by more than
    :data:`AGREE` of the tolerance (or whose bound is not resolved yet) are halved, the
    samples across doubled while their remainder is what exceeds it."""
    nu, nv = FIRST_SAMPLES
    rulings = getattr(strip, "ruling_parameters", None)
    kinks = np.zeros(0)
    if rulings is not None:  # d's slope may turn at every ruling: they are samples too
        kinks = np.asarray(rulings, dtype=float)
        kinks = np.unique(np.clip(kinks[np.isfinite(kinks)], 0.0, 1.0))
    if len(kinks) >= 2:  # a sample on every ruling and one between (each piece resolved at once)
        u = np.union1d(np.union1d(kinks, 0.5 * (kinks[1:] + kinks[:-1])), [0.0, 1.0])
        u = u if len(u) >= nu else np.union1d(u, np.linspace(0.0, 1.0, nu))
    else:
        u = np.linspace(0.0, 1.0, nu)
    v = np.linspace(0.0, 1.0, nv)
    rows = _distances(design, strip, u, v)
    while True:
        worst = np.unravel_index(int(np.argmax(rows)), rows.shape)
        sampled = float(rows[worst])
        cells, unresolved = _cell_bounds(u, rows, np.isin(u, kinks))
        bound = max(float(cells.max()), sampled)
        slack = AGREE * tolerance
        if (sampled > tolerance or (bound - sampled <= slack and not unresolved.any())
                or rows.size > MOST_SAMPLES):
            where = strip.point_at(u[worst[0]], v[worst[1]])
            return Deviation(bound, sampled, np.asarray(where, dtype=float), rows.shape)
        across = (np.abs(rows[:, 2:] - 2.0 * rows[:, 1:-1] + rows[:, :-2]).max(initial=0.0) / 8.0
                  if len(v) > 2 else 0.0)
        if across > 0.5 * slack:  # the samples across are too coarse: double them everywhere
            v = np.linspace(0.0, 1.0, 2 * len(v) - 1)
            rows = _distances(design, strip, u, v)
            continue
        split = (cells > sampled + slack) | unresolved
        middles = 0.5 * (u[:-1] + u[1:])[split]
        new = _distances(design, strip, middles, v)
        u = np.concatenate([u, middles])
        order = np.argsort(u, kind="stable")
        u, rows = u[order], np.concatenate([rows, new])[order]


def _distances(design: Surface, strip: Surface, u: FloatArray, v: FloatArray) -> FloatArray:
    uu, vv = np.meshgrid(u, v, indexing="ij")
    points = strip.point_at(uu.ravel(), vv.ravel())
    # the strip lies within a few tolerances of the design: the nearest seeds suffice, and a
    # parameter step of 1e-10 moves the distance by far less than the 1 % certified
    return design.closest_point(points, candidates=2, tolerance=1e-10).distances.reshape(len(u), len(v))


def uncovered(
    design: Surface, strips: Sequence[Surface], samples: int = 200
) -> tuple[FloatArray, FloatArray]:
    """Points along the design's four edges and each one's distance to the nearest strip.

    A strip is a ruled surface: straight across, so a grid of its points :data:`ALONG` long
    and :data:`ACROSS` wide, cut into triangles, lies on it to the rails' chord error
    (under 1e-5 of a 10 m strip's curvature radius). Each edge point's distance to it is
    the exact distance to the triangles of the cells nearest it (trimesh's
    point–triangle distance), so a strip's uneven parameterisation (fans) cannot mislead
    a closest-point iteration."""
    t = np.linspace(0.0, 1.0, samples)
    zero, one = np.zeros_like(t), np.ones_like(t)
    u = np.concatenate([t, one, t, zero])
    v = np.concatenate([zero, t, one, t])
    points = design.point_at(u, v)
    nearest = np.full(len(points), np.inf)
    for strip in strips:
        nearest = np.minimum(nearest, _mesh_distance(strip, points))
    return points, nearest


def end_gaps(
    design: Surface, strip: Surface, a: Curve, b: Curve, samples: int = 25
) -> tuple[float, FloatArray]:
    """How far the design's edge between the two boundaries' ends is from the strip (its
    end closes that stretch with straight rulings, a chord of a curved edge): the largest
    distance of ``samples`` points along each of the two stretches, and the farthest point."""
    ends = np.array([a.point_at(0.0), b.point_at(0.0), a.point_at(1.0), b.point_at(1.0)])
    uv = design.closest_point(ends).parameters
    w = np.linspace(0.0, 1.0, samples)[:, None]
    stretch = np.concatenate([(1 - w) * uv[0] + w * uv[1], (1 - w) * uv[2] + w * uv[3]])
    points = design.point_at(stretch[:, 0], stretch[:, 1])
    gaps = _mesh_distance(strip, points)
    k = int(np.argmax(gaps))
    return float(gaps[k]), points[k]


#: Grid of a strip's points for :func:`uncovered`: along its rails (evenly by their
#: length, and at its rulings) × across.
ALONG, ACROSS = 401, 33
#: The strip's edges are measured on this many times :data:`ALONG` points for the grid.
LENGTH_SAMPLES = 4
#: Nearest cells (by their centres) whose triangles a query is measured to.
NEAREST = 24


def _mesh_distance(strip: Surface, points: FloatArray) -> FloatArray:
    from trimesh.triangles import closest_point as closest_on_triangles  # on first use (trimesh_type)

    # along: at the strip's rulings too, where its edges may turn a corner (a strip cut at
    # the design's edge, :mod:`.outline_cut`): a mesh that cut the corner would over-report
    along = _even_along(strip)
    rulings = getattr(strip, "ruling_parameters", None)
    if rulings is not None:
        rulings = np.asarray(rulings, dtype=float)
        along = np.union1d(along, np.clip(rulings[np.isfinite(rulings)], 0.0, 1.0))
    count = len(along)
    gu, gv = np.meshgrid(along, np.linspace(0.0, 1.0, ACROSS), indexing="ij")
    grid = strip.point_at(gu.ravel(), gv.ravel())
    a = (np.arange(count - 1)[:, None] * ACROSS + np.arange(ACROSS - 1)).ravel()  # cells' first corners
    b, c, d = a + ACROSS, a + ACROSS + 1, a + 1
    # cells by their centres (a fan's cells share a corner at its apex, never a centre)
    centres = 0.25 * (grid[a] + grid[b] + grid[c] + grid[d])
    _, index = cKDTree(centres).query(points, k=NEAREST)
    cells = np.asarray(index).reshape(len(points), NEAREST)
    triangles = np.stack([np.stack([a, b, c], -1), np.stack([a, c, d], -1)], 1)[cells].reshape(-1, 3)
    query = np.repeat(points, NEAREST * 2, axis=0)
    with np.errstate(invalid="ignore", divide="ignore"):  # a cell of zero width: NaN, left out
        found = closest_on_triangles(grid[triangles], query)
    # a degenerate triangle (two rulings a hair apart) has no closest point of its own; its
    # neighbours' edges hold it, so the nearest of the others is the distance
    return np.fmin.reduce(np.linalg.norm(found - query, axis=1).reshape(len(points), -1), axis=1)


def _even_along(strip: Surface) -> FloatArray:
    """:data:`ALONG` parameters evenly spaced by the length of the strip's two edges
    together (measured on :data:`LENGTH_SAMPLES` times as many): where a cut strip's edge
    runs fast in its parameter (its lines sweep along a trim), an even grid of parameters
    would chord off its edge there (5.7 cm where the strip reaches the edge to 0.8 mm)."""
    t = np.linspace(0.0, 1.0, LENGTH_SAMPLES * ALONG)
    edges = [strip.point_at(t, np.full(len(t), v)) for v in (0.0, 1.0)]
    steps = sum(np.linalg.norm(np.diff(edge, axis=0), axis=1) for edge in edges)
    length = np.concatenate([[0.0], np.cumsum(steps)])
    if not length[-1] > 0.0:
        return np.linspace(0.0, 1.0, ALONG)
    return np.interp(np.linspace(0.0, length[-1], ALONG), length, t)


def crease_angle(lower: RulingResult, lower_edge: Curve, upper: RulingResult, upper_edge: Curve) -> float:
    """The largest fold angle (rad) between two neighbouring strips along the boundary they
    share: the angle between the lower strip's tangent plane along its upper edge (ruling ×
    the edge's tangent at each ruling's end) and the upper strip's along its lower edge,
    the latter interpolated along the boundary's parameter to the former's rulings. NaN
    where a plane is undefined (a ruling of zero length) is left out; NaN if all are."""
    n_low = np.cross(lower.ends - lower.starts, lower_edge.derivatives(lower.t, 1)[1])
    n_up = np.cross(upper.ends - upper.starts, upper_edge.derivatives(upper.s, 1)[1])
    with np.errstate(invalid="ignore", divide="ignore"):
        n_low /= np.linalg.norm(n_low, axis=1, keepdims=True)
        n_up /= np.linalg.norm(n_up, axis=1, keepdims=True)
    order = np.argsort(upper.s, kind="stable")
    s, normals = upper.s[order], n_up[order]
    ok = np.isfinite(normals).all(axis=1)
    if ok.sum() < 2:
        return float("nan")
    at = np.column_stack([np.interp(lower.t, s[ok], normals[ok, k]) for k in range(3)])
    with np.errstate(invalid="ignore", divide="ignore"):
        at /= np.linalg.norm(at, axis=1, keepdims=True)
    angle = angle_between(n_low, at)
    angle = angle[np.isfinite(angle)]
    return float(angle.max()) if len(angle) else float("nan")


def distances_to_strips(points: FloatArray, strips: Sequence[Surface]) -> FloatArray:
    """Each point's distance to the nearest of ``strips`` (as :func:`uncovered` measures)."""
    nearest = np.full(len(points), np.inf)
    for strip in strips:
        nearest = np.minimum(nearest, _mesh_distance(strip, points))
    return nearest
