"""A node's preview actors are kept while its values change (issue "Fluid", item 3): a
kind of geometry that comes or goes (the Kaohsiung strips' fold points) adds or removes
only its own actor, and cells that change (rulings added) are replaced in the actor's own
dataset."""

from __future__ import annotations

import numpy as np
from PySide6.QtCore import QPoint, Qt
from PySide6.QtTest import QTest

from tests.support.fixtures_gui import EXAMPLES, downstream_of, slider_handle, wait_solved
from torsal.app.gui.viewport.datasets import Piece, dataset, reshape

#: 'Inward scale' values of the Kaohsiung example: the file's own (no strip folds) and
#: ones near the top of the slider, where some strips fold (its Folds output has points)
PLAIN, FOLDING = 0.72, (0.9, 0.95, 0.85)


def strip_actors(window) -> dict[str, tuple[object, object, int]]:
    """The strip node's actors by name: the actor, its dataset and its point count."""
    entry = window.viewport.preview.nodes["strip"]
    data = entry.datasets
    return {name: (entry.actors[name], data[name], data[name].n_points) for name in entry.names}


def set_scale(qtbot, window, value: float) -> None:
    window.editor.set_setting("scale", "value", value)
    wait_solved(qtbot, window)


def test_fold_points_that_come_and_go_leave_the_strips_other_actors_in_place(qtbot, window):
    assert window.open_file(EXAMPLES / "kaohsiung-stadium.graph", ask=False)
    wait_solved(qtbot, window)
    set_scale(qtbot, window, PLAIN)
    plain = strip_actors(window)
    assert not any(":points:" in name for name in plain)
    for value in FOLDING:
        set_scale(qtbot, window, value)
        folding = strip_actors(window)
        if any(":points:" in name for name in folding):
            break
    assert any(":points:" in name for name in folding), "no 'Inward scale' tried folds a strip any more"
    renderer = window.viewport.plotter.renderer
    for name, (actor, data, _count) in plain.items():
        assert folding[name][0] is actor and folding[name][1] is data  # the same actor and dataset
    (points_name,) = [name for name in folding if ":points:" in name]
    assert renderer.actors[points_name] is folding[points_name][0]
    folds = window.doc.results["strip"].outputs["Folds"].all_items()
    assert folding[points_name][2] == len(folds)

    set_scale(qtbot, window, PLAIN)
    again = strip_actors(window)
    assert set(again) == set(plain) and points_name not in renderer.actors
    for name, (actor, data, count) in plain.items():
        assert again[name][0] is actor and again[name][1] is data and again[name][2] == count


def test_reshaping_a_dataset_gives_it_the_new_points_and_cells():
    lines = Piece("rulings", np.eye(3)[:2], lines=np.array([2, 0, 1]))
    poly = dataset(lines)
    more = np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]])
    reshape(poly, Piece("rulings", more, lines=np.array([2, 0, 1, 2, 2, 3])))
    np.testing.assert_array_equal(poly.points, more)
    assert poly.n_lines == 2 and poly.lines.tolist() == [2, 0, 1, 2, 2, 3]
    poly.points[:] = 0.0  # its arrays are its own: writing them leaves the piece alone
    assert more[1, 0] == 1.0


def test_a_drag_rebuilds_no_actor_and_leaves_nodes_it_does_not_reach_untouched(qtbot, window, monkeypatch):
    """Dragging 'Inward scale' (over its lower half, where no strip folds) makes no actor
    and removes none: the strips, inner rim and edge curves have their points moved in the
    datasets they had, and the base curve, upstream of the slider, is not touched at all."""
    assert window.open_file(EXAMPLES / "kaohsiung-stadium.graph", ask=False)
    wait_solved(qtbot, window)
    preview, plotter = window.viewport.preview, window.viewport.plotter
    reached = downstream_of(window.doc.graph, "scale")
    assert {"inner", "edge_curves", "strip"} <= reached and "base" not in reached
    before = {node: dict(entry.datasets) for node, entry in preview.nodes.items()}
    actors = {node: dict(entry.actors) for node, entry in preview.nodes.items()}
    mtimes = {node: {name: data.GetMTime() for name, data in sets.items()} for node, sets in before.items()}
    made, removed = [], []
    add_mesh, remove_actor = plotter.add_mesh, plotter.remove_actor
    monkeypatch.setattr(plotter, "add_mesh", lambda *a, **k: made.append(k.get("name")) or add_mesh(*a, **k))
    monkeypatch.setattr(
        plotter, "remove_actor", lambda *a, **k: removed.append(a[0]) or remove_actor(*a, **k)
    )
    solves = []
    window.doc.results_changed.connect(solves.append)
    start, left, _right = slider_handle(window, "scale")
    viewport = window.view.viewport()
    QTest.mousePress(viewport, Qt.MouseButton.LeftButton, Qt.KeyboardModifier.NoModifier, start)
    for x in range(start.x(), left, -3):  # down from the file's 0.72 towards 0.4
        QTest.mouseMove(viewport, QPoint(x, start.y()))
        qtbot.wait(15)
    end = QPoint(left, start.y())
    QTest.mouseRelease(viewport, Qt.MouseButton.LeftButton, Qt.KeyboardModifier.NoModifier, end)
    wait_solved(qtbot, window)
    assert len(solves) >= 2
    assert made == [] and removed == []
    for node, entry in preview.nodes.items():
        assert entry.actors == actors[node] and entry.datasets == before[node]  # the same objects
        for name, data in entry.datasets.items():
            assert data is before[node][name]
            moved = data.GetMTime() != mtimes[node][name]
            assert moved == (node in reached), (node, name)
