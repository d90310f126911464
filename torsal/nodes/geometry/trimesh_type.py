"""trimesh's mesh class, named without importing trimesh.

Importing trimesh imports its voxels (scipy.ndimage), paths (shapely) and texture code
(PIL): 0.12-0.2 CPU s, a tenth of the desktop app's start. Most graphs, the Kaohsiung
flagship among them, never make a mesh, so the kernel imports trimesh inside the
functions that make or read one, and a module that only needs to recognise a mesh
checks ``isinstance(value, TriangleMesh)``: the same answer as
``isinstance(value, trimesh.Trimesh)``, without importing trimesh (until something has
imported it, no value can be a Trimesh).

:class:`TriangleMesh` is an abstract base class with a subclass hook, as
``collections.abc.Sized`` recognises any class with a ``__len__``: ``issubclass`` and
``isinstance`` work, but it is not in a mesh's ``__mro__``, so a lookup by the classes
of a value's MRO does not find it (see :func:`torsal.nodes.common.preview.preview_of`).
"""

from __future__ import annotations

import sys
from abc import ABC


class TriangleMesh(ABC):  # noqa: B024 (no abstract methods: it only recognises trimesh's class)
    """``trimesh.Trimesh`` and its subclasses, recognised once trimesh has been imported."""

    __slots__ = ()

    @classmethod
    def __subclasshook__(cls, other: type) -> bool:
        mesh_class = getattr(sys.modules.get("trimesh"), "Trimesh", None)
        if mesh_class is None:
            return NotImplemented  # trimesh is not imported: no class can be its Trimesh
        return issubclass(other, mesh_class)


__all__ = ["TriangleMesh"]
