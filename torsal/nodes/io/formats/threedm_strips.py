"""Developable strips as Rhino geometry that follows their own rulings, in few control points.

A strip made of rulings (a :class:`~torsal.nodes.geometry.ruled.RuledSurface` with
``ruling_lines``, as Rationalise and the strip nodes make) goes to a ``.3dm`` as faces:

- each run of torsal rulings (consecutive rulings that do not share an end) is one ruled
  NURBS face, degree 1 across: its two rails are the strip's own rails over that run,
  fitted *together* (one knot vector, parameter u of the strip) by scipy's
  ``make_lsq_spline``: double knots at the rulings (the rails' pace is piecewise cubic
  between them, C1 at them), then knots inserted where the fit is worst until both rails
  are within :data:`FIT` of the strip's size — so the face's isocurve at a ruling's u is
  that ruling (to the fit), and the face has as few control points as that takes (not one
  per sample). Its end control points are the end rulings' ends and the next ones give the
  rails' own end tangents, so a rail that stands still next to a fan stands still in the
  face too and the face's normals there are the strip's;
- each triangle of a fan (two consecutive rulings sharing an end) is a planar face, a
  trimmed plane through its three corners;
- faces next to each other share their ruling edge exactly (the same two points); a
  degenerate piece (a ruling or triangle of no length or area) is left out, never written
  as a zero-length curve.

The faces of one strip are separate single-face breps in one Rhino group named for the
strip (rhino3dm cannot join breps); their shared edges coincide, so Rhino's Join makes
them one polysurface.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import rhino3dm as rh
from scipy.interpolate import BSpline, make_lsq_spline

from torsal.nodes.geometry.curve_rail import CurveRail
from torsal.nodes.geometry.nurbs_surface import NurbsSurface
from torsal.nodes.geometry.ruled import RuledSurface
from torsal.nodes.io.formats.threedm_native import rhino_surface

#: How close the fitted rails stay to the strip's own, relative to its size.
FIT = 1e-6

#: Samples of the rails per ruling interval, to fit on (and twice as many to check).
SAMPLES = 12

#: The densest sampling tried (per ruling interval) before a fit settles for what it reached.
LARGEST_SAMPLING = 192

#: Two ruling ends closer than this (relative to the size) are one point: a fan.
SAME_POINT = 1e-12


@dataclass(frozen=True)
class Piece:
    """One face of a strip: a rhino3dm brep, its kind and the rulings it spans."""

    brep: rh.Brep
    kind: str  #: "torsal" (a ruled face) or "fan" (a planar triangle)
    first: int  #: index of its first ruling in the strip
    last: int  #: index of its last ruling
    deviation: float  #: largest distance of the face's rails from the strip's (0 for a fan)
    controls: int  #: control points per rail (3 for a fan's corners)


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
    pieces: list[Piece] = []
    k = 0
    n = len(lines)
    while k < n - 1:
        if shared[k]:
            triangle = _fan(lines[k], lines[k + 1], size)
            if triangle is not None:
                pieces.append(Piece(triangle, "fan", k, k + 1, 0.0, 3))
            k += 1
            continue
        end = k + 1
        while end < n - 1 and not shared[end]:
            end += 1
        pieces.append(_ruled(strip, u, lines, k, end, size))
        k = end
    return pieces


def _fan(first: np.ndarray, second: np.ndarray, size: float) -> rh.Brep | None:
    corners = [first[0], first[1], second[1] if np.abs(first[0] - second[0]).max() <= SAME_POINT * size
               else second[0]]
    a, b, c = (np.asarray(p, dtype=float) for p in corners)
    if np.linalg.norm(np.cross(b - a, c - a)) <= 1e-12 * size * size:
        return None
    points = [rh.Point3d(*map(float, p)) for p in (a, b, c, a)]
    plane = rh.Plane(points[0], points[1], points[2])
    return rh.Brep.CreateTrimmedPlane(plane, rh.PolylineCurve(points))


def _ruled(strip: RuledSurface, u: np.ndarray, lines: np.ndarray, first: int, last: int,
           size: float) -> Piece:
    """The ruled face over rulings ``first`` … ``last``: rails fitted with inserted knots."""
    span = u[first:last + 1]
    # the rails are the curves at a pace that is piecewise cubic between rulings (C1 at them):
    # the rulings' parameters are double knots from the start (C1 there too), else the fit
    # converges slowly round them
    rulings = np.repeat(span[1:-1], 2).tolist()
    interior: list[float] = []
    lo, hi = float(span[0]), float(span[-1])
    tolerance = FIT * size
    ends = span[[0, -1]]
    slopes = np.hstack([strip.curve_a.derivatives(ends, 1)[1], strip.curve_b.derivatives(ends, 1)[1]])
    per = SAMPLES
    best: tuple[float, np.ndarray, object] = (np.inf, np.empty(0), None)
    while True:
        fine, data = _samples(strip, span, per, lines[first:last + 1])
        check, truth = _samples(strip, span, 2 * per)
        while True:
            knots = np.concatenate([[lo] * 4, sorted(rulings + interior), [hi] * 4])
            try:
                spline = make_lsq_spline(fine, data, knots, k=3)
            except (ValueError, np.linalg.LinAlgError):  # too many knots for these samples
                break
            # clamped: the end control points are the end rulings' ends, exactly (shared edges),
            # and the next ones give the rails' own end tangents (a rail that stands still there,
            # next to a fan, stands still in the face too: its normals stay the strip's)
            ends = np.array(spline.c)
            n = len(knots) - 4
            ends[0], ends[n - 1] = data[0], data[-1]
            ends[1] = ends[0] + (knots[4] - lo) / 3.0 * slopes[0]
            ends[n - 2] = ends[n - 1] - (hi - knots[n - 1]) / 3.0 * slopes[1]
            spline = BSpline(knots, ends, 3)
            fitted = spline(check)
            error = np.maximum(np.linalg.norm(fitted[:, :3] - truth[:, :3], axis=1),
                               np.linalg.norm(fitted[:, 3:] - truth[:, 3:], axis=1))
            worst = float(error.max())
            if not np.isfinite(worst):  # a span without samples: the previous fit stands
                break
            best = (worst, knots, spline)
            if worst <= tolerance or len(knots) - 4 >= len(fine) // 3:
                break
            breaks = np.unique(np.concatenate([span, interior]))
            where = np.searchsorted(breaks, check[error > tolerance]) - 1
            bad = np.unique(np.clip(where, 0, len(breaks) - 2))
            grown = sorted({*interior, *((breaks[bad] + breaks[bad + 1]) / 2).tolist()})
            if len(grown) == len(interior):  # nothing left to split: the samples are the limit
                break
            interior = grown
        if best[0] <= tolerance or per >= LARGEST_SAMPLING:
            break
        per *= 2  # more knots are needed than these samples can carry
    worst, knots, spline = best
    count = len(knots) - 4
    controls = np.asarray(spline.c)[:count]
    net = np.stack([controls[:, :3], controls[:, 3:]], axis=1)
    surface = NurbsSurface(net, 3, 1, knots, [0.0, 0.0, 1.0, 1.0])
    brep = rh.Brep.CreateFromSurface(rhino_surface(surface))
    return Piece(brep, "torsal", first, last, worst, count)


def _samples(strip: RuledSurface, span: np.ndarray, per: int, lines: np.ndarray | None = None
             ) -> tuple[np.ndarray, np.ndarray]:
    """Parameters ``per`` to a ruling interval, and both rails there side by side (n, 6);
    with ``lines``, the rulings' own ends stand at their parameters (the node's lines exactly)."""
    at = _between(span, per)
    data = np.hstack([strip.curve_a.point_at(at), strip.curve_b.point_at(at)])
    if lines is not None:
        data[np.searchsorted(at, span)] = lines.reshape(-1, 6)
    return at, data


def _between(parameters: np.ndarray, per: int) -> np.ndarray:
    """``per`` evenly spaced parameters in each interval of ``parameters``, ends included."""
    steps = np.linspace(0.0, 1.0, per + 1)[:-1]
    inner = parameters[:-1, None] + (parameters[1:] - parameters[:-1])[:, None] * steps
    return np.concatenate([inner.ravel(), parameters[-1:]])
