"""The node library's table of contents: which modules hold node classes.

``default_registry()`` registers every node class in these modules (each class with a
``type_id``) plus any installed plug-ins from the ``torsal.nodes`` entry-point group.
A module ``nodes.<palette>.<name>`` holds only ``<palette>.*`` node types (a test checks
it), which lets palettes be imported on demand.
"""

from __future__ import annotations

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
    "nodes.surfaces.freeform",
    "nodes.surfaces.primitives",
    "nodes.surfaces.analysis",
    "nodes.surfaces.mesh",
    "nodes.transform.euclidean",
    "nodes.transform.arrays",
    "nodes.display.preview",
    "nodes.display.plot",
    "nodes.developable.ruling_developable",
    "nodes.developable.spline_approximation",
    "nodes.developable.surface_coupling",
    "nodes.developable.cylindrical",
    "nodes.developable.conical",
    "nodes.developable.tangent",
    "nodes.developable.parametric_ruled",
    "nodes.developable.paper_strip",
    "nodes.developable.rationalise",
    "nodes.patching.staggered",
    "nodes.patching.surface_patching",
    "nodes.io.rhino",
    "nodes.io.cutting",
    "nodes.io.meshes",
    "nodes.io.data",
    "nodes.analysis.vectors",
    "nodes.analysis.surface_analysis",
    "nodes.analysis.iso_mapping",
    "nodes.analysis.curve_of_regression",
    "nodes.analysis.curvature_histogram",
    "nodes.analysis.warp_chart",
    "nodes.analysis.bending",
)


def default_registry(plugins: bool = True) -> Registry:
    """Torsal's own node types plus installed plug-ins.

    Palettes load lazily: a module ``nodes.<palette>.<name>`` is imported the first time
    a ``<palette>.*`` type is asked for, so ``torsal run`` on a graph of sliders and
    expressions never pays for the geometry libraries.
    """
    registry = Registry()
    for module_name in MODULES:
        registry.register_lazy(module_name.split(".")[1], module_name)
    if plugins:
        registry.load_entry_points()
    return registry
