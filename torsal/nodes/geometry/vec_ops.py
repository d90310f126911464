"""Lean row-wise vector operations on ``(..., 3)`` arrays: cross, dot, det, norm, unit, extent, bounds;
and the plane cross product (cross2).

``np.cross`` and ``np.linalg.norm`` spend most of their time on axis bookkeeping for
the small arrays the kernels pass around (a strip's few hundred rulings), and solvers
call these hundreds of times per solve; written out they are two to three times
faster. They take arrays as they are (no conversion, no checks): for validated input
use :mod:`.vectors`. This is the kernel's one home for them; it imports nothing of the
kernel but :mod:`.array_types`, so any module can use it without an import circle.

>>> import numpy as np
>>> cross(np.array([[1.0, 0, 0]]), np.array([[0, 1.0, 0]])).tolist()
[[0.0, 0.0, 1.0]]
"""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager
from contextvars import ContextVar

import numpy as np
from numpy.typing import ArrayLike

from .array_types import FloatArray


def cross(a: FloatArray, b: FloatArray) -> FloatArray:
    """Row-wise cross product (broadcasting), component by component from the coordinates'
    columns: (a × b)_x = a_y·b_z − a_z·b_y and so on (``np.cross``'s values, bit for bit,
    without its axis bookkeeping). (It gathered the coordinates with ``take`` along the last
    axis before: several times slower past a thousand rows when timed alone, the same in
    the flagship's re-solve, so the plain formula stays.)"""
    out = np.empty(np.broadcast_shapes(a.shape, b.shape), dtype=np.result_type(a, b))
    for k, (i, j) in enumerate(_AFTER):
        np.subtract(a[..., i] * b[..., j], a[..., j] * b[..., i], out=out[..., k])
    return out


#: For each coordinate k of a cross product, the two after it (cyclically): i, j.
_AFTER = ((1, 2), (2, 0), (0, 1))


def cross2(a: FloatArray, b: FloatArray) -> FloatArray:
    """Row-wise cross product of plane (2-) vectors, a_x·b_y − a_y·b_x: twice the signed area
    of the triangle they span (positive when b is counter-clockwise of a)."""
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


def dot(a: FloatArray, b: FloatArray) -> FloatArray:
    """Row-wise dot product (broadcasting), of 3-vectors or of plane (2-) vectors."""
    if a.shape[-1] == 3:  # (a0·b0 + a1·b1) + a2·b2, the products in one multiplication
        products = a * b
        return products[..., 0] + products[..., 1] + products[..., 2]
    return np.einsum("...i,...i->...", a, b)


def det(r: FloatArray, u: FloatArray, v: FloatArray) -> FloatArray:
    """Row-wise determinant det[r, u, v] = r · (u × v) (broadcasting)."""
    products = r * cross(u, v)
    return products[..., 0] + products[..., 1] + products[..., 2]


def flatnonzero(a: FloatArray) -> FloatArray:
    """``np.flatnonzero(a)`` for an array: the indices of its non-zero items, flattened."""
    return a.ravel().nonzero()[0]


def norm(a: FloatArray) -> FloatArray:
    """Row-wise Euclidean length."""
    return np.sqrt(np.einsum("...i,...i->...", a, a))


def linalg_norm(a: FloatArray) -> FloatArray:
    """``np.linalg.norm(a, axis=-1)`` of a float array, bit for bit: the square root of the same
    sum of the same squares (:func:`norm` sums them in another order). numpy adds fewer than
    eight items one after another, from the first: so are a point's 2 or 3 squares added
    here, as whole columns (numpy's reduction along a short axis goes one row at a time,
    four times slower on 8,000 triangles' edges)."""
    squares = a * a
    if a.shape[-1] >= 8:  # (numpy sums as many pairwise: its own reduction)
        return np.sqrt(np.add.reduce(squares, axis=-1))
    total = squares[..., 0].copy()
    for k in range(1, a.shape[-1]):
        total += squares[..., k]
    return np.sqrt(total)


def unit(a: FloatArray) -> FloatArray:
    """Row-wise unit vectors; zero rows stay zero."""
    length = norm(a)[..., None]
    return a / np.where(length > 0, length, 1.0)


def extent(points: FloatArray) -> FloatArray:
    """Per-coordinate spread (max − min) of ``(n, 3)`` points: ``np.ptp(points, axis=0)``, bit
    for bit, several times faster on small arrays (reducing the rows of an (n, 3) array
    strides across it; its transposed copy reduces along contiguous rows)."""
    low, high = bounds(points)
    return high - low


def bounds(points: FloatArray) -> tuple[FloatArray, FloatArray]:
    """Per-coordinate ``(min, max)`` of ``(n, k)`` points, from one transposed copy (reducing
    along contiguous rows): what :func:`extent` and :func:`anchor` are made of."""
    columns = np.ascontiguousarray(points.T)
    return columns.min(axis=1), columns.max(axis=1)


def anchor(points: FloatArray) -> FloatArray:
    """A point to measure ``(n, k)`` points from: the centre of their bounding box.

    Kernel objects keep their coefficients relative to it, so that what they compute
    from differences of positions (derivatives, chords, areas) carries rounding error
    relative to the object's extent, not to its distance from the world origin: a
    curve at site coordinates (1e6 m) is as accurate, and converges as fast, as the same
    curve at the origin. ``points - anchor(points)`` is exact where the extent is small
    against the coordinates (Sterbenz), so the local coordinates lose nothing.
    """
    low, high = bounds(points)
    return 0.5 * (high + low)


#: Ulps of the largest coordinate that a difference of computed positions may be off by.
POSITION_ULPS = 16


def position_rounding(points: FloatArray) -> float:
    """The rounding error of a difference of positions near ``points`` (absolute).

    A point computed at site coordinates (1e6 m) is rounded to ~1e-10 m whatever the
    object's size, so a gap between two computed positions (a query and its closest
    point, say) cannot be smaller than this; tests of such a gap against a tolerance
    relative to the object's size add it, or they never pass far from the origin.
    """
    own = POSITION_ULPS * _EPS * float(np.maximum.reduce(np.abs(points), axis=None, initial=0.0))
    return max(own, _ROUNDING_FLOOR.get())


def position_roundings(largest: FloatArray) -> FloatArray:
    """:func:`position_rounding` of several objects at once, from the largest magnitude of
    a coordinate of each (the same values)."""
    return np.maximum(POSITION_ULPS * _EPS * largest, _ROUNDING_FLOOR.get())


#: The least :func:`position_rounding` inside a :func:`rounding_of` block (0 outside).
_ROUNDING_FLOOR: ContextVar[float] = ContextVar("rounding_floor", default=0.0)


@contextmanager
def rounding_of(points: ArrayLike) -> Iterator[None]:
    """Inside the block, positions are known no better than near ``points``: the world
    coordinates of a model solved in a frame anchored at it
    (:mod:`torsal.nodes.geometry.local_frame`). Its inputs were rounded there (1.2e-7 m at
    1e9 m), so tests that allow for the rounding of positions (a flat run of two curves,
    a warp's check) allow for that, as a solve in world coordinates would, though the
    local coordinates are small."""
    floor = position_rounding(np.asarray(points, dtype=float))
    token = _ROUNDING_FLOOR.set(floor)
    try:
        yield
    finally:
        _ROUNDING_FLOOR.reset(token)


#: How much a derivative made of positions (finite differences, rational weights) may
#: amplify their rounding, relative to the object's size: the gain behind
#: :func:`derivative_noise`.
NOISE_GAIN = 1e4


def derivative_noise(points: FloatArray) -> float:
    """The share of an object's derivatives (and of an integral of them, per unit of its
    domain) that its coordinates' rounding may leave as noise: :data:`NOISE_GAIN` ulps of
    the largest coordinate over the object's extent. ~2e-12 at the origin (below every
    tolerance); 4e-7 for a 5 m object at 1e6 m, where a curve given by a function of its
    world coordinates has finite-difference derivatives noisy at 2e-8: an adaptive
    integral stops refining there instead of chasing the noise (minutes of work)."""
    size = float(norm(extent(points))) if len(points) else 0.0
    if not size > 0.0:
        return 0.0
    return NOISE_GAIN * _EPS * float(np.maximum.reduce(np.abs(points), axis=None, initial=0.0)) / size


def differenced(geometry: object) -> bool:
    """Whether a curve's or surface's first derivatives may be differences of its positions
    (a function of world coordinates, differentiated numerically): only then is
    :func:`derivative_noise` the floor of an integral of them. An object that says
    ``exact_derivatives`` is as it says; a wrapper (a rail, a transform, a curve on a
    surface: its ``curve`` or ``surface``) is as exact as what it wraps; any other kind may
    be differenced."""
    for _ in range(_WRAPPERS):
        exact = getattr(geometry, "exact_derivatives", None)
        if exact is not None:
            return not exact
        inner = getattr(geometry, "curve", None)
        if inner is None:
            inner = getattr(geometry, "surface", None)
        if inner is None or inner is geometry:
            return True
        geometry = inner
    return True


#: Most wrappers :func:`differenced` looks through.
_WRAPPERS = 16

_EPS = float(np.finfo(float).eps)
