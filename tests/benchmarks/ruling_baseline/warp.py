"""Warp angles: how far a ruling is from being torsal (developable).

A ruling R from a point of edge A to a point of edge B, with unit edge tangents T1 and
T2 at its two ends, has end normals N1 = R × T1 and N2 = R × T2: the normals of the two
planes that the sheet would have at its ends. A developable sheet has one tangent plane
along the whole ruling, so N1 ∥ N2, i.e. det[R, T1, T2] = 0 (the ruling is *torsal*).

- The **warp angle** is the angle between the *lines* of N1 and N2, in [0, π/2]: what a
  fabricator twists a flat sheet by over the ruling (the thesis's definition; divided by
  |R| it is the warp factor in rad/m).
- The **signed warp** is the angle *from N1 to N2* about R, in (−π, π]. With both edges
  running the same way and rulings that do not cross, a sheet's two normals point to the
  same side, so a good ruling has a signed warp near 0. A value near ±π also has zero
  (unsigned) warp but belongs to a sheet folded back on itself — its rulings cross, or
  its edge of regression (the cusp) runs between the two edges. That is the "second,
  wrong tangent plane" a search on the unsigned angle picks on re-parameterised curves.

Zero-length vectors (a ruling of length 0, a ruling along an edge tangent, an apex)
give a warp of 0: no plane is defined there, so none is violated.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from nodes.geometry.curve_base import FloatArray
from nodes.geometry.vec_ops import cross, dot, norm, unit


def warp_angles(
    starts: ArrayLike,
    ends: ArrayLike,
    tangents_a: ArrayLike,
    tangents_b: ArrayLike,
    signed: bool = False,
) -> FloatArray:
    """Warp angle of each ruling ``starts[i] → ends[i]`` given the edge tangents at its ends.

    Args:
        starts, ends: ``(n, 3)`` ruling end points (on edge A and edge B).
        tangents_a, tangents_b: ``(n, 3)`` edge tangents there (any length; both edges
            oriented the same way for the signed angle to mean anything).
        signed: ``False`` for the warp angle in [0, π/2] (angle between normal lines);
            ``True`` for the angle from N1 to N2 about the ruling, in (−π, π].

    Computed as ``atan2`` of the cross and dot products of the normals, which keeps full
    relative accuracy for tiny angles (``arccos`` of a dot product would not).

    >>> warp_angles([[0, 0, 0]], [[0, 1, 0]], [[1, 0, 0]], [[1, 0, 1]]).round(6).tolist()
    [0.785398]
    """
    start = np.asarray(starts, dtype=float)
    ruling = np.asarray(ends, dtype=float) - start
    n1 = cross(ruling, unit(np.asarray(tangents_a, dtype=float)))
    n2 = cross(ruling, unit(np.asarray(tangents_b, dtype=float)))
    normal_cross = cross(n1, n2)
    normal_dot = dot(n1, n2)
    if signed:
        return np.arctan2(dot(normal_cross, unit(ruling)), normal_dot)
    return np.arctan2(norm(normal_cross), np.abs(normal_dot))


def edge_tangents(points: ArrayLike) -> FloatArray:
    """Tangents of the polyline through ``points`` ``(n, 3)``: second-order central
    differences inside, one-sided at the two ends (unit length; zero where points repeat)."""
    p = np.asarray(points, dtype=float)
    if len(p) < 2:
        return np.zeros_like(p)
    return unit(np.gradient(p, axis=0))


def warp_of_rulings(starts: ArrayLike, ends: ArrayLike, signed: bool = False) -> FloatArray:
    """Warp angles of a ruled strip known only by its rulings, in order along the strip.

    The edge tangents are those of the two edge polylines (through the starts and
    through the ends; :func:`edge_tangents`), so this reports the warp of *any* output —
    a loft, an optimised strip, an imported surface — without its defining curves. The
    tangents are second-order accurate in the ruling spacing, so on a smooth developable
    the reported warp is O(h²), not 0; use :func:`warp_angles` with exact tangents where
    they are known. A fan (rulings through one point) has a zero tangent at the point,
    which counts as no warp there.
    """
    a = np.asarray(starts, dtype=float)
    b = np.asarray(ends, dtype=float)
    return warp_angles(a, b, edge_tangents(a), edge_tangents(b), signed=signed)


def in_plane_tangent(
    ruling: FloatArray, other: FloatArray, left: FloatArray, right: FloatArray
) -> FloatArray:
    """The edge direction at a corner that lies in the plane of the ruling and the other
    edge's tangent, where there is one.

    At a corner of an edge (a polyline vertex, a kinked NURBS) the tangent jumps from
    ``left`` to ``right``; every direction between them is tangent to the corner, so a
    ruling ending there is torsal when the plane through the ruling and the other end's
    tangent ``other`` separates ``left`` from ``right`` (a cone with its apex at the
    corner). This returns that in-plane blend of ``left`` and ``right`` where their
    determinants have opposite signs, and otherwise whichever of them gives the smaller
    warp — among those that orient the sheet's normals consistently (R × other and
    R × tangent to one side), which decides when both lie in the plane (a planar piece
    fanned from the corner). All arguments are ``(n, 3)``; the result is unit length.
    """
    left = unit(np.asarray(left, dtype=float))
    right = unit(np.asarray(right, dtype=float))
    f_left = dot(ruling, cross(other, left))
    f_right = dot(ruling, cross(other, right))
    straddles = f_left * f_right < 0
    denominator = np.where(straddles, f_right - f_left, 1.0)
    blend = (f_right[:, None] * left - f_left[:, None] * right) / denominator[:, None]
    normal = cross(ruling, other)
    left_agrees = dot(normal, cross(ruling, left)) >= 0
    right_agrees = dot(normal, cross(ruling, right)) >= 0
    take_left = np.where(left_agrees != right_agrees, left_agrees, np.abs(f_left) <= np.abs(f_right))
    pick = np.where(take_left[:, None], left, right)
    return unit(np.where(straddles[:, None], blend, pick))
