"""Vectors and frames: normalising, angles, rotations and the :class:`Plane` frame.

Every function takes single vectors ``(3,)`` or stacks ``(n, 3)`` and broadcasts; none
loops over points. Zero-length vectors never produce NaN: :func:`unit` maps them to the
zero vector and :func:`angle_between` reports 0 for them. The lean unchecked array
helpers (:mod:`.vec_ops`) do the arithmetic; this module adds conversion and checks.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from .array_types import FloatArray
from .vec_ops import cross, dot

#: Below this length a vector counts as zero (lengths are in model units).
ZERO_LENGTH = 1e-300


def as_points(points: ArrayLike) -> FloatArray:
    """``points`` as a float ``(n, 3)`` array; 2-D points get z = 0, one point becomes ``(1, 3)``.

    >>> as_points([[0, 1], [2, 3]]).tolist()
    [[0.0, 1.0, 0.0], [2.0, 3.0, 0.0]]
    """
    array = np.atleast_2d(np.asarray(points, dtype=float))
    if array.ndim != 2 or array.shape[1] not in (2, 3):
        raise ValueError(f"Expected points with 2 or 3 coordinates, got shape {array.shape}.")
    if array.shape[1] == 2:
        array = np.column_stack([array, np.zeros(len(array))])
    return array


def as_vector(vector: ArrayLike) -> FloatArray:
    """One vector as a float ``(3,)`` array (a 2-D vector gets z = 0)."""
    array = np.asarray(vector, dtype=float).reshape(-1)
    if array.shape == (2,):
        array = np.append(array, 0.0)
    if array.shape != (3,):
        raise ValueError(f"Expected a vector with 2 or 3 coordinates, got {array.shape[0]}.")
    return array


def norm(vectors: ArrayLike) -> FloatArray:
    """Euclidean length along the last axis."""
    return np.linalg.norm(np.asarray(vectors, dtype=float), axis=-1)


def unit(vectors: ArrayLike) -> FloatArray:
    """Unit vectors along the last axis; zero vectors stay zero (never NaN)."""
    v = np.asarray(vectors, dtype=float)
    length = np.linalg.norm(v, axis=-1, keepdims=True)
    safe = np.where(length > ZERO_LENGTH, length, 1.0)
    return np.where(length > ZERO_LENGTH, v / safe, 0.0)


def normalise(vector: ArrayLike, what: str = "vector") -> FloatArray:
    """One unit vector, or ``ValueError`` naming ``what`` when it has zero length.

    Use this for inputs that must have a direction (an axis, a normal); use :func:`unit`
    for stacks where zero vectors should pass through.
    """
    v = as_vector(vector)
    length = float(np.linalg.norm(v))
    if not np.isfinite(length) or length <= ZERO_LENGTH:
        raise ValueError(f"The {what} has zero length, so it has no direction.")
    return v / length


def angle_between(a: ArrayLike, b: ArrayLike) -> FloatArray:
    """Angle in [0, π] between vectors, broadcast over stacks.

    Uses ``atan2(|a×b|, a·b)``, which is accurate for nearly parallel vectors (where
    ``arccos`` of the dot product loses half the digits) and is 0 for zero vectors.
    """
    a = np.asarray(a, dtype=float)
    b = np.asarray(b, dtype=float)
    return np.arctan2(norm(cross(a, b)), dot(a, b))


def signed_angle(a: ArrayLike, b: ArrayLike, normal: ArrayLike) -> FloatArray:
    """Angle in (-π, π] from ``a`` to ``b``, positive counter-clockwise seen from ``normal``."""
    a = np.asarray(a, dtype=float)
    b = np.asarray(b, dtype=float)
    n = unit(normal)
    return np.arctan2(dot(cross(a, b), n), dot(a, b))


def rotation_matrix(axis: ArrayLike, angle: float) -> FloatArray:
    """3×3 matrix rotating by ``angle`` (radians, right-handed) about the unit ``axis``.

    Rodrigues' formula ``R = I + sin θ K + (1 − cos θ) K²`` with ``K`` the cross-product
    matrix of the axis.
    """
    x, y, z = normalise(axis, "rotation axis")
    k = np.array([[0.0, -z, y], [z, 0.0, -x], [-y, x, 0.0]])
    return np.eye(3) + np.sin(angle) * k + (1.0 - np.cos(angle)) * (k @ k)


def rotate(vectors: ArrayLike, axis: ArrayLike, angle: float | ArrayLike) -> FloatArray:
    """Rotate vectors about an axis through the origin by ``angle`` (radians).

    ``angle`` may be one value or one per vector. Rodrigues' rotation formula:
    ``v cos θ + (k×v) sin θ + k (k·v)(1 − cos θ)``.
    """
    v = np.asarray(vectors, dtype=float)
    k = normalise(axis, "rotation axis")
    theta = np.asarray(angle, dtype=float)[..., None]
    cos, sin = np.cos(theta), np.sin(theta)
    return v * cos + np.cross(k, v) * sin + k * (v @ k)[..., None] * (1.0 - cos)


def rotate_2d(points: ArrayLike, angle: float | ArrayLike) -> FloatArray:
    """Rotate 2-D points ``(n, 2)`` counter-clockwise about the origin by ``angle``."""
    p = np.asarray(points, dtype=float)
    theta = np.asarray(angle, dtype=float)
    cos, sin = np.cos(theta), np.sin(theta)
    x, y = p[..., 0], p[..., 1]
    return np.stack([cos * x - sin * y, sin * x + cos * y], axis=-1)


def perpendicular(vectors: ArrayLike) -> FloatArray:
    """A unit vector perpendicular to each input (deterministic; zero for zero input).

    Crosses with the world axis least aligned with the vector, so the result is never
    ill-conditioned.
    """
    v = np.asarray(vectors, dtype=float)
    axes = np.eye(3)[np.argmin(np.abs(v), axis=-1)]
    return unit(np.cross(v, axes))


@dataclass(frozen=True)
class Plane:
    """A right-handed orthonormal frame: ``origin`` and unit axes ``x``, ``y``, ``z = x × y``.

    Build one with :meth:`Plane.from_normal`, :meth:`Plane.from_axes` or
    :meth:`Plane.from_points`; the plain constructor expects axes that are already
    orthonormal and right-handed (it checks).

    >>> p = Plane.from_normal([0, 0, 0], [0, 0, 2])
    >>> p.z.tolist()
    [0.0, 0.0, 1.0]
    """

    origin: FloatArray
    x: FloatArray
    y: FloatArray
    z: FloatArray

    def __post_init__(self) -> None:
        for name in ("origin", "x", "y", "z"):
            value = as_vector(getattr(self, name))
            value.setflags(write=False)
            object.__setattr__(self, name, value)
        axes = np.stack([self.x, self.y, self.z])
        if not np.allclose(axes @ axes.T, np.eye(3), atol=1e-9) or np.linalg.det(axes) < 0:
            raise ValueError("A plane's axes must be orthonormal and right-handed.")

    @classmethod
    def from_axes(cls, origin: ArrayLike, x_axis: ArrayLike, y_axis: ArrayLike) -> Plane:
        """Plane through ``origin`` with x along ``x_axis`` and y in the (x_axis, y_axis) plane.

        ``y_axis`` need not be perpendicular to ``x_axis`` (Gram–Schmidt makes it so),
        but the two must not be parallel.
        """
        x = normalise(x_axis, "plane's x axis")
        y = as_vector(y_axis)
        y = y - (y @ x) * x
        y = normalise(y, "plane's y axis (parallel to the x axis)")
        return cls(as_vector(origin), x, y, np.cross(x, y))

    @classmethod
    def from_normal(cls, origin: ArrayLike, normal: ArrayLike) -> Plane:
        """Plane through ``origin`` with normal ``normal``; x is chosen deterministically.

        x is the world x axis projected into the plane when possible (so the world XY
        plane comes back as itself), otherwise the world y axis projected.
        """
        z = normalise(normal, "plane normal")
        seed = np.array([1.0, 0.0, 0.0]) if abs(z[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
        x = unit(seed - (seed @ z) * z)
        return cls(as_vector(origin), x, np.cross(z, x), z)

    @classmethod
    def from_points(cls, a: ArrayLike, b: ArrayLike, c: ArrayLike) -> Plane:
        """Plane through three points: origin ``a``, x towards ``b``, ``c`` on the +y side."""
        a = as_vector(a)
        return cls.from_axes(a, as_vector(b) - a, as_vector(c) - a)

    @property
    def normal(self) -> FloatArray:
        """The unit normal (the z axis)."""
        return self.z

    @property
    def axes(self) -> FloatArray:
        """The 3×3 matrix whose rows are x, y, z."""
        return np.stack([self.x, self.y, self.z])

    def point_at(self, u: ArrayLike, v: ArrayLike, w: ArrayLike = 0.0) -> FloatArray:
        """World points at plane coordinates ``(u, v, w)`` (broadcast)."""
        uvw = np.stack(np.broadcast_arrays(*(np.asarray(c, dtype=float) for c in (u, v, w))), -1)
        return self.origin + uvw @ self.axes

    def to_local(self, points: ArrayLike) -> FloatArray:
        """Plane coordinates ``(u, v, w)`` of world points (w is the signed distance)."""
        return (np.asarray(points, dtype=float) - self.origin) @ self.axes.T

    def signed_distance(self, points: ArrayLike) -> FloatArray:
        """Signed distance of points from the plane, positive on the normal's side."""
        return (np.asarray(points, dtype=float) - self.origin) @ self.z

    def project(self, points: ArrayLike) -> FloatArray:
        """Orthogonal projection of points onto the plane."""
        p = np.asarray(points, dtype=float)
        return p - self.signed_distance(p)[..., None] * self.z

    def flipped(self) -> Plane:
        """The same plane with its normal reversed (x and y swapped to stay right-handed)."""
        return Plane(self.origin, self.y, self.x, -self.z)

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, Plane):
            return NotImplemented
        return all(np.array_equal(getattr(self, n), getattr(other, n)) for n in ("origin", "x", "y", "z"))

    def __hash__(self) -> int:
        return hash(tuple(np.concatenate([self.origin, self.x, self.y, self.z]).tolist()))


#: The world XY plane.
WORLD_XY = Plane(np.zeros(3), np.array([1.0, 0, 0]), np.array([0.0, 1, 0]), np.array([0.0, 0, 1]))
#: The world YZ plane (normal +x).
WORLD_YZ = Plane(np.zeros(3), np.array([0.0, 1, 0]), np.array([0.0, 0, 1]), np.array([1.0, 0, 0]))
#: The world ZX plane (normal +y).
WORLD_ZX = Plane(np.zeros(3), np.array([0.0, 0, 1]), np.array([1.0, 0, 0]), np.array([0.0, 1, 0]))
