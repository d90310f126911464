"""The node library's registry: every palette of ``nodes`` plus installed plug-ins.

Each palette package declares its node modules (``NODE_TYPES``) and the modules defining
its value types (``VALUE_TYPES``) in its ``__init__``; :meth:`Registry.discover` finds
them by walking ``nodes``, so adding a palette is adding a package. A module
``nodes.<palette>.<name>`` holds only ``<palette>.*`` node types (a test checks it),
which lets palettes be imported on demand.
"""

from __future__ import annotations

from torsal.engine.registry import Registry

#: The package whose sub-packages are Torsal's palettes.
LIBRARY = "torsal.nodes"


def default_registry(plugins: bool = True) -> Registry:
    """Torsal's own node and value types plus installed plug-ins (``torsal.nodes`` entry points).

    Palettes load lazily: a module ``nodes.<palette>.<name>`` is imported the first time
    a ``<palette>.*`` type is asked for, so ``torsal run`` on a graph of sliders and
    expressions never pays for the geometry libraries.
    """
    registry = Registry()
    registry.discover(LIBRARY)
    if plugins:
        registry.load_entry_points()
    return registry
