"""4×4 transform matrices acting on points in homogeneous coordinates (column vectors).

A point ``p`` maps to ``M @ [p, 1]``; compose with ``A @ B`` (B applies first). Every
builder returns a fresh ``(4, 4)`` array; :func:`apply_transform` applies one to an
``(n, 3)`` stack, :func:`apply_to_vectors` to directions (ignoring translation).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from .array_types import FloatArray
from .vectors import Plane, as_points, as_vector, normalise, rotation_matrix


def translation(vector: ArrayLike) -> FloatArray:
    """Move by ``vector``."""
    m = np.eye(4)
    m[:3, 3] = as_vector(vector)
    return m


def rotation(axis: ArrayLike, angle: float, centre: ArrayLike = (0.0, 0.0, 0.0)) -> FloatArray:
    """Rotate by ``angle`` radians (right-handed) about ``axis`` through ``centre``."""
    c = as_vector(centre)
    m = np.eye(4)
    m[:3, :3] = rotation_matrix(axis, angle)
    m[:3, 3] = c - m[:3, :3] @ c
    return m


def scaling(factor: float, centre: ArrayLike = (0.0, 0.0, 0.0)) -> FloatArray:
    """Scale uniformly by ``factor`` about ``centre``."""
    return non_uniform_scaling((factor, factor, factor), centre)


def non_uniform_scaling(
    factors: ArrayLike, centre: ArrayLike = (0.0, 0.0, 0.0), plane: Plane | None = None
) -> FloatArray:
    """Scale by ``(fx, fy, fz)`` along the axes of ``plane`` (world axes if ``None``),
    keeping ``centre`` (or the plane's origin when a plane is given) fixed."""
    f = as_vector(factors)
    axes = np.eye(3) if plane is None else plane.axes
    origin = as_vector(centre) if plane is None else plane.origin
    m = np.eye(4)
    # axesᵀ diag(f) axes: express in plane coordinates, scale, go back
    m[:3, :3] = axes.T @ np.diag(f) @ axes
    m[:3, 3] = origin - m[:3, :3] @ origin
    return m


def mirror(plane: Plane) -> FloatArray:
    """Reflect across ``plane``: ``p ↦ p − 2((p − o)·n) n``."""
    n = plane.z
    m = np.eye(4)
    m[:3, :3] -= 2.0 * np.outer(n, n)
    m[:3, 3] = 2.0 * (plane.origin @ n) * n
    return m


def orient(source: Plane, target: Plane) -> FloatArray:
    """The rigid motion taking ``source`` onto ``target`` (origin to origin, axes to axes)."""
    m = np.eye(4)
    m[:3, :3] = target.axes.T @ source.axes
    m[:3, 3] = target.origin - m[:3, :3] @ source.origin
    return m


def change_of_basis(plane: Plane) -> FloatArray:
    """World coordinates → coordinates in ``plane`` (the inverse of ``orient(WORLD_XY, plane)``)."""
    m = np.eye(4)
    m[:3, :3] = plane.axes
    m[:3, 3] = -plane.axes @ plane.origin
    return m


def is_affine(matrix: ArrayLike) -> bool:
    """Whether the bottom row is ``[0, 0, 0, 1]`` (no perspective)."""
    return bool(np.array_equal(np.asarray(matrix, dtype=float)[3], [0.0, 0.0, 0.0, 1.0]))


def check_matrix(matrix: ArrayLike) -> FloatArray:
    """``matrix`` as a finite ``(4, 4)`` float array, or ``ValueError``."""
    m = np.asarray(matrix, dtype=float)
    if m.shape != (4, 4):
        raise ValueError(f"Expected a 4×4 transform matrix, got shape {m.shape}.")
    if not np.all(np.isfinite(m)):
        raise ValueError("The transform matrix has a non-finite entry.")
    return m


def apply_transform(matrix: ArrayLike, points: ArrayLike) -> FloatArray:
    """Transform points ``(n, 3)`` (or one ``(3,)`` point), dividing by w if projective."""
    m = check_matrix(matrix)
    single = np.ndim(points) == 1
    p = as_points(points)
    image = p @ m[:3, :3].T + m[:3, 3]
    if not is_affine(m):
        w = p @ m[3, :3] + m[3, 3]
        if np.any(w == 0):
            raise ValueError("The transform sends a point to infinity.")
        image = image / w[:, None]
    return image[0] if single else image


def apply_to_vectors(matrix: ArrayLike, vectors: ArrayLike) -> FloatArray:
    """Transform directions ``(n, 3)`` by the linear part only (no translation).

    For normals under non-uniform scaling use the inverse transpose instead.
    """
    m = check_matrix(matrix)
    return np.asarray(vectors, dtype=float) @ m[:3, :3].T


def transform_plane(matrix: ArrayLike, plane: Plane) -> Plane:
    """The image of a plane under a similarity transform (axes re-orthonormalised).

    Mirrors flip handedness; the image keeps x and y and takes z = x × y.
    """
    m = check_matrix(matrix)
    origin = apply_transform(m, plane.origin)
    x = apply_to_vectors(m, plane.x)
    y = apply_to_vectors(m, plane.y)
    return Plane.from_axes(origin, normalise(x, "transformed x axis"), y)
