"""The binding's lost references to ``None`` (app/gui/qt_compat.py) cannot run out in use.

PySide6 6.12 drops a reference to ``None`` on static void calls and on many ordinary void
methods (``setPen``, ``QRectF.setWidth`` …), so a canvas that keeps repainting loses
references all the time; on CPython 3.11 the process aborts when the count reaches 0.
This measures the loss per repaint of a real window's canvas and holds the reserve to
a century of repainting at 1,000 frames a second (the reserve was once 2**30: about six
days at this rate, two references a frame on the Kaohsiung example).
"""

from __future__ import annotations

import sys

import pytest
from PySide6.QtWidgets import QApplication

from tests.support.fixtures_gui import EXAMPLES, wait_solved
from torsal.app.gui import qt_compat

REPAINTS = 40
SECONDS_PER_CENTURY = 100 * 365.25 * 24 * 3600


def test_nones_reserve_outlasts_a_century_of_continuous_repainting(qtbot, window):
    if not qt_compat.RESERVED:
        pytest.skip("this binding or interpreter keeps None's count itself")
    assert window.open_file(EXAMPLES / "kaohsiung-stadium.graph", ask=False)
    wait_solved(qtbot, window)
    viewport = window.view.viewport()
    before = sys.getrefcount(None)
    for _ in range(REPAINTS):
        viewport.repaint()  # the whole canvas: every node, wire and group painted
        QApplication.processEvents()
    lost_per_frame = max(0, before - sys.getrefcount(None)) / REPAINTS
    assert lost_per_frame > 0, "the binding no longer loses references: qt_compat's reserve can go"
    frames_left = (sys.getrefcount(None) - 1) / lost_per_frame
    assert frames_left / 1000.0 > SECONDS_PER_CENTURY, f"{lost_per_frame:.0f} references lost a frame"
