"""A palette (nodes/<name>/) imports no other palette: what two palettes share lives in
nodes/common (or the kernel, nodes/geometry), so each can be read, moved or dropped alone."""

from __future__ import annotations

from tests.support.import_graph import import_graph

#: Packages under nodes/ that are not palettes: the shared helpers and the kernel.
SHARED = {"common", "geometry"}


def _palette(module: str) -> str | None:
    parts = module.split(".")
    in_nodes = parts[:2] == ["torsal", "nodes"] and len(parts) > 3
    return parts[2] if in_nodes and parts[2] not in SHARED else None


def test_no_palette_imports_another_palette():
    crossings = sorted(
        f"{module} -> {target}"
        for module, targets in import_graph().items()
        if _palette(module)
        for target in targets
        if _palette(target) not in (None, _palette(module))
    )
    assert crossings == []


def test_a_module_of_a_palette_is_told_from_shared_and_kernel_modules():
    assert _palette("torsal.nodes.analysis.bending") == "analysis"
    assert _palette("torsal.nodes.common.files") is None
    assert _palette("torsal.nodes.geometry.curves.line") is None
    assert _palette("torsal.nodes.limits") is None
