"""Booleans of closed triangle meshes: union, difference and intersection.

trimesh computes them with the manifold3d library (``trimesh.boolean``, engine
``"manifold"``), an optional dependency (``pip install 'torsal[booleans]'``): without it
:func:`engine_missing` says so and :func:`mesh_boolean` raises :class:`BooleanUnavailable`.
A boolean needs closed meshes (every edge shared by two triangles, consistently wound):
:func:`why_not_closed` says what is wrong with one that is not.

The meshes are moved together so that their common bounding box is centred on the origin
before the boolean, and the result back: meshes at site coordinates (1e6 m) are cut as
at the origin.
"""

from __future__ import annotations

import importlib.util
from collections.abc import Sequence
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    import trimesh

#: The operations, in the words of Grasshopper's Mesh Union, Mesh Difference, Mesh Intersection.
OPERATIONS = ("union", "difference", "intersection")
INSTALL = "pip install 'torsal[booleans]'"


class BooleanUnavailable(RuntimeError):
    """The boolean engine (manifold3d) is not installed."""


def engine_missing() -> str | None:
    """Why booleans cannot be computed here (the engine is not installed), or None."""
    try:
        found = importlib.util.find_spec("manifold3d") is not None
    except (ImportError, ValueError):
        found = False
    return None if found else f"mesh booleans need the manifold3d library, which is not installed ({INSTALL})"


def why_not_closed(mesh: trimesh.Trimesh) -> str | None:
    """Why ``mesh`` is not a closed volume a boolean can use ("it has 4 open edges"), or None."""
    import trimesh

    if len(mesh.faces) == 0:
        return "it has no faces"
    if not np.all(np.isfinite(mesh.vertices)):
        return "it has a vertex with a coordinate that is not a finite number"
    open_edges = len(trimesh.grouping.group_rows(mesh.edges_sorted, require_count=1))
    if open_edges:
        return f"it is not closed: {open_edges} of its edges belong to one triangle only"
    if not mesh.is_watertight:
        return "it is not closed: some of its edges are shared by more than two triangles"
    if not mesh.is_winding_consistent:
        return "its triangles are not wound consistently (some face inwards, some outwards)"
    if not mesh.volume > 0:
        return "it encloses no volume (or faces inwards: flip it)"
    return None


def mesh_boolean(first: Sequence[trimesh.Trimesh], operation: str,
                 second: Sequence[trimesh.Trimesh] = ()) -> trimesh.Trimesh:
    """The ``operation`` of closed meshes: ``"union"`` of ``first``; ``"difference"``, the
    union of ``first`` less the union of ``second``; ``"intersection"``, what the union of
    ``first`` and the union of ``second`` share. An empty mesh when nothing is left."""
    if operation not in OPERATIONS:
        raise ValueError(f"operation must be one of {', '.join(OPERATIONS)}, not {operation!r}")
    missing = engine_missing()
    if missing:
        raise BooleanUnavailable(missing)
    import trimesh

    meshes = [*first, *second]
    corners = np.concatenate([np.asarray(m.bounds, dtype=float) for m in meshes])
    centre = 0.5 * (corners.min(axis=0) + corners.max(axis=0))
    moved = [m.copy() for m in meshes]
    for mesh in moved:
        mesh.apply_translation(-centre)
    a, b = moved[:len(first)], moved[len(first):]

    def union(group: list[trimesh.Trimesh]) -> trimesh.Trimesh:
        if len(group) == 1:
            return group[0]
        return trimesh.boolean.union(group, engine="manifold", check_volume=False)

    if operation == "union":
        result = union(a)
    elif operation == "difference":
        result = trimesh.boolean.difference([union(a), union(b)], engine="manifold", check_volume=False)
    else:
        result = trimesh.boolean.intersection([union(a), union(b)], engine="manifold", check_volume=False)
    result.apply_translation(centre)
    return result


__all__ = ["OPERATIONS", "BooleanUnavailable", "engine_missing", "mesh_boolean", "why_not_closed"]
