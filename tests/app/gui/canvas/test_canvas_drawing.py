"""How the canvas stacks and spaces what it draws: wires above group boxes and nodes, ports
far enough apart to hit."""

from __future__ import annotations

import itertools

from torsal.app.gui.canvas.port_item import HIT_R


def test_wires_draw_above_group_boxes_and_nodes(first_steps):
    scene = first_steps.scene
    lowest_wire = min(w.zValue() for w in scene.wires.values())
    assert lowest_wire > max(g.zValue() for g in scene.groups.values())
    assert lowest_wire > max(n.zValue() for n in scene.nodes.values())


def test_neighbouring_ports_are_at_least_16_px_apart_and_their_targets_do_not_overlap(first_steps):
    for item in first_steps.scene.nodes.values():
        for slots in (item.layout.inputs, item.layout.outputs):
            for a, b in itertools.pairwise(slots):
                gap = abs(b.centre.y() - a.centre.y())
                assert gap >= 16.0, (item.node_id, a.name, b.name, gap)
                assert gap >= 2 * HIT_R


def test_a_wire_does_not_take_the_clicks_of_a_node_it_crosses(first_steps):
    assert all(not w.acceptedMouseButtons() for w in first_steps.scene.wires.values())
