"""A graph built only with the mouse and keyboard solves the same in `torsal run`."""

from __future__ import annotations

import json
import subprocess
import sys

from PySide6.QtCore import QPoint, QPointF

from tests.support.fixtures_gui import ROOT, drag, place_by_search, port_point, view_point, wait_solved
from torsal.app.gui.canvas.inline_widgets import SliderWidget
from torsal.engine.types import summarize_value


def gui_outputs(window) -> dict:
    """What the GUI shows for every node, in the shape of `torsal run --json` outputs."""
    shown = {}
    for node_id, result in window.doc.results.items():
        shown[node_id] = {
            port: {path: [summarize_value(v) for v in items] for path, items in tree.to_dict().items()}
            for port, tree in result.outputs.items()
        }
    return json.loads(json.dumps(shown))


def test_graph_built_with_search_wires_and_slider_drag_solves_the_same_headless(qtbot, window, tmp_path):
    origin = window.view.mapToScene(window.view.viewport().rect().center()) - QPointF(400, 200)

    def at(x: float, y: float) -> QPointF:
        return origin + QPointF(x, y)

    step = place_by_search(qtbot, window, "number slider", at(0, 0))
    count = place_by_search(qtbot, window, "intsl", at(0, 110))
    series = place_by_search(qtbot, window, "Series", at(280, 20))
    point = place_by_search(qtbot, window, "point", at(480, 20))
    panel = place_by_search(qtbot, window, "panel", at(480, 150))
    graph = window.doc.graph
    assert [graph.nodes[n].type_id for n in (step, count, series, point, panel)] == [
        "params.NumberSlider",
        "params.IntegerSlider",
        "maths.Series",
        "params.Point",
        "params.Panel",
    ]

    for source, out, target, inp in (
        (step, "Value", series, "Step"),
        (count, "Value", series, "Count"),
        (series, "Series", point, "X"),
        (point, "Point", panel, "Input"),
    ):
        drag(window, port_point(window, source, out, False), port_point(window, target, inp, True))
    assert [(w.source, w.target_port) for w in graph.wires] == [
        (step, "Step"),
        (count, "Count"),
        (series, "X"),
        (point, "Input"),
    ]

    # drag the number slider's handle to the right
    item = window.scene.nodes[step]
    slider = item.widget
    assert isinstance(slider, SliderWidget)
    rect = item.layout.widget_rect
    handle = view_point(window, item.mapToScene(QPointF(slider.handle_x(rect), rect.center().y())))
    drag(window, handle, handle + QPoint(45, 0), steps=12)
    wait_solved(qtbot, window)
    value = graph.nodes[step].node.settings["value"]
    assert value > 0.6
    assert window.doc.undo_stack.undoText() == f"Set value of {graph.nodes[step].title}"  # one for the drag

    series_out = window.doc.results[series].outputs["Series"].all_items()
    assert len(series_out) == 5 and series_out[1] == value  # Count 5 (default), Start 0, Step = slider
    assert window.viewport.preview_actor_count() == 1  # the points (the panel is not previewed)

    path = tmp_path / "built.graph"
    assert window.save_as(path)
    assert not window.doc.dirty
    run = subprocess.run(
        [sys.executable, "-m", "torsal.app.cli", "run", str(path), "--json"],
        cwd=ROOT,
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert run.returncode == 0, run.stderr
    headless = {node_id: node["outputs"] for node_id, node in json.loads(run.stdout)["nodes"].items()}
    assert headless == gui_outputs(window)
