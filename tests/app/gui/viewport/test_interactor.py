"""The viewport's plotter and widget (torsal/app/gui/viewport/interactor.py): on X11 (Xvfb)
VTK's own Qt widget with a pyvista plotter drawing in it; mouse events on the widget
reach VTK's interactor, screenshots read what it drew, and closing lets the window go."""

from __future__ import annotations

import numpy as np
from PySide6.QtCore import QPoint, Qt
from PySide6.QtGui import QGuiApplication, QImage
from PySide6.QtTest import QTest
from PySide6.QtWidgets import QApplication
from vtkmodules.qt.QVTKRenderWindowInteractor import QVTKRenderWindowInteractor

from tests.support.fixtures_gui import EXAMPLES, close_window, make_window, wait_solved
from torsal.app.gui.viewport.interactor import NATIVE_WINDOW_PLATFORMS, ViewportPlotter


def test_on_x11_the_viewport_is_vtks_widget_with_a_pyvista_plotter(window):
    viewport = window.viewport
    assert QGuiApplication.platformName() in NATIVE_WINDOW_PLATFORMS
    assert isinstance(viewport.plotter, ViewportPlotter)
    assert isinstance(viewport.interactor, QVTKRenderWindowInteractor)
    assert viewport.plotter.widget is viewport.interactor
    assert viewport.plotter.ren_win is viewport.interactor.GetRenderWindow()
    assert viewport.plotter.ren_win.GetMultiSamples() == 0


def test_a_left_drag_on_the_widget_orbits_the_camera_about_its_focal_point(qtbot, window):
    """A drag by QTest events on the widget turns the camera (trackball style): its
    position moves, its distance to the unchanged focal point stays (a rotation)."""
    assert window.open_file(EXAMPLES / "paper-strip.graph", ask=False)
    wait_solved(qtbot, window)
    viewport = window.viewport
    qtbot.waitUntil(lambda: viewport.frames > 0, timeout=10000)
    camera = viewport.plotter.camera
    eye, focus = np.array(camera.position), np.array(camera.focal_point)
    interactor = viewport.interactor
    centre = QPoint(interactor.width() // 2, interactor.height() // 2)
    QTest.mousePress(interactor, Qt.MouseButton.LeftButton, Qt.KeyboardModifier.NoModifier, centre)
    for step in range(1, 6):
        QTest.mouseMove(interactor, centre + QPoint(20 * step, 5 * step))
    QTest.mouseRelease(interactor, Qt.MouseButton.LeftButton, Qt.KeyboardModifier.NoModifier,
                       centre + QPoint(100, 25))
    moved, still = np.array(camera.position), np.array(camera.focal_point)
    distance = np.linalg.norm(eye - focus)
    assert np.linalg.norm(moved - eye) > 0.05 * distance
    np.testing.assert_allclose(still, focus, atol=1e-9 * distance)
    np.testing.assert_allclose(np.linalg.norm(moved - still), distance, rtol=1e-6)


def test_a_screenshot_has_the_widgets_size_in_pixels_and_shows_the_model(qtbot, window, tmp_path):
    assert window.open_file(EXAMPLES / "paper-strip.graph", ask=False)
    wait_solved(qtbot, window)
    viewport = window.viewport
    image = QImage(str(viewport.screenshot(tmp_path / "viewport.png")))
    ratio = viewport.interactor.devicePixelRatioF()
    assert (image.width(), image.height()) == (round(viewport.interactor.width() * ratio),
                                               round(viewport.interactor.height() * ratio))
    colours = {image.pixel(x, y) for x in range(0, image.width(), 13) for y in range(0, image.height(), 13)}
    assert len(colours) > 50  # the model and its shading, not a blank background


def test_closing_the_plotter_releases_it_and_deletes_its_widget(qtbot, window):
    viewport = window.viewport
    plotter, interactor = viewport.plotter, viewport.interactor
    destroyed = []
    interactor.destroyed.connect(lambda *_: destroyed.append(True))
    viewport.close_plotter()
    assert viewport.plotter is None and viewport.interactor is None
    assert plotter.ren_win is None  # pyvista let its render window go
    qtbot.waitUntil(lambda: bool(destroyed), timeout=5000)
    QApplication.processEvents()
    viewport.close_plotter()  # a second close does nothing


def test_where_qt_gives_no_native_windows_pyvistaqts_interactor_draws_the_viewport(
        qtbot, registry, config_folder, monkeypatch):
    """The fallback (Wayland): pyvistaqt's QtInteractor is both plotter and widget, and the
    viewport draws an example through it as through VTK's widget."""
    from pyvistaqt import QtInteractor

    import torsal.app.gui.viewport.interactor as interactor_module

    monkeypatch.setattr(interactor_module, "NATIVE_WINDOW_PLATFORMS", frozenset())
    window = make_window(qtbot, registry, config_folder)
    try:
        viewport = window.viewport
        assert isinstance(viewport.plotter, QtInteractor) and viewport.interactor is viewport.plotter
        assert window.open_file(EXAMPLES / "paper-strip.graph", ask=False)
        wait_solved(qtbot, window)
        qtbot.waitUntil(lambda: viewport.frames > 0, timeout=10000)
        assert viewport.preview_actor_count() > 0
    finally:
        close_window(window)
