"""One way to apply a 4×4 transform to every kind of value a Geometry input may carry.

:func:`transform_value` maps points, vectors, planes, curves (lines, polylines,
NURBS ...), surfaces, triangle meshes and mesh surfaces through a matrix from
:mod:`torsal.nodes.geometry.transforms`, returning a new value of the same kind; inputs
are never changed in place. Anything else raises a warning naming what arrived.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from torsal.engine.node import NodeWarning
from torsal.engine.types import describe
from torsal.engine.values import Plane, Point, Vector
from torsal.nodes.common.convert import engine_plane, kernel_errors, kernel_plane, point, vector
from torsal.nodes.geometry.curve_base import Curve
from torsal.nodes.geometry.mesh_surface import MeshSurface
from torsal.nodes.geometry.surface_base import Surface
from torsal.nodes.geometry.transforms import apply_to_vectors, apply_transform, transform_plane
from torsal.nodes.geometry.trimesh_type import TriangleMesh

if TYPE_CHECKING:
    import trimesh

SUPPORTED = "points, vectors, planes, curves, surfaces and meshes"


def _mesh(mesh: trimesh.Trimesh, matrix: np.ndarray) -> trimesh.Trimesh:
    moved = mesh.copy()
    moved.apply_transform(matrix)  # trimesh flips the faces when the matrix mirrors
    return moved


def transform_value(value: Any, matrix: np.ndarray) -> Any:
    """``value`` moved by the affine ``matrix``; a warning for values that are not geometry.

    Vectors are directions: they take the matrix's linear part and ignore its
    translation. Planes keep their origin's image and the images of their X and Y
    axes, made orthonormal again (X first); a mirrored plane keeps X and Y, so its
    normal is X × Y rather than the mirror image of the old normal.
    """
    if value is None:
        raise NodeWarning("Geometry is empty (null)")
    with kernel_errors():
        if isinstance(value, Vector):
            return vector(apply_to_vectors(matrix, np.asarray(value)))
        if isinstance(value, Point):
            return point(apply_transform(matrix, np.asarray(value)))
        if isinstance(value, Plane):
            return engine_plane(transform_plane(matrix, kernel_plane("Geometry", value)))
        if isinstance(value, Curve | Surface):
            return value.transformed(matrix)
        if isinstance(value, TriangleMesh):
            return _mesh(value, matrix)
        if isinstance(value, MeshSurface):
            return MeshSurface(_mesh(value.mesh, matrix))
    raise NodeWarning(f"Geometry {describe(value)} is not geometry; transforms work on {SUPPORTED}")
