"""The drawing meshes of many ruled surfaces in one pass (the viewport's strips).

A slider drag of the Kaohsiung roof re-draws its strips' ruled surfaces on every solve:
84 surfaces for 28 strips, 840 for 280. Meshed one by one (:meth:`Surface.mesh_arrays`),
each pays a dozen small evaluations whose fixed cost is most of the work. Here the
surfaces whose rails run on curves (:func:`~torsal.nodes.geometry.curve_rail.ruled_between`)
are meshed together: every rail's pace on the shared grid in one polynomial evaluation per
set of ruling parameters, every curve evaluated once at all its rails' parameters, and the
surfaces' points, derivatives and normals as stacked arrays. Every step is elementwise
(the curves are of :data:`~torsal.nodes.geometry.curve_rail.POINTWISE` types), so each
surface gets what its own :meth:`~Surface.mesh_arrays` gives, bit for bit; other surfaces
are meshed one by one.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from .curve_base import FloatArray
from .curve_rail import POINTWISE, CurveRail
from .curves.shared_knots import derivatives_together
from .ruled import RuledSurface
from .surface_base import DEGENERATE_RATIO, Surface, _grid_triangles, _uv_grid, broadcast_uv
from .vec_ops import cross, dot

Mesh = tuple[FloatArray, np.ndarray, FloatArray]


def _together(surface: Surface) -> bool:
    """Whether ``surface`` is meshed in the joint pass: a plain ruled surface between two
    curve rails on pointwise curves (what :func:`ruled_between` makes)."""
    if type(surface) is not RuledSurface or surface._both is not None:
        return False
    rails = (surface.curve_a, surface.curve_b)
    return all(type(rail) is CurveRail and isinstance(rail.curve, POINTWISE) for rail in rails)


def ruled_mesh_arrays(surfaces: Sequence[Surface], nu: int, nv: int) -> list[Mesh]:
    """``[s.mesh_arrays(nu, nv) for s in surfaces]``, the same arrays bit for bit, the
    ruled surfaces between curve rails meshed together."""
    joint = [k for k, surface in enumerate(surfaces) if _together(surface)]
    if len(joint) < 2:
        joint = []
    alone = set(range(len(surfaces))) - set(joint)
    out = [surface.mesh_arrays(nu, nv) if k in alone else None for k, surface in enumerate(surfaces)]
    if joint:
        for k, mesh in zip(joint, _joint([surfaces[k] for k in joint], nu, nv), strict=True):  # type: ignore[arg-type]
            out[k] = mesh
    return out  # type: ignore[return-value]


def _joint(surfaces: list[RuledSurface], nu: int, nv: int) -> list[Mesh]:
    if nu < 2 or nv < 2:
        raise ValueError("to_mesh needs at least 2 × 2 vertices")
    grid = _uv_grid(nu, nv)
    rails = [surface.curve_a for surface in surfaces]
    rails += [surface.curve_b for surface in surfaces]
    anchors = [surface._rail_anchors for surface in surfaces]
    origins = np.array([a[0] for a in anchors])
    offsets = np.array([a[1] for a in anchors])
    points, su, sv = _derivatives(rails, origins, offsets, *broadcast_uv(grid[0].copy(), grid[1].copy()))
    # Surface._grid_normals, for all the surfaces at once: a normal that degenerates is
    # re-taken a step inwards (every surface evaluated there, its degenerate points kept)
    normal = cross(su, sv)
    length = np.sqrt(dot(normal, normal))
    bad = ~(length > DEGENERATE_RATIO * (dot(su, su) + dot(sv, sv)))
    if bad.any():  # (the surfaces that have such points, at the grid points some of them have)
        some, where = np.flatnonzero(bad.any(axis=1)), np.flatnonzero(bad.any(axis=0))
        inwards = [rails[k] for k in some] + [rails[len(surfaces) + k] for k in some]
        s, t = broadcast_uv(grid[2], grid[3])
        _, su_in, sv_in = _derivatives(inwards, origins[some], offsets[some], s[where], t[where])
        bad_in = bad[some][:, where]
        retaken = cross(su_in[bad_in], sv_in[bad_in])
        normal[bad] = retaken
        length[bad] = np.sqrt(dot(retaken, retaken))
    found = length > 0.0
    np.divide(normal, length[..., None], out=normal, where=found[..., None])
    if not found.all():
        normal[~found] = np.nan  # (no normal, as normal_at says)
    faces = _grid_triangles(nu, nv)
    return [(points[k], faces, normal[k]) for k in range(len(surfaces))]


def _derivatives(
    rails: list[CurveRail], origins: FloatArray, offsets: FloatArray, s: FloatArray, t: FloatArray
) -> tuple[FloatArray, FloatArray, FloatArray]:
    """:meth:`RuledSurface.derivatives` (order 1) of every surface at ``(s, t)``, stacked
    ``(surfaces, len(s), 3)``: ``rails`` are the surfaces' rails A, then their rails B."""
    # the rails at each distinct u of the grid (every step is pointwise), then on the grid
    u, grid = np.unique(s, return_inverse=True)
    at, speed = _paces(rails, u)
    # each curve evaluated once, at the parameters of every rail on it
    values = np.empty((len(rails), len(u), 3))
    tangents = np.empty((len(rails), len(u), 3))
    on: dict[int, list[int]] = {}
    for row, rail in enumerate(rails):
        on.setdefault(id(rail.curve), []).append(row)
    groups = list(on.values())
    curves = [rails[rows[0]].curve for rows in groups]
    order = np.concatenate(groups)
    # (CurveRail._wrapped: a closed curve's parameters taken round, an open one's clipped)
    closed = np.array([rail.curve.closed for rail in rails])
    wrapped = np.clip(at, 0.0, 1.0)
    if closed.any():
        wrapped[closed] = np.mod(at[closed], 1.0)
    x = wrapped[order].reshape(-1)
    bounds = np.zeros(len(groups) + 1, dtype=np.int64)
    np.cumsum([len(rows) * len(u) for rows in groups], out=bounds[1:])
    ders = derivatives_together(curves, x, bounds, 1, local=True)
    values[order] = ders[0].reshape(-1, len(u), 3)
    tangents[order] = ders[1].reshape(-1, len(u), 3)
    tangents *= speed[:, :, None]  # (CurveRail._compose at order 1)
    values, tangents = values[:, grid], tangents[:, grid]
    count = len(origins)
    da0, da1 = values[:count], tangents[:count]
    db0, db1 = values[count:] + offsets[:, None, :], tangents[count:]
    w = t[None, :, None]
    span = db0 - da0
    return origins[:, None, :] + (da0 + w * span), da1 + w * (db1 - da1), span


def _paces(rails: list[CurveRail], u: FloatArray) -> tuple[FloatArray, FloatArray]:
    """Each rail's pace σ and σ' at ``u`` ``(rails, len(u))``: :meth:`Pace.derivatives`,
    one evaluation for the rails that share their ruling parameters."""
    at = np.empty((len(rails), len(u)))
    speed = np.empty((len(rails), len(u)))
    shared: dict[int, list[int]] = {}
    for row, rail in enumerate(rails):
        shared.setdefault(id(rail._pace.u), []).append(row)
    for rows in shared.values():
        paces = [rails[row]._pace for row in rows]
        knots = paces[0].u
        i = np.minimum(np.maximum(np.searchsorted(knots, u, side="right") - 1, 0), len(knots) - 2)
        z = u - knots[i]
        joined = paces[0].joined
        if all(pace.joined is joined for pace in paces):  # (fitted together: one gather each)
            at_i = np.array([pace.first for pace in paces])[:, None] + i
            c3, c2, c1, c0 = (c[at_i] for c in joined)
        else:
            c3, c2, c1, c0 = (np.array([getattr(pace, c) for pace in paces])[:, i]
                              for c in ("c3", "c2", "c1", "c0"))
        at[rows] = ((c3 * z + c2) * z + c1) * z + c0
        speed[rows] = (3.0 * c3 * z + 2.0 * c2) * z + c1
    return at, speed
