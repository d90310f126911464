"""The node library's table of contents: which modules hold node classes.

``default_registry()`` registers every node class in these modules (each class with a
``type_id``) plus any installed plug-ins from the ``torsal.nodes`` entry-point group.
Modules are imported on demand, so a headless run pays only for what it loads.
"""

from __future__ import annotations

import importlib

from engine.registry import Registry

MODULES: tuple[str, ...] = (
    "nodes.params.sliders",
    "nodes.params.panel",
    "nodes.params.value_list",
    "nodes.params.points",
    "nodes.params.vectors",
    "nodes.maths.expression",
    "nodes.maths.sequences",
    "nodes.maths.domains",
    "nodes.maths.random_numbers",
    "nodes.lists.items",
    "nodes.lists.ordering",
    "nodes.lists.culling",
    "nodes.lists.trees",
    "nodes.curves.primitives",
    "nodes.curves.splines",
    "nodes.curves.analysis",
    "nodes.curves.offset",
    "nodes.transform.euclidean",
    "nodes.transform.arrays",
    "nodes.display.preview",
    "nodes.display.plot",
)


def default_registry(plugins: bool = True) -> Registry:
    """Torsal's own node types plus installed plug-ins."""
    importlib.import_module("nodes.types")  # geometry value types, before any node uses them
    registry = Registry()
    for module_name in MODULES:
        registry.register_module(importlib.import_module(module_name))
    if plugins:
        registry.load_entry_points()
    return registry
