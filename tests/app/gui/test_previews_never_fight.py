"""Previews that never fight, example by example: no two surfaces of different nodes lie on
each other where both are drawn (they would z-fight into streaks) — a colour map may lie
on a surface only when it is drawn offset towards the camera — and a flat development
never lies under the model in plan (the examples lay them side by side)."""

from __future__ import annotations

import numpy as np
import pytest
from vtkmodules.vtkCommonCore import reference

from tests.support.fixtures_gui import EXAMPLES, wait_solved
from torsal.nodes.geometry.mesh_surface import MeshSurface
from torsal.nodes.geometry.surface_base import Surface

SURFACES = ("surfaces", "scalars")


def drawn_surfaces(preview) -> list[tuple[str, str, object, object]]:
    """(node, kind, dataset, actor) of every visible surface actor."""
    out = []
    for node_id, entry in preview.nodes.items():
        for name, piece in entry.pieces.items():
            actor = entry.actors[name]
            if piece.kind in SURFACES and actor.GetVisibility() and entry.datasets[name].n_cells:
                out.append((node_id, piece.kind, entry.datasets[name], actor))
    return out


def offset_towards_camera(actor) -> bool:
    factor, units = reference(0.0), reference(0.0)
    actor.GetMapper().GetRelativeCoincidentTopologyPolygonOffsetParameters(factor, units)
    return float(factor) < 0 and float(units) < 0


def share_on(a, b) -> float:
    """The share of a's cell centres lying on b: within 3e-3 of the two's size, where two
    tessellations of one surface interleave and the depth buffer shows streaks of each
    (the rationalised roof's strips and their bending colours: 100 % at 3e-3)."""
    size = max(np.ptp(np.reshape(d.bounds, (3, 2)), axis=1).max() for d in (a, b))
    centres = a.cell_centers().points
    if len(centres) > 400:
        centres = centres[:: len(centres) // 400]
    _, closest = b.find_closest_cell(centres, return_closest_point=True)
    return float(np.mean(np.linalg.norm(centres - closest, axis=1) <= 3e-3 * size))


@pytest.mark.parametrize("example", sorted(p.stem for p in EXAMPLES.glob("*.graph")))
def test_no_two_previewed_surfaces_coincide_and_developments_lie_beside_the_model(qtbot, window, example):
    assert window.open_file(EXAMPLES / f"{example}.graph", ask=False)
    wait_solved(qtbot, window)
    window.viewport.refresh()
    surfaces = drawn_surfaces(window.viewport.preview)
    for i, (node_a, kind_a, data_a, actor_a) in enumerate(surfaces):
        for node_b, kind_b, data_b, actor_b in surfaces[i + 1:]:
            if node_a == node_b:
                continue
            if (kind_a == "scalars" and offset_towards_camera(actor_a)) or (
                kind_b == "scalars" and offset_towards_camera(actor_b)
            ):
                continue  # a colour map drawn in front of what it lies on
            shared = max(share_on(data_a, data_b), share_on(data_b, data_a))
            assert shared < 0.2, f"{example}: {node_a} and {node_b} lie on each other ({shared:.0%})"
    # a flat sheet (a development, flat panels) never lies under a 3D surface in plan: each
    # drawn output's surfaces boxed on their own (one node may draw both, as PaperStrip does)
    flat, solid = [], []
    for node_id, name, box in output_boxes(window):
        size = np.ptp(box, axis=0).max()
        (flat if np.ptp(box[:, 2]) <= 1e-9 * size else solid).append((f"{node_id}.{name}", box))
    for name_f, f in flat:
        for name_s, s in solid:
            apart = f[1, 0] < s[0, 0] or s[1, 0] < f[0, 0] or f[1, 1] < s[0, 1] or s[1, 1] < f[0, 1]
            assert apart, f"{example}: the flat {name_f} lies under {name_s} in plan"


def output_boxes(window) -> list[tuple[str, str, np.ndarray]]:
    """(node, output, [[xmin, ymin, zmin], [xmax, ymax, zmax]]) of every drawn output that
    holds surfaces, for the nodes whose surfaces are shown."""
    preview = window.viewport.preview
    boxes = []
    for node_id in preview.nodes:
        if node_id in preview.hidden:
            continue
        record, result = window.doc.graph.nodes[node_id], window.doc.results[node_id]
        for name in record.node.previewed_outputs():
            items = [v for v in result.output(name).all_items() if isinstance(v, Surface | MeshSurface)]
            if items:
                corners = np.concatenate([np.asarray(v.bounding_box(), dtype=float) for v in items])
                boxes.append((node_id, name, np.stack([corners.min(axis=0), corners.max(axis=0)])))
    return boxes
