"""Opening a file frames what matters: the whole graph when it reads at 0.6 zoom or more,
otherwise the last (most downstream) previewed node with what feeds it, at a readable zoom."""

from __future__ import annotations

import functools

import pytest
from PySide6.QtWidgets import QApplication

from tests.support.fixtures_gui import EXAMPLES, wait_solved

DRAWN_NOTHING = {"Number", "Integer", "Boolean", "Text", "Domain", "Colour"}


def last_previewed(graph) -> str:
    """The previewed node (geometry output, preview on) furthest downstream; the rightmost of equals."""
    feeds = {n: [w.source for w in graph.wires if w.target == n] for n in graph.nodes}

    @functools.cache
    def depth(node_id: str) -> int:
        return 1 + max((depth(s) for s in feeds[node_id]), default=-1)

    shown = [
        n for n, r in graph.nodes.items()
        if r.preview and r.enabled
        and any(p.preview and p.type.name not in DRAWN_NOTHING for p in r.node.output_ports())
    ]
    return max(shown, key=lambda n: (depth(n), graph.nodes[n].position[0]))


@pytest.mark.parametrize("example", sorted(p.stem for p in EXAMPLES.glob("*.graph")))
def test_opening_an_example_shows_its_last_previewed_node_whole_at_a_readable_zoom(qtbot, window, example):
    assert window.open_file(EXAMPLES / f"{example}.graph", ask=False)
    for _ in range(5):
        QApplication.processEvents()
    view = window.view
    visible = view.mapToScene(view.viewport().rect()).boundingRect()
    last = last_previewed(window.doc.graph)
    assert view.zoom() >= 0.6 - 1e-9
    assert visible.contains(window.scene.nodes[last].sceneBoundingRect()), (example, last)
    wait_solved(qtbot, window)  # the window closes after its results have reached the viewport
