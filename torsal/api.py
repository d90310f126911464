"""Torsal's public API for plug-ins: what a node package may import, and what stays put.

Everything a plug-in needs is imported from here, never from ``torsal.engine`` or
``torsal.nodes`` directly (those are Torsal's own layout and may move)::

    from torsal.api import NUMBER, In, Node, Out, checks

    class Wave(Node):
        \"\"\"A sine wave's height at X.\"\"\"

        type_id = "waves.Wave"
        inputs = (In("X", NUMBER, "X", "Where along the wave.", default=0.0),
                  In("Length", NUMBER, "L", "The wave length.", default=1.0))
        outputs = (Out("Height", NUMBER, "H", "sin(2π X / Length)."),)

        def solve(self, x: float, length: float) -> float:
            length = checks.positive("Length", length)
            return math.sin(2 * math.pi * x / length)

The promise (docs/plugins.md says it in full): every name in :data:`__all__` keeps its
meaning and call signature within a major version of Torsal; a name is removed or changed
only in a new major version, after a minor version in which using it warns. Anything else
of ``torsal`` may change in any release.

What is here:

- the node: :class:`Node`, its ports :class:`In` and :class:`Out`, their access ``ITEM``,
  ``LIST`` and ``TREE``, :class:`Setting` (a value a node keeps in the file),
  :class:`NodeError` and :class:`NodeWarning` (stop with a message), :class:`DataTree`;
- the value types: ``GENERIC``, ``NUMBER``, ``INTEGER``, ``BOOLEAN``, ``TEXT``, ``POINT``,
  ``VECTOR``, ``DOMAIN``, ``PLANE`` and the geometry's ``CURVE``, ``LINE``, ``SURFACE``,
  ``MESH``, ``MESH_SURFACE``, ``DEVELOPMENT``; :class:`ValueType` and :func:`register_cast`
  to add one; the values :class:`Point`, :class:`Vector`, :class:`Domain`, :class:`Plane`;
- the input checks: :mod:`checks` (numbers, counts, angles, points: the one wording of
  every refusal) and :mod:`geometry_checks` (curves and surfaces);
- the preview protocol: :class:`PreviewGeometry` and :class:`PreviewMesh` (geometry as
  plain arrays), :class:`Previewable` (a class offering ``preview_geometry()``) and
  :func:`register_preview` (an adapter for a class you do not own).

The geometry names load Torsal's geometry kernel (numpy, scipy, trimesh) when first used,
so a plug-in of number nodes that imports this module stays as quick to load as Torsal's
own sliders.
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

from torsal.engine.datatree import DataTree
from torsal.engine.node import ITEM, LIST, TREE, In, Node, NodeError, NodeWarning, Out, Setting
from torsal.engine.types import (
    BOOLEAN,
    DOMAIN,
    GENERIC,
    INTEGER,
    NUMBER,
    PLANE,
    POINT,
    TEXT,
    VECTOR,
    ValueType,
    register_cast,
)
from torsal.engine.values import Domain, Plane, Point, Vector

if TYPE_CHECKING:  # the names loaded on first use, for type checkers and readers
    from torsal.nodes.common import checks, geometry_checks
    from torsal.nodes.common.preview import Previewable, PreviewGeometry, PreviewMesh, register_preview
    from torsal.nodes.common.values import CURVE, DEVELOPMENT, LINE, MESH, MESH_SURFACE, SURFACE

#: Names loaded when first asked for: name → (module, attribute or None for the module itself).
_LAZY: dict[str, tuple[str, str | None]] = {
    "checks": ("torsal.nodes.common.checks", None),
    "geometry_checks": ("torsal.nodes.common.geometry_checks", None),
    **{name: ("torsal.nodes.common.preview", name)
       for name in ("PreviewGeometry", "PreviewMesh", "Previewable", "register_preview")},
    **{name: ("torsal.nodes.common.values", name)
       for name in ("CURVE", "LINE", "SURFACE", "MESH", "MESH_SURFACE", "DEVELOPMENT")},
}

__all__ = [
    "BOOLEAN", "CURVE", "DEVELOPMENT", "DOMAIN", "GENERIC", "INTEGER", "ITEM", "LINE", "LIST", "MESH",
    "MESH_SURFACE", "NUMBER", "PLANE", "POINT", "SURFACE", "TEXT", "TREE", "VECTOR",
    "DataTree", "Domain", "In", "Node", "NodeError", "NodeWarning", "Out", "Plane", "Point",
    "PreviewGeometry", "PreviewMesh", "Previewable", "Setting", "ValueType", "Vector",
    "checks", "geometry_checks", "register_cast", "register_preview",
]


def __getattr__(name: str) -> Any:
    """Load a geometry name (or a checks module) the first time it is asked for."""
    if name not in _LAZY:
        raise AttributeError(f"module 'torsal.api' has no attribute {name!r}")
    module_name, attribute = _LAZY[name]
    module = importlib.import_module(module_name)
    value = module if attribute is None else getattr(module, attribute)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__))
