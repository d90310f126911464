"""Direct developables: cylinders, cones and tangent developables, ruling by ruling.

Each is developable by construction, whatever the input curve:

- a **cylinder** translates the curve: every ruling is parallel to one direction;
- a **cone** joins the curve to one point, the apex;
- a **tangent developable** ``S(u, v) = C(u) + v·T(u)`` is swept by the tangent lines of
  a space curve, which becomes its edge of regression.

The functions return the rulings with the *exact* tangents of both edge curves at their
ends (from the curve's derivatives, not from neighbouring rulings), and the warp angles
those give, which are zero to rounding. The ``Segments + 1`` rulings start at stations
spaced evenly in arc length along the curve (see :mod:`.stations`).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from ..counts import segment_count
from ..curve_base import Curve, FloatArray
from ..vectors import as_vector, normalise, unit
from .stations import Spacing, station_parameters
from .warp import warp_angles


class Rulings(NamedTuple):
    """Rulings of a ruled strip, one row per ruling, in order along the strip."""

    parameters: FloatArray  #: (n,) parameter t of each ruling's station on the input curve
    starts: FloatArray  #: (n, 3) start points (on the first edge)
    ends: FloatArray  #: (n, 3) end points (on the second edge)
    start_tangents: FloatArray  #: (n, 3) unit tangents of the first edge (zero where undefined)
    end_tangents: FloatArray  #: (n, 3) unit tangents of the second edge (zero where undefined)
    warp: FloatArray  #: (n,) warp angles, rad, from those exact tangents


def _finite(value: float, name: str) -> float:
    value = float(value)
    if not np.isfinite(value):
        raise ValueError(f"{name} must be a finite number; got {value}.")
    return value


def _rulings(
    u: FloatArray, starts: FloatArray, ends: FloatArray, ta: FloatArray, tb: FloatArray,
    apex_a: bool = False, apex_b: bool = False,
) -> Rulings:
    ta, tb = unit(ta), unit(tb)
    return Rulings(u, starts, ends, ta, tb, warp_angles(starts, ends, ta, tb, apex_a=apex_a, apex_b=apex_b))


def cylinder_rulings(
    curve: Curve, direction: ArrayLike, height: float, segments: int, spacing: Spacing = "length"
) -> Rulings:
    """Rulings of the cylinder through ``curve``: ``C(u) → C(u) + height·d`` with d = unit(direction).

    The curve may be planar or not, closed or open; a negative ``height`` extrudes the
    other way. Both edges have the tangent C'(u), so every warp angle is exactly 0.

    >>> from torsal.nodes.geometry.curves import Line
    >>> r = cylinder_rulings(Line([0, 0, 0], [1, 0, 0]), [0, 0, 2], 3.0, 2)
    >>> r.ends.tolist()
    [[0.0, 0.0, 3.0], [0.5, 0.0, 3.0], [1.0, 0.0, 3.0]]
    """
    n = segment_count(segments) + 1
    d = normalise(direction, "cylinder direction")
    h = _finite(height, "The height")
    u = station_parameters(curve, n, spacing)
    c, d1 = curve.derivatives(u, 1)
    return _rulings(u, c, c + h * d, d1, d1)


def cone_rulings(
    curve: Curve, apex: ArrayLike, height: float, segments: int, spacing: Spacing = "length"
) -> Rulings:
    """Rulings of the cone joining ``curve`` to ``apex``: from C(u) towards the apex, length ``height``.

    A ruling whose curve point is nearer the apex than ``height`` stops at the apex
    (clamped), so a large height gives the whole cone. A negative height runs the
    rulings away from the apex (the flaring part of the same cone), unclamped.

    The far edge ``E(u) = C(u) + h·w(u)``, with ``w = (P − C)/ρ`` the unit direction to
    the apex P at distance ρ, has the exact tangent ``E' = C' − (h/ρ)(C' − (C'·w) w)``
    (the derivative of a unit vector is its direction's derivative minus its component
    along itself). A clamped ruling ends at the apex, where the edge stands still and
    the tangent is zero.
    """
    n = segment_count(segments) + 1
    p = as_vector(apex)
    h = _finite(height, "The height")
    u = station_parameters(curve, n, spacing)
    c, d1 = curve.derivatives(u, 1)
    to_apex = p - c
    rho = np.linalg.norm(to_apex, axis=1)
    w = unit(to_apex)
    clamped = (h >= rho) & (h > 0)
    length = np.where(clamped, rho, h)
    ends = np.where(clamped[:, None], p, c + length[:, None] * w)
    safe_rho = np.where(rho > 0, rho, 1.0)
    along = np.einsum("ij,ij->i", d1, w)[:, None] * w
    end_tangents = d1 - (h / safe_rho)[:, None] * (d1 - along)
    end_tangents = np.where((clamped | (rho == 0))[:, None], 0.0, end_tangents)
    return _rulings(u, c, ends, d1, end_tangents)


def tangent_developable_rulings(
    curve: Curve,
    segments: int,
    length: float,
    cutting_length: float = 0.0,
    two_sided: bool = False,
    spacing: Spacing = "length",
) -> Rulings:
    """Rulings of the tangent developable ``S(u, v) = C(u) + v·T(u)`` of a space curve.

    Each ruling runs along the unit tangent T(u) from ``v = cutting_length`` to
    ``v = length`` (both in model units; the curve itself, v = 0, is the edge of
    regression, where the surface has a sharp cusp — a positive cutting length keeps
    the sheet clear of it). With ``two_sided`` the other sheet, v from
    ``−cutting_length`` to ``−length``, follows as rows ``n … 2n−1`` (loft the two sheets
    separately: they meet only along the cusp).

    Tangents are exact: T = C'/|C'| and its derivative ``T' = (C'' − (C''·T)T)/|C'|``
    give the edge tangents ``C' + v·T'``.

    Raises ``ValueError`` unless ``length > cutting_length`` (and, two-sided,
    ``cutting_length >= 0``, so the sheets do not overlap).
    """
    n = segment_count(segments) + 1
    v_far = _finite(length, "The length")
    v_near = _finite(cutting_length, "The cutting length")
    if not v_far > v_near:
        raise ValueError(f"The length ({v_far}) must exceed the cutting length ({v_near}).")
    if two_sided and v_near < 0:
        raise ValueError("A two-sided tangent developable needs a cutting length >= 0.")
    u = station_parameters(curve, n, spacing)
    c, d1, d2 = curve.derivatives(u, 2)
    tangent = curve.tangent_at(u)
    speed = np.linalg.norm(d1, axis=1)
    moving = speed > 0
    bend = d2 - np.einsum("ij,ij->i", d2, tangent)[:, None] * tangent
    tangent_rate = np.where(moving[:, None], bend / np.where(moving, speed, 1.0)[:, None], 0.0)
    sheets = [(v_near, v_far)] + ([(-v_near, -v_far)] if two_sided else [])
    parts = [
        _rulings(
            u,
            c + a * tangent,
            c + b * tangent,
            d1 + a * tangent_rate,
            d1 + b * tangent_rate,
            apex_a=a == 0,  # on the curve: the edge of regression (warp.py)
            apex_b=b == 0,
        )
        for a, b in sheets
    ]
    return Rulings(*(np.concatenate(fields) for fields in zip(*parts, strict=True)))
