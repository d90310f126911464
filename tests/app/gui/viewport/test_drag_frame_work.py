"""What the GUI does per solve and per mouse move of a slider drag, kept small: tables
and items are redrawn only when what they show changed, and a drag repaints only its
slider (the frame-rate bar itself is in tests/benchmarks/bench_gui.py)."""

from __future__ import annotations

import gc
import itertools
import time

import numpy as np
from PySide6.QtCore import QPoint, QRectF, Qt
from PySide6.QtGui import QImage
from PySide6.QtTest import QTest
from PySide6.QtWidgets import QMenu

from tests.support.fixtures_gui import EXAMPLES, slider_handle, wait_solved
from torsal.app.gui.canvas.node_item import BUSY_WIDGET_INTERVAL_MS
from torsal.app.gui.viewport.datasets import Piece, dataset, move_points

NONE = Qt.KeyboardModifier.NoModifier
LEFT = Qt.MouseButton.LeftButton


def bad_slider(qtbot, window) -> str:
    """A slider whose min is above its max: an error message that does not name its value."""
    node_id = window.editor.add_node("params.NumberSlider", (0.0, 0.0), settings={"min": 2.0, "max": 1.0})
    wait_solved(qtbot, window)
    window._fill_tables()
    return node_id


def kaohsiung_slider(qtbot, window) -> tuple[QPoint, int, int]:
    """Open the Kaohsiung example; where its 'scale' slider's handle and track ends are."""
    assert window.open_file(EXAMPLES / "kaohsiung-stadium.graph", ask=False)
    wait_solved(qtbot, window)
    return slider_handle(window, "scale")


def test_the_message_log_is_not_rebuilt_when_a_solve_says_the_same(qtbot, window):
    node_id = bad_slider(qtbot, window)
    fills, rows = window.log.fills, list(window.log.node_rows)
    window.editor.set_setting(node_id, "value", 1.5)  # solved again: the same error
    wait_solved(qtbot, window)
    window._fill_tables()
    assert window.log.node_rows == rows
    assert window.log.fills == fills
    log = window.log
    extra = (1 if log.hidden_remarks else 0) + len(log.app_messages)
    assert log.topLevelItemCount() == len(log.node_groups()) + extra


def test_the_message_log_is_rebuilt_when_a_solve_says_something_else(qtbot, window):
    node_id = bad_slider(qtbot, window)
    fills = window.log.fills
    window.editor.set_setting(node_id, "min", 0.0)  # now valid: the error is gone
    wait_solved(qtbot, window)
    window._fill_tables()
    assert window.log.fills == fills + 1
    assert not any(row[1] == node_id for row in window.log.node_rows)


def node_image(window, node_id: str) -> QImage:
    """The canvas's pixels where the node is."""
    item = window.scene.nodes[node_id]
    rect = window.view.mapFromScene(item.sceneBoundingRect()).boundingRect()
    return window.view.viewport().grab(rect).toImage()


def pixels(image: QImage) -> np.ndarray:
    """The image's RGB values as integers, ``(height, width, 3)``."""
    image = image.convertToFormat(QImage.Format.Format_RGB888)
    rows = np.frombuffer(image.constBits(), np.uint8).reshape(image.height(), image.bytesPerLine())
    return rows[:, : 3 * image.width()].reshape(image.height(), image.width(), 3).astype(int)


def test_after_a_slider_drag_the_message_log_shows_the_last_solves_messages(qtbot, window):
    start, left, right = kaohsiung_slider(qtbot, window)
    viewport = window.view.viewport()
    solves = []
    window.doc.results_changed.connect(solves.append)
    fills = window.log.fills
    QTest.mousePress(viewport, LEFT, NONE, start)
    x, began = start.x(), time.perf_counter()
    while time.perf_counter() - began < 1.5:
        x = max(left, min(right, x - 3))
        QTest.mouseMove(viewport, QPoint(x, start.y()))
        qtbot.wait(15)
    filled_while_dragging = window.log.fills - fills
    QTest.mouseRelease(viewport, LEFT, NONE, QPoint(x, start.y()))
    wait_solved(qtbot, window)
    qtbot.waitUntil(lambda: not window._tables_timer.isActive(), timeout=3000)
    # the strips' messages say how much of each is closed by flat triangles: they change
    # with every solve, and the log is refilled about once a second while dragging
    assert len(solves) >= 2  # solved while dragging, and after
    assert filled_while_dragging <= 2
    outcome = window.doc.last_outcome
    expected = sorted(
        (m.level.name.lower(), n, m.text) for n, r in outcome.results.items() for m in r.messages
    )
    assert sorted((level, node, text) for level, node, _title, text in window.log.node_rows) == expected
    items = [window.log.topLevelItem(i) for i in range(window.log.topLevelItemCount())]
    shown = []
    for item in items:
        if item.data(0, Qt.ItemDataRole.UserRole):  # a node's row: its messages beneath, or itself
            children = [item.child(k) for k in range(item.childCount())] or [item]
            shown += [child.text(2) for child in children]
    # warnings and errors are listed; remarks only on request (a row says how many are hidden)
    assert sorted(shown) == sorted(text for level, _node, text in expected if level != "remark")


def test_a_node_whose_state_a_solve_leaves_as_it_was_is_not_repainted(qtbot, window):
    assert window.open_file(EXAMPLES / "kaohsiung-stadium.graph", ask=False)
    wait_solved(qtbot, window)
    item = window.scene.nodes["edge_curves"]
    state = item.drawn_state()
    updates = []
    item.update = lambda *args: updates.append(args)  # the item's own repaint requests
    window.editor.set_setting("scale", "value", 0.66)
    wait_solved(qtbot, window)
    assert item.result is window.doc.results["edge_curves"]  # a new result, in the same state
    assert item.drawn_state() == state
    assert updates == []


def test_a_node_whose_state_changes_is_repainted(qtbot, window):
    node_id = bad_slider(qtbot, window)
    item = window.scene.nodes[node_id]
    updates = []
    item.update = lambda *args: updates.append(args)
    window.editor.set_setting(node_id, "min", 0.0)
    wait_solved(qtbot, window)
    assert item.state == "ok"
    assert updates


def test_dragging_a_slider_repaints_only_the_slider_and_draws_the_node_as_a_full_repaint(qtbot, window):
    assert window.open_file(EXAMPLES / "kaohsiung-stadium.graph", ask=False)
    wait_solved(qtbot, window)
    item = window.scene.nodes["scale"]
    exposed: list[QRectF] = []
    paint = type(item).paint

    def recording(painter, option, widget=None):
        exposed.append(QRectF(option.exposedRect))
        paint(item, painter, option, widget)

    item.paint = recording
    start, left, _right = slider_handle(window, "scale")
    viewport = window.view.viewport()
    applied = []  # the drag's values the graph took (each redraws the whole node once)
    window.doc.graph_changed.connect(lambda event: event.node_id == "scale" and applied.append(event))
    QTest.mousePress(viewport, LEFT, NONE, start)
    qtbot.wait(50)
    exposed.clear()
    for step in range(1, 6):
        QTest.mouseMove(viewport, QPoint(max(left, start.x() - 6 * step), start.y()))
        qtbot.wait(20)
    # a move made while a solve runs is drawn once BUSY_WIDGET_INTERVAL_MS has passed since
    # the last drawing: wait for it, so that the picture below shows the last move
    qtbot.wait(2 * BUSY_WIDGET_INTERVAL_MS)
    moved = node_image(window, "scale")
    around = item.layout.widget_rect.adjusted(-2, -2, 2, 2)
    partial = [rect for rect in exposed if around.contains(rect)]
    assert partial
    assert len(exposed) - len(partial) <= len(applied)
    item.update()  # the whole node painted again, as it is
    qtbot.wait(50)
    full = node_image(window, "scale")
    # the same picture, but for antialiased edge pixels a level or two apart (2 measured)
    assert np.abs(pixels(full) - pixels(moved)).max() <= 4
    QTest.mouseRelease(viewport, LEFT, NONE, QPoint(max(left, start.x() - 30), start.y()))
    wait_solved(qtbot, window)


def test_a_sliders_new_value_leaves_its_wires_as_they_were_routed(qtbot, window):
    assert window.open_file(EXAMPLES / "kaohsiung-stadium.graph", ask=False)
    wait_solved(qtbot, window)
    wires = window.scene.wire_items_of("scale")
    assert wires
    rerouted = []
    for wire in wires:
        wire.update_path = lambda wire=wire: rerouted.append(wire)
    window.editor.set_setting("scale", "value", 0.66)
    wait_solved(qtbot, window)
    assert window.scene.nodes["scale"].widget.text() == "0.66"
    assert rerouted == []


def test_a_solve_with_no_node_selected_leaves_the_inspector_as_it_is(qtbot, window, monkeypatch):
    node_id = bad_slider(qtbot, window)
    window.scene.clearSelection()
    qtbot.wait(10)
    fills = []
    monkeypatch.setattr(window.inspector, "_fill", lambda graph: fills.append(graph))
    window.editor.set_setting(node_id, "value", 1.5)
    wait_solved(qtbot, window)
    assert fills == []
    assert window.inspector.ports.topLevelItemCount() == 0
    assert window.inspector.settings.rowCount() == 0


def test_moving_points_writes_into_the_datasets_own_arrays():
    faces = np.array([[0, 1, 2], [1, 3, 2]])
    normals = np.tile([0.0, 0.0, 1.0], (4, 1))
    points = np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0]])
    poly = dataset(Piece("surfaces", points, faces=faces, normals=normals))
    vtk_points, vtk_normals = poly.GetPoints().GetData(), poly.GetPointData().GetNormals()
    tilted = np.column_stack([np.zeros(4), -np.ones(4), np.ones(4)]) / np.sqrt(2)
    raised = points + np.array([0.0, 0.0, 5.0])
    move_points(poly, Piece("surfaces", raised, faces=faces, normals=tilted))
    assert poly.GetPoints().GetData() is vtk_points  # the same VTK arrays, new values
    assert poly.GetPointData().GetNormals() is vtk_normals
    np.testing.assert_array_equal(poly.points, raised)
    np.testing.assert_array_equal(poly.point_data.active_normals, tilted)
    assert poly.bounds[4] == 5.0  # VTK sees the change (the bounds are measured again)


def test_no_full_garbage_collection_runs_while_a_slider_is_dragged_and_they_run_again_after(qtbot, window):
    start, left, _right = kaohsiung_slider(qtbot, window)
    before = gc.get_threshold()
    viewport = window.view.viewport()
    full = []

    def watch(phase, info):
        if phase == "start" and info["generation"] == 2:
            full.append(info)

    QTest.mousePress(viewport, LEFT, NONE, start)
    gc.callbacks.append(watch)
    try:
        for step in range(1, 40):  # each middle collection counts towards a full one (10 by default)
            QTest.mouseMove(viewport, QPoint(max(left, start.x() - 2 * step), start.y()))
            gc.collect(1)
            qtbot.wait(5)
    finally:
        gc.callbacks.remove(watch)
    held = gc.get_threshold()
    QTest.mouseRelease(viewport, LEFT, NONE, QPoint(max(left, start.x() - 80), start.y()))
    wait_solved(qtbot, window)
    assert full == []
    assert held[2] > 10_000 and held[:2] == before[:2]
    assert gc.get_threshold() == before


def test_the_status_bars_solve_time_keeps_its_size_so_the_window_is_not_laid_out_again(qtbot, window):
    node_id = bad_slider(qtbot, window)
    label = window.status.solve_label
    sizes = []
    for value in (1.2, 1.4, 1.6):
        window.editor.set_setting(node_id, "value", value)
        wait_solved(qtbot, window)
        assert label.text().startswith("Solved ")
        sizes.append((label.minimumWidth(), label.maximumWidth()))
        assert label.width() >= label.sizeHint().width()  # the whole text shows
    assert all(low == high for low, high in sizes)  # fixed: a new text asks for no new layout
    assert [low for low, _ in sizes] == sorted(low for low, _ in sizes)  # it only ever grows


def test_a_selected_node_is_shown_once_a_second_while_dragging_and_as_solved_after(qtbot, window):
    start, left, right = kaohsiung_slider(qtbot, window)
    window.scene.select_nodes(["strip"])
    qtbot.wait(20)
    viewport = window.view.viewport()
    refreshes, solves = [], []
    fill = window.inspector._fill
    window.inspector._fill = lambda graph: (refreshes.append(time.perf_counter()), fill(graph))
    window.doc.results_changed.connect(solves.append)
    QTest.mousePress(viewport, LEFT, NONE, start)
    x, began = start.x(), time.perf_counter()
    while time.perf_counter() - began < 1.5:
        x = max(left, min(right, x - 3))
        QTest.mouseMove(viewport, QPoint(x, start.y()))
        qtbot.wait(15)
    during = len(refreshes)
    QTest.mouseRelease(viewport, LEFT, NONE, QPoint(x, start.y()))
    wait_solved(qtbot, window)
    assert window.scene.selected_node_ids() == ["strip"]  # the drag did not change the selection
    assert during <= 2
    seconds = f"{window.doc.results['strip'].seconds * 1000:.2f} ms"
    assert seconds in window.inspector.header.text()  # the last solve's time, after the drag


def test_a_slider_drag_ends_when_a_menu_takes_the_mouse_before_the_release(qtbot, window):
    start, left, _right = kaohsiung_slider(qtbot, window)
    before = gc.get_threshold()
    viewport = window.view.viewport()
    QTest.mousePress(viewport, LEFT, NONE, start)
    for step in range(1, 6):
        QTest.mouseMove(viewport, QPoint(max(left, start.x() - 4 * step), start.y()))
        qtbot.wait(5)
    assert window.editor.dragging
    menu = QMenu(window)  # a popup opens mid-drag and the button is let go over it
    menu.addAction("Something")
    menu.popup(viewport.mapToGlobal(start + QPoint(0, 40)))
    qtbot.waitExposed(menu)
    QTest.mouseRelease(menu, LEFT, NONE, QPoint(5, 5))
    menu.close()
    QTest.mouseMove(viewport, start + QPoint(30, 60))  # back over the canvas, button up
    wait_solved(qtbot, window)
    assert not window.editor.dragging
    assert gc.get_threshold() == before
    assert window.doc.undo_stack.undoText().startswith("Set value of ")  # the drag's one step, closed


def test_while_a_solve_runs_a_dragged_slider_is_drawn_at_most_every_40_ms_and_ends_drawn(qtbot, window):
    """Every mouse move drew the slider again, beside the solve it waited for; now a move
    made while a solve runs is drawn once 40 ms have passed since the last drawing (the
    last move's value), and a move made with no solve running is drawn at once."""
    start, left, _right = kaohsiung_slider(qtbot, window)
    item = window.scene.nodes["scale"]
    around = item.layout.widget_rect.adjusted(-2, -2, 2, 2)
    paints: list[tuple[float, bool]] = []  # (when, a solve in flight) of each drawing of the slider alone
    drawn: list[float] = []  # when the node was drawn at all (a solve's end redraws all of it)
    paint = type(item).paint

    def recording(painter, option, widget=None):
        drawn.append(time.perf_counter())
        if around.contains(QRectF(option.exposedRect)):
            paints.append((time.perf_counter(), window.doc.solves.in_flight()))
        paint(item, painter, option, widget)

    item.paint = recording
    values: list[tuple[float, object]] = []  # (when, value) of each value the drag asked for
    drag_setting = window.editor.drag_setting

    def asking(node_id, name, value, drag_key):
        values.append((time.perf_counter(), value))
        drag_setting(node_id, name, value, drag_key)

    window.editor.drag_setting = asking
    solved: list[float] = []  # when each solve's results arrived
    window.doc.results_changed.connect(lambda _outcome: solved.append(time.perf_counter()))
    viewport = window.view.viewport()
    QTest.mousePress(viewport, LEFT, NONE, start)
    qtbot.wait(50)
    moves = []
    for x in range(start.x() - 3, left, -3):
        QTest.mouseMove(viewport, QPoint(x, start.y()))
        moves.append((time.perf_counter(), window.doc.solves.in_flight()))
        qtbot.wait(5)
    qtbot.wait(2 * BUSY_WIDGET_INTERVAL_MS)
    QTest.mouseRelease(viewport, LEFT, NONE, QPoint(left, start.y()))
    wait_solved(qtbot, window)
    busy_moves = sum(1 for _, busy in moves if busy)
    assert busy_moves >= 10  # most moves came while a solve ran
    busy = [when for when, in_flight in paints if in_flight]
    assert len(busy) < busy_moves / 2
    # Two drawings during one solve are 40 ms apart. One during the next solve may come at
    # once: a move made while no solve runs is drawn at once, and the solve it starts may be
    # under way by the time the drawing is painted. A solve stops running a little before
    # its results arrive (more so on a loaded machine), so both are looked for between two
    # drawings: a results' arrival, or a move that found no solve running.
    idle = [when for when, in_flight in moves if not in_flight]
    gaps = [b - a for a, b in itertools.pairwise(busy) if not any(a < t < b for t in (*solved, *idle))]
    # (a timer's rounding: Qt's coarse timers fire within 5 % of their interval)
    assert np.all(np.array(gaps) >= 0.9 * BUSY_WIDGET_INTERVAL_MS / 1000)  # (none when solves were quick)
    # the last new value was drawn (alone or with the whole node): moves past the track's
    # end ask for no new value
    pairs = zip(values[1:], values[:-1], strict=True)
    changes = [when for (when, value), (_, before) in pairs if value != before]
    last_new = changes[-1] if changes else values[0][0]
    assert drawn[-1] > last_new
