"""TrueShape nesting in the app: the rows at once, the true-shape sheets when the
background search has found them, the canvas answering meanwhile, Esc keeping the best
(torsal/app/gui/improvements.py, torsal/engine/improve.py)."""

from __future__ import annotations

import json
import time

from PySide6.QtCore import Qt
from PySide6.QtTest import QTest

from tests.app.gui.test_live_solving import watch_event_loop
from tests.support.fixtures_gui import EXAMPLES, copy_fixture, wait_solved
from torsal.nodes.io.formats import cutfiles


def _example(tmp_path, budget: float):  # type: ignore[no-untyped-def]
    """kaohsiung-cut-sheets with Nesting = TrueShape and a small TimeBudget."""
    data = json.loads((EXAMPLES / "kaohsiung-cut-sheets.graph").read_text(encoding="utf-8"))
    (cut,) = [n for n in data["nodes"] if n["id"] == "cut"]
    cut["inputs"]["Nesting"] = {"value": "TrueShape"}
    cut["inputs"]["TimeBudget"] = {"value": budget}
    path = tmp_path / "cut-sheets.graph"
    path.write_text(json.dumps(data), encoding="utf-8")
    return path


def _layout(window):  # type: ignore[no-untyped-def]
    return window.doc.results["cut"].output("Layout").all_items()[0]


def test_rows_at_once_then_the_true_shape_sheets_while_the_canvas_answers(qtbot, window, tmp_path):
    assert window.open_file(_example(tmp_path, 3.0), ask=False)
    wait_solved(qtbot, window, timeout=60000)
    first = _layout(window)
    assert first.nesting == cutfiles.SHELF  # shown at once
    improvements = window.doc.improvements
    assert improvements.running()
    shown = []
    improvements.improved.connect(shown.append)
    watch = watch_event_loop(qtbot, 1000)  # the search runs; the GUI thread never waits for it
    assert max(watch.gaps[1:]) < 500 and len(watch.gaps) > 20
    with qtbot.waitSignal(improvements.improved, timeout=600000):
        pass
    wait_solved(qtbot, window, timeout=60000)
    # the status bar says what happened, not "Solved 1 node in 0.0 ms"
    assert window.status.currentMessage().startswith("Took in the background search's better result")
    better = _layout(window)
    assert better.nesting == cutfiles.TRUE_SHAPE and better.stock_usage > first.stock_usage
    texts = [m.text for m in window.doc.results["cut"].messages]
    assert any(t.startswith("TrueShape nesting") and "% of the stock" in t for t in texts), texts
    (preview,) = window.doc.results["cut"].output("Preview").all_items()
    assert preview.layout is better  # what the viewport draws now
    # each better layout is drawn as the search finds it, then its final one (the sheets are
    # filled one at a time: layouts on the way that take less stock than the rows are few)
    qtbot.waitUntil(lambda: not improvements.running(), timeout=600000)
    wait_solved(qtbot, window, timeout=60000)
    final = _layout(window)
    print(f"\n{len(shown)} layouts shown: rows {first.stock_usage:.1%}, first true-shape "
          f"{better.stock_usage:.1%}, final {final.stock_usage:.1%}")
    assert len(shown) >= 1 and final.stock_usage >= better.stock_usage
    texts = [m.text for m in window.doc.results["cut"].messages]
    assert any(t.startswith("TrueShape nesting: ") for t in texts), texts  # the search has ended
    (preview,) = window.doc.results["cut"].output("Preview").all_items()
    assert preview.layout is final


def test_esc_stops_the_search_and_keeps_its_best(qtbot, window, tmp_path):
    """Esc (a key event on the canvas) while the search runs, a true-shape layout already
    shown: the search ends, and the layout kept is the best shown (a later one being engraved
    when Esc came is abandoned, not waited for)."""
    assert window.open_file(_example(tmp_path, 60.0), ask=False)
    wait_solved(qtbot, window, timeout=60000)
    improvements = window.doc.improvements
    assert improvements.running()
    with qtbot.waitSignal(improvements.improved, timeout=600000):
        pass
    wait_solved(qtbot, window, timeout=60000)
    shown = _layout(window)
    assert shown.nesting == cutfiles.TRUE_SHAPE
    qtbot.wait(300)
    window.view.setFocus()
    pressed = time.perf_counter()
    QTest.keyClick(window.view, Qt.Key.Key_Escape)
    qtbot.waitUntil(lambda: not improvements.running(), timeout=30000)
    print(f"\nthe search stopped {time.perf_counter() - pressed:.2f} s after Esc")
    wait_solved(qtbot, window, timeout=60000)
    layout = _layout(window)
    assert layout.nesting == cutfiles.TRUE_SHAPE and layout.stock_usage >= shown.stock_usage
    assert window.doc.results["cut"].state == "ok"


def _display(viewport, point):  # type: ignore[no-untyped-def]
    """Where the viewport shows model ``point``, as a Qt position in the interactor."""
    from PySide6.QtCore import QPoint

    renderer = viewport.plotter.renderer
    renderer.SetWorldPoint(float(point[0]), float(point[1]), float(point[2]), 1.0)
    renderer.WorldToDisplay()
    x, y, _ = renderer.GetDisplayPoint()
    ratio = viewport.interactor.devicePixelRatioF()
    # VTK counts pixels from the lower left, Qt from the upper left
    return QPoint(round(x / ratio), round((renderer.GetSize()[1] - 1 - y) / ratio))


def test_clicking_a_part_on_the_sheets_highlights_it_and_its_strip_on_the_roof(qtbot, window, tmp_path):
    """A click (QTest, on the interactor) inside a part of the example's sheets highlights
    that part and the 3D strip it was cut from: the highlight spans that strip's bounding
    box on the roof (the surface's tight box, polished by scipy), not the sheets; a click
    on bare sheet clears it."""
    import numpy as np
    import shapely

    from torsal.app.gui.viewport.picking import STRIP_ACTOR

    assert window.open_file(copy_fixture(EXAMPLES / "kaohsiung-cut-sheets.graph", tmp_path), ask=False)
    wait_solved(qtbot, window, timeout=60000)
    window.view.setFocus()  # Esc: the sheets stay as they are (the rows) while the parts are clicked
    QTest.keyClick(window.view, Qt.Key.Key_Escape)
    qtbot.waitUntil(lambda: not window.doc.improvements.running(), timeout=30000)
    wait_solved(qtbot, window, timeout=60000)
    viewport = window.viewport
    qtbot.waitUntil(lambda: viewport.plotter is not None and viewport.frames > 0, timeout=60000)
    strips = window.doc.results["strip"].output("Surface").all_items()
    (preview,) = window.doc.results["cut"].output("Preview").all_items()
    index = len(preview.layout.parts) // 2
    contour = preview.part_polylines()[index][0]
    inside = shapely.Polygon(contour[:, :2]).representative_point()
    QTest.mouseClick(viewport.interactor, Qt.MouseButton.LeftButton, Qt.KeyboardModifier.NoModifier,
                     _display(viewport, (inside.x, inside.y, contour[0, 2])))
    qtbot.waitUntil(lambda: viewport.picker.picked is not None, timeout=5000)
    assert viewport.picker.picked == ("cut", preview.layout.parts[index].id)
    bounds = np.array(viewport.plotter.renderer.actors[STRIP_ACTOR].GetBounds()).reshape(3, 2).T
    box = strips[index].bounding_box()
    size = float(np.ptp(box, axis=0).max())
    print(f"\nhighlight box off the strip's by {np.abs(bounds - box).max() / size:.1e} of its size")
    assert np.allclose(bounds, box, atol=1e-3 * size)
    assert bounds[1, 0] < preview.bounds()[0, 0]  # on the roof, left of the sheets
    corner = preview.sheet_borders()[0][0] + np.array([2.0, 2.0, 0.0]) * preview.scale  # 2 mm into the margin
    QTest.mouseClick(viewport.interactor, Qt.MouseButton.LeftButton, Qt.KeyboardModifier.NoModifier,
                     _display(viewport, corner))
    qtbot.waitUntil(lambda: viewport.picker.picked is None, timeout=5000)
    assert STRIP_ACTOR not in viewport.plotter.renderer.actors
    # the reverse: the middle of a strip the eye sees first along its ray
    from torsal.app.gui.viewport.datasets import collect, pieces

    eye = np.array(viewport.plotter.camera.position)
    triangles = []
    for strip in strips:
        (piece,) = [p for p in pieces(collect([strip])) if p.kind == "surfaces"]
        triangles.append(piece.points[piece.faces])
    for index, strip in enumerate(strips):
        target = np.asarray(strip.point_at(0.5, 0.5), dtype=float).reshape(3)
        if _first_hit(eye, target - eye, triangles) == index:
            break
    else:
        raise AssertionError("the eye sees no strip's middle first")
    QTest.mouseClick(viewport.interactor, Qt.MouseButton.LeftButton, Qt.KeyboardModifier.NoModifier,
                     _display(viewport, target))
    qtbot.waitUntil(lambda: viewport.picker.picked is not None, timeout=5000)
    assert viewport.picker.picked == ("cut", preview.layout.parts[index].id)
    assert STRIP_ACTOR in viewport.plotter.renderer.actors


def _first_hit(origin, direction, meshes):  # type: ignore[no-untyped-def]
    """Which of ``meshes`` (``(m, 3, 3)`` triangles each) the ray meets first (Möller-Trumbore)."""
    import numpy as np

    best, first = np.inf, None
    for k, tri in enumerate(meshes):
        a, b, c = tri[:, 0], tri[:, 1], tri[:, 2]
        e1, e2 = b - a, c - a
        h = np.cross(direction, e2)
        det = np.einsum("ij,ij->i", e1, h)
        ok = np.abs(det) > 1e-12
        f = np.where(ok, 1.0 / np.where(ok, det, 1.0), 0.0)
        s = origin - a
        u = f * np.einsum("ij,ij->i", s, h)
        q = np.cross(s, e1)
        v = f * (q @ direction)
        t = f * np.einsum("ij,ij->i", e2, q)
        hit = ok & (u >= 0) & (v >= 0) & (u + v <= 1) & (t > 0)
        if hit.any() and t[hit].min() < best:
            best, first = float(t[hit].min()), k
    return first
