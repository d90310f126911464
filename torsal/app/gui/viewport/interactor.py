"""The 3D viewport's widget and pyvista plotter: VTK's own Qt widget
(``vtkmodules.qt.QVTKRenderWindowInteractor``) with a pyvista :class:`BasePlotter` drawing
into its render window.

pyvistaqt's ``QtInteractor`` is the same pairing in one class. Torsal makes its own
because importing pyvistaqt costs ~0.25 CPU s of the start-up (qtpy, under it,
star-imports every class of QtCore, QtGui and QtWidgets: ~640 enums made), where VTK's
widget imports in ~0.03 s (``tests/benchmarks/bench_startup.py``). What pyvistaqt adds
beyond the pairing (an auto-update timer, file drops, menus) the app does not use.

VTK's widget draws through a native window of its own (VTK makes the OpenGL context on
it), which X11, Windows and macOS give a Qt widget; Wayland does not, and there
:func:`make_plotter` falls back to pyvistaqt's ``QtInteractor``, which draws through a
``QOpenGLWidget``. Either way :func:`make_plotter` returns the pyvista plotter and the Qt
widget that shows it (for pyvistaqt one object).
"""

from __future__ import annotations

from typing import Any

from PySide6.QtGui import QGuiApplication
from PySide6.QtWidgets import QWidget
from pyvista.plotting import BasePlotter, RenderWindowInteractor

#: Qt platforms where a widget's native window can take VTK's OpenGL context
NATIVE_WINDOW_PLATFORMS = frozenset({"xcb", "windows", "cocoa"})


class ViewportPlotter(BasePlotter):
    """pyvista's plotting (meshes, actors, camera, screenshots) on the render window of
    :attr:`widget`, a VTK ``QVTKRenderWindowInteractor`` made as a child of ``parent``.
    Qt drives it: a paint of the widget renders, its mouse and key events go to the
    interactor (rotate, pan and zoom as pyvista's trackball style)."""

    def __init__(self, parent: QWidget, multi_samples: int = 0) -> None:
        from vtkmodules.qt.QVTKRenderWindowInteractor import QVTKRenderWindowInteractor

        super().__init__()
        self.widget = QVTKRenderWindowInteractor(parent)
        self.ren_win = self.widget.GetRenderWindow()
        self.ren_win.SetMultiSamples(multi_samples)
        for renderer in self.renderers:
            renderer.view_isometric()
            self.ren_win.AddRenderer(renderer)
        self.iren = RenderWindowInteractor(self, interactor=self.ren_win.GetInteractor())
        self.iren.initialize()
        self.enable_trackball_style()
        # What a subclass of BasePlotter says once its window is live (pyvista's Plotter
        # does it in show()): render() and screenshot() then draw instead of waiting for show()
        self._first_time = False

    def render(self) -> None:
        """Render now (not waiting for Qt's next paint)."""
        if not getattr(self, "_closed", False):
            super().render()

    def close(self) -> None:
        """Release the render window and its OpenGL context, then the widget (deleted
        on the next event-loop turn: Qt sends it no more events)."""
        if getattr(self, "_closed", False):
            return
        super().close()
        self.widget.close()  # VTK's widget finalizes its render window again: harmless
        self.widget.deleteLater()


def make_plotter(parent: QWidget) -> tuple[Any, QWidget]:
    """A pyvista plotter without multisampling drawing into a new child widget of
    ``parent``, and that widget: a :class:`ViewportPlotter` where the Qt platform gives
    widgets native windows (X11, Windows, macOS), else pyvistaqt's ``QtInteractor``."""
    if QGuiApplication.platformName() in NATIVE_WINDOW_PLATFORMS:
        plotter = ViewportPlotter(parent, multi_samples=0)
        return plotter, plotter.widget
    from pyvistaqt import QtInteractor

    interactor = QtInteractor(parent, auto_update=False, multi_samples=0)
    if interactor.iren is not None:
        interactor.iren.clear_key_event_callbacks()  # no 'q' closing the viewport
    return interactor, interactor
