"""Boundary curves for Rationalise: the design's parameter lines, or a family that runs
through guide curves and blends between them and the design's edges.

A family of boundaries is a curve for every level c in [0, 1]: level 0 and level 1 are
two opposite edges of the design, and the curves in between sweep across it without
meeting. :class:`IsoBoundaries` are the parameter lines of one direction. With guides
(:class:`GuidedBoundaries`), each guide is projected onto the design and read as a
profile v = g(u) in its parameter square (or u = g(v)); the edges are the profiles 0
and 1. A level between two neighbouring profiles is their blend,

    v(t) = (1 − w)·g_k(t) + w·g_{k+1}(t),   w = (c − c_k) / (c_{k+1} − c_k),

where c_k is the mean of g_k: so the curve at level c_k is the guide itself, and the
curves near a guide follow it while those near an edge straighten out towards it (as
Grasshopper's Tween Curves do between two curves). The levels of the guides split the
design into bands; Rationalise places a boundary on every guide and marches each band.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike
from scipy.interpolate import BSpline, make_interp_spline

from ..array_types import FloatArray
from ..curve_base import Curve
from ..local_frame import Mover, register
from ..surface_base import CurveOnSurface, IsoCurve, Surface

#: Samples of each guide projected onto the design.
GUIDE_SAMPLES = 65
#: How far short of the design's edges (in its parameter) a guide may stop: the rest of
#: the way its profile is continued by its spline.
EDGE_REACH = 0.02
#: Closest a guide may come to an edge or to another guide, in the design's parameter.
APART = 1e-3

#: ``path(t, order)``: the path in the parameter square and its derivatives, each (n, 2).
Path = Callable[[FloatArray, int], list[FloatArray]]


class SurfaceCurve(CurveOnSurface):
    """The curve C(t) = S(u(t), v(t)) on a surface, for a path in its parameter square.

    Derivatives up to order 2 are exact by the chain rule from the surface's own; order
    3 comes from :class:`~torsal.nodes.geometry.surface_base.CurveOnSurface`.
    """

    def __init__(self, surface: Surface, path: Path, breaks: ArrayLike = (0.0, 1.0)) -> None:
        self.surface = surface
        self.path = path
        self.breaks = np.asarray(breaks, dtype=float)

    def __repr__(self) -> str:
        return f"SurfaceCurve({self.surface!r})"

    def _breakpoints(self) -> FloatArray:
        return self.breaks

    def _eval(self, t: FloatArray, order: int) -> list[FloatArray]:
        p = self.path(t, order)
        uv = p[0]
        ders = self.surface.derivatives(uv[:, 0], uv[:, 1], order)
        out = [ders[0]]
        if order >= 1:
            du, dv = p[1][:, :1], p[1][:, 1:]
            out.append(ders[1] * du + ders[2] * dv)
        if order >= 2:
            ddu, ddv = p[2][:, :1], p[2][:, 1:]
            out.append(ders[3] * du * du + 2.0 * ders[4] * du * dv + ders[5] * dv * dv
                       + ders[1] * ddu + ders[2] * ddv)
        return out


@register(SurfaceCurve)
def _moved(curve: SurfaceCurve, move: Mover) -> SurfaceCurve:
    """The same path on the moved surface (see :mod:`..local_frame`)."""
    return SurfaceCurve(move(curve.surface), curve.path, curve.breaks)


@dataclass(frozen=True)
class IsoBoundaries:
    """The design's parameter lines along ``family`` ("u": curves along u at fixed v)."""

    design: Surface
    family: str

    @property
    def levels(self) -> FloatArray:
        return np.array([0.0, 1.0])

    def at(self, level: float) -> Curve:
        return IsoCurve(self.design, self.family, level)


@dataclass(frozen=True)
class GuidedBoundaries:
    """Boundaries through guide curves (see the module): ``profiles[k](t)`` is the
    parameter across ``family`` of profile k, whose level is ``levels[k]``; profile 0 and
    the last are the design's edges."""

    design: Surface
    family: str
    profiles: tuple[BSpline | float, ...]
    levels: FloatArray

    def _profile(self, k: int, t: FloatArray, order: int) -> FloatArray:
        g = self.profiles[k]
        if isinstance(g, float):
            return np.full_like(t, g) if order == 0 else np.zeros_like(t)
        return g(t, nu=order) if order else g(t)

    def path(self, level: float) -> Path:
        k = int(np.clip(np.searchsorted(self.levels, level, side="right") - 1, 0, len(self.levels) - 2))
        w = (level - self.levels[k]) / (self.levels[k + 1] - self.levels[k])
        along = 0 if self.family == "u" else 1

        def path(t: FloatArray, order: int) -> list[FloatArray]:
            out = []
            for d in range(order + 1):
                across = (1.0 - w) * self._profile(k, t, d) + w * self._profile(k + 1, t, d)
                running = t if d == 0 else (np.ones_like(t) if d == 1 else np.zeros_like(t))
                pair = np.empty((len(t), 2))
                pair[:, along], pair[:, 1 - along] = running, across
                out.append(pair)
            return out

        return path

    def at(self, level: float) -> Curve:
        return SurfaceCurve(self.design, self.path(level))


def _profile_of(design: Surface, guide: Curve, index: int) -> tuple[str, FloatArray, FloatArray]:
    """A guide projected onto the design: the direction it runs along ("u" or "v") and its
    samples as (along, across) parameters, along increasing."""
    points = guide.point_at(np.linspace(0.0, 1.0, GUIDE_SAMPLES))
    uv = design.closest_point(points).parameters
    steps = np.abs(np.diff(uv, axis=0)).sum(axis=0)
    family = "u" if steps[0] >= steps[1] else "v"
    along, across = (uv[:, 0], uv[:, 1]) if family == "u" else (uv[:, 1], uv[:, 0])
    if along[-1] < along[0]:
        along, across = along[::-1], across[::-1]
    if not np.all(np.diff(along) > 0.0):
        raise ValueError(
            f"guide {index} turns back on itself along the design: a guide must run from one side of "
            "the design to the other without doubling back"
        )
    if along[0] > EDGE_REACH or along[-1] < 1.0 - EDGE_REACH:
        raise ValueError(
            f"guide {index} covers only {family} = {along[0]:.3g} to {along[-1]:.3g} of the design: "
            "extend it from edge to edge of the design"
        )
    return family, along, across


def guided_boundaries(design: Surface, guides: Sequence[Curve]) -> GuidedBoundaries:
    """The boundaries through ``guides`` (curves on or near the design, each running from
    one edge to the opposite one, none meeting another); ``ValueError`` saying which
    guide is at fault otherwise."""
    if design.closed_u or design.closed_v:
        raise ValueError("guides need a design open in both directions: cut it open first")
    read = [_profile_of(design, guide, i + 1) for i, guide in enumerate(guides)]
    families = {family for family, _, _ in read}
    if len(families) > 1:
        raise ValueError("the guides run different ways across the design: give guides that all run "
                         "along the same direction")
    family = families.pop()
    t = np.linspace(0.0, 1.0, 257)
    splines, values = [], []
    for i, (_, along, across) in enumerate(read):
        spline = make_interp_spline(along, across, k=3)
        g = spline(t)
        if g.min() < APART or g.max() > 1.0 - APART:
            raise ValueError(f"guide {i + 1} runs onto or off an edge of the design: keep it inside")
        splines.append(spline)
        values.append(g)
    order = np.argsort([g.mean() for g in values])
    profiles: list[BSpline | float] = [0.0, *(splines[i] for i in order), 1.0]
    sampled = [np.zeros_like(t), *(values[i] for i in order), np.ones_like(t)]
    for k in range(1, len(sampled) - 2):
        if np.min(sampled[k + 1] - sampled[k]) < APART:
            first, second = sorted((int(order[k - 1]) + 1, int(order[k]) + 1))
            raise ValueError(f"guides {first} and {second} cross or touch on the design: guides must "
                             "stay apart")
    levels = np.array([float(np.mean(g)) for g in sampled])
    levels[0], levels[-1] = 0.0, 1.0
    return GuidedBoundaries(design, family, tuple(profiles), levels)
