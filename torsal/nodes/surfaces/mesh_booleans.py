"""Mesh Union, Mesh Difference and Mesh Intersection: booleans of closed triangle meshes.

They need the optional manifold3d library (``pip install 'torsal[booleans]'``); without it
each says so and makes nothing. See :mod:`torsal.nodes.geometry.mesh_booleans`.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

from torsal.engine.node import LIST, In, Node, NodeError, NodeWarning, Out
from torsal.nodes.common.values import MESH
from torsal.nodes.geometry.mesh_booleans import engine_missing, mesh_boolean, why_not_closed

#: The most triangles one boolean takes, all its meshes together (a mesh of millions of
#: triangles wired in by mistake is refused, not cut for minutes).
MAX_TRIANGLES = 2_000_000


def _closed(name: str, meshes: Sequence[Any]) -> list[Any]:
    """The meshes of input ``name``, each checked closed (a warning naming the first that is not)."""
    missing = engine_missing()
    if missing:
        raise NodeError(missing[:1].upper() + missing[1:])
    kept = [m for m in meshes if m is not None]
    if not kept:
        raise NodeWarning(f"{name} is empty: give one closed mesh or more")
    for index, mesh in enumerate(kept):
        problem = why_not_closed(mesh)
        if problem:
            where = name if len(kept) == 1 else f"{name} item {index}"
            raise NodeWarning(f"{where} cannot take part in a boolean: {problem}")
    return kept


def _solved(meshes: list[Any], operation: str, second: Sequence[Any] = ()) -> Any:
    triangles = sum(len(m.faces) for m in (*meshes, *second))
    if triangles > MAX_TRIANGLES:
        raise NodeWarning(f"The meshes have {triangles:,} triangles together, more than the "
                          f"{MAX_TRIANGLES:,} one boolean takes: reduce them first")
    result = mesh_boolean(meshes, operation, second)
    if len(result.faces) == 0:
        raise NodeWarning({
            "union": "The union is empty",
            "difference": "Nothing of A is left: B holds all of it",
            "intersection": "A and B do not overlap: their intersection is empty",
        }[operation])
    return result


class MeshUnion(Node):
    """Join closed meshes into one: the space any of them takes.

    Every mesh must be closed (watertight, its triangles wound consistently), as for a 3D
    print; the result is closed too. Overlaps are merged, meshes apart stay apart in one
    mesh. Needs the manifold3d library.
    """

    type_id = "surfaces.MeshUnion"
    nickname, aliases = "MUnion", ("Mesh Union", "boolean union", "Solid Union", "join solids")
    inputs = (In("Meshes", MESH, "M", "The closed meshes to join.", access=LIST),)
    outputs = (Out("Result", MESH, "R", "The union, one closed mesh."),)

    def solve(self, meshes: Sequence[Any]) -> Any:
        return _solved(_closed("Meshes", meshes), "union")


class MeshDifference(Node):
    """Cut closed meshes out of others: what A takes and no mesh of B does.

    A and B may each be several closed meshes (each side is joined first). The result is
    closed; when B holds all of A, nothing is left and the node warns. Needs the manifold3d
    library.
    """

    type_id = "surfaces.MeshDifference"
    nickname, aliases = "MDif", ("Mesh Difference", "boolean difference", "Solid Difference",
                                 "subtract", "cut out")
    inputs = (
        In("A", MESH, "A", "The closed meshes to cut.", access=LIST),
        In("B", MESH, "B", "The closed meshes to cut away.", access=LIST),
    )
    outputs = (Out("Result", MESH, "R", "A less B, one closed mesh."),)

    def solve(self, a: Sequence[Any], b: Sequence[Any]) -> Any:
        return _solved(_closed("A", a), "difference", _closed("B", b))


class MeshIntersection(Node):
    """Keep what closed meshes share: the space taken by A and by B.

    A and B may each be several closed meshes (each side is joined first). When they do
    not overlap the node warns. Needs the manifold3d library.
    """

    type_id = "surfaces.MeshIntersection"
    nickname, aliases = "MInt", ("Mesh Intersection", "boolean intersection", "Solid Intersection",
                                 "common part")
    inputs = (
        In("A", MESH, "A", "The first closed meshes.", access=LIST),
        In("B", MESH, "B", "The closed meshes A is intersected with.", access=LIST),
    )
    outputs = (Out("Result", MESH, "R", "What A and B share, one closed mesh."),)

    def solve(self, a: Sequence[Any], b: Sequence[Any]) -> Any:
        return _solved(_closed("A", a), "intersection", _closed("B", b))
