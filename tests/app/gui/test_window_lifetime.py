"""No Python wrapper outlives the Qt object it stands for when a window is deleted.

A wrapper of an object Qt deleted behind PySide's back stays in PySide's address map until
Python lets go of it; a new Qt object later made at the same address then comes back to
Python as that stale wrapper, of the wrong type. That crashed the GUI suite at random (a
segfault in whichever later window was being built, or "'QOffscreenSurface' object has no
attribute 'addAction'"). The garbage collector is held off here, as it is between its runs.
"""

from __future__ import annotations

import gc
from collections.abc import Iterator

import pytest
import shiboken6
from PySide6.QtCore import QEvent
from PySide6.QtWidgets import QApplication

from tests.support.fixtures_gui import close_window, wait_solved
from torsal.app.gui.main_window import MainWindow


@pytest.fixture
def no_collection() -> Iterator[None]:
    gc.collect()
    gc.disable()
    try:
        yield
    finally:
        gc.enable()


def shown_window(qtbot, registry, folder) -> MainWindow:
    """A window as :func:`make_window` makes one, left out of pytest-qt's list: the test
    deletes it itself (pytest-qt would close it again at teardown)."""
    window = MainWindow(registry=registry, settings_folder=folder)
    window.resize(1500, 920)
    window.show()
    qtbot.waitExposed(window)
    window.start(None, offer_recovery=False)
    wait_solved(qtbot, window)
    return window


def delete(window: MainWindow) -> None:
    window.deleteLater()
    QApplication.sendPostedEvents(None, QEvent.Type.DeferredDelete.value)  # as the event loop would
    QApplication.processEvents()


def test_a_deleted_window_leaves_no_wrapper_of_the_viewports_gl_surface(
    qtbot, registry, config_folder, no_collection
):
    window = shown_window(qtbot, registry, config_folder)
    close_window(window)
    delete(window)
    del window
    # names only: printing a stale wrapper reads freed memory
    names = [type(w).__name__ for w in shiboken6.getAllValidWrappers()]
    assert "QOffscreenSurface" not in names


def test_the_inspectors_plot_area_is_deleted_with_its_window_by_qt(
    qtbot, registry, config_folder, no_collection
):
    window = shown_window(qtbot, registry, config_folder)
    area = window.inspector.plot_area  # not on a tab: no node with a plot is selected
    close_window(window)
    delete(window)
    assert not shiboken6.isValid(area)  # deleted by Qt on this thread, not later by a collection
