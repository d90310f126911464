"""The viewport panel: a pyvista plotter in a Qt widget (:mod:`torsal.app.gui.viewport.interactor`)
with view buttons, fed by solve results.

pyvista and VTK take a second or two to import, so the interactor is created after the
main window is first shown (:meth:`ViewportPanel.create_plotter`); until then a
placeholder stands in its place.
"""

from __future__ import annotations

import time
from pathlib import Path
from typing import Any

import numpy as np
from PySide6.QtCore import Qt, QTimer, Signal
from PySide6.QtGui import QAction
from PySide6.QtWidgets import QLabel, QStackedLayout, QToolBar, QVBoxLayout, QWidget

from torsal.app.gui import theme
from torsal.app.gui.document import Document
from torsal.app.gui.solve_controller import SolveOutcome
from torsal.engine.events import PREVIEW_CHANGED
from torsal.engine.graph import GraphEvent
from torsal.engine.solver import Solver, SolveReport

REPREVIEW_EVENTS = PREVIEW_CHANGED
#: A frame asked for longer ago than this (seconds) is no longer waited for by
#: :meth:`ViewportPanel.frame_due` (a window that does not paint: minimised, covered).
FRAME_DUE_LIMIT = 0.25


class ViewportPanel(QWidget):
    """The 3D preview of every node with preview on; the selected nodes are highlighted."""

    frame_rendered = Signal()
    plotter_created = Signal()  # pyvista and VTK set up (start-up is timed by it)

    def __init__(self, doc: Document, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.doc = doc
        self.plotter: Any = None  #: pyvista's plotter (viewport/interactor.py: make_plotter)
        self.interactor: QWidget | None = None  #: the Qt widget it draws in (mouse events go there)
        self.preview: Any = None
        self.picker: Any = None  #: highlights a cut-sheet part clicked and its strip (viewport/picking.py)
        self.frames = 0
        self.render_seconds = 0.0
        self._fit_pending = True
        self._auto_camera: np.ndarray | None = None  # the camera as the app last framed it
        self._hint_shown = False
        self._grid_bounds: tuple[float, ...] | None = None
        self._selected: set[str] = set()
        self._render_began = 0.0
        self._render_asked: float | None = None  # when a render was asked for, until it is done
        outer = QVBoxLayout(self)
        outer.setContentsMargins(0, 0, 0, 0)
        outer.setSpacing(0)
        self.toolbar = QToolBar("Viewport")
        self.toolbar.setIconSize(self.toolbar.iconSize() * 0.8)
        outer.addWidget(self.toolbar)
        self.stack = QStackedLayout()
        outer.addLayout(self.stack, 1)
        self.placeholder = QLabel("Starting the 3D viewport…")
        self.placeholder.setAlignment(Qt.AlignmentFlag.AlignCenter)
        self.placeholder.setStyleSheet(f"background: {theme.VIEWPORT_BACKGROUND}; color: #666;")
        self.stack.addWidget(self.placeholder)
        self.actions_by_name: dict[str, QAction] = {}
        for name, text, tip in (
            ("extents", "Zoom extents", "Fit everything in view"),
            ("top", "Top", "Look down the Z axis (parallel)"),
            ("front", "Front", "Look along the Y axis (parallel)"),
            ("right", "Right", "Look along the X axis (parallel)"),
            ("perspective", "Perspective", "Isometric perspective view"),
        ):
            action = self.toolbar.addAction(text, lambda n=name: self.set_view(n))
            action.setToolTip(tip)
            self.actions_by_name[name] = action
        self.toolbar.setEnabled(False)
        doc.results_changed.connect(self._on_results)
        doc.solves.partial.connect(self._on_partial)
        doc.graph_changed.connect(self._on_graph_event)
        doc.graph_replaced.connect(self._on_replaced)
        doc.context_changed.connect(self._on_context)  # a cluster entered or left: the model outside, dimmed
        # an edit of many nodes (deleting 1,000) refreshes once, when its undo command has
        # run (or on the next event-loop turn for an edit made outside the undo stack)
        self._refresh_due = False
        self._refresh_timer = QTimer(self)
        self._refresh_timer.setSingleShot(True)
        self._refresh_timer.setInterval(0)
        self._refresh_timer.timeout.connect(self._refresh_if_due)
        doc.undo_group.indexChanged.connect(lambda _index: self._refresh_if_due())

    # -- creation --------------------------------------------------------------------
    def create_plotter(self) -> None:
        """Import pyvista and make the plotter and its widget (once)."""
        if self.plotter is not None:
            return
        import pyvista as pv

        from torsal.app.gui.viewport.interactor import make_plotter
        from torsal.app.gui.viewport.picking import PartPicker
        from torsal.app.gui.viewport.preview import Preview

        pv.global_theme.allow_empty_mesh = True
        # The interactor draws in a native window (VTK's widget) or is a QOpenGLWidget
        # (pyvistaqt's, on Wayland): in the second case Qt would compose its whole native
        # window through OpenGL on every repaint of anything in it (~35 ms a time with
        # software GL). In a native child window of its own, the rest of the main window
        # repaints as plain raster (~1 ms) and only the viewport pays for GL; VTK's widget
        # makes its own native window there without making its ancestors native.
        holder = QWidget(self)
        holder.setAttribute(Qt.WidgetAttribute.WA_DontCreateNativeAncestors)
        holder.setAttribute(Qt.WidgetAttribute.WA_NativeWindow)
        layout = QVBoxLayout(holder)
        layout.setContentsMargins(0, 0, 0, 0)
        # No multisampling and no FXAA: with software OpenGL (Mesa llvmpipe, Xvfb) they cost
        # 25-50 ms a frame, more than everything else together.
        plotter, interactor = make_plotter(holder)
        layout.addWidget(interactor)
        interactor.setAcceptDrops(False)  # a dropped .graph goes to the main window
        plotter.set_background(theme.VIEWPORT_BACKGROUND, top=theme.VIEWPORT_BACKGROUND_TOP)
        plotter.add_axes(interactive=False)
        plotter.ren_win.AddObserver("StartEvent", self._render_started)
        plotter.ren_win.AddObserver("EndEvent", self._render_ended)
        self.plotter = plotter
        self.interactor = interactor
        self.preview = Preview(plotter)
        self.picker = PartPicker(plotter, self._sheet_previews, self.schedule_render)
        self.doc.solves.prepare = self._prepare
        self.stack.addWidget(holder)
        self.stack.setCurrentWidget(holder)
        self.toolbar.setEnabled(True)
        self._update_grid()
        self.refresh()
        self.plotter_created.emit()

    def close_plotter(self) -> None:
        if self.plotter is not None:
            self.plotter.close()
            # pyvistaqt keeps Python wrappers of its GL context's QOffscreenSurface, which Qt
            # deletes with the widget without PySide knowing. Until the interactor was garbage
            # collected, a new Qt object at that address came back to Python as that stale
            # wrapper (a segfault or "'QOffscreenSurface' object has no attribute ..." later).
            forget = getattr(self.plotter, "_forget_context", None)
            if forget is not None:
                forget()
            self.plotter = None
            self.interactor = None
            self.picker = None

    # -- updates ---------------------------------------------------------------------
    def _on_graph_event(self, event: GraphEvent) -> None:
        if isinstance(event, REPREVIEW_EVENTS):
            self._refresh_due = True
            self._refresh_timer.start()

    def _refresh_if_due(self) -> None:
        if self._refresh_due:
            self._refresh_due = False
            self._refresh_timer.stop()
            self.refresh()

    def _on_replaced(self) -> None:
        self._fit_pending = True
        self._grid_bounds = None
        if self.preview is not None:
            self.preview.clear()
            self.refresh()

    def _on_context(self) -> None:
        if self.plotter is not None:
            from torsal.app.gui.viewport.outside import show_outside

            show_outside(self.plotter, self.doc)
            self.schedule_render()

    def _on_results(self, outcome: SolveOutcome) -> None:
        self.refresh(outcome.prepared)

    def _on_partial(self, outcome: SolveOutcome) -> None:
        """A long solve's nodes solved so far: show them now (the rest follow)."""
        if self.preview is not None and self.preview.update(
            self.doc.graph, outcome.results, outcome.prepared
        ):
            self._frame_or_follow()
            self.schedule_render()

    def _prepare(self, solver: Solver, report: SolveReport) -> object:
        """On the solver's thread: the meshes of the nodes just solved."""
        from torsal.app.gui.viewport.preview import prepare_solved

        return prepare_solved(solver.graph, solver.results, report.solved)

    def refresh(self, prepared: object = None) -> None:
        """Bring the actors up to date with the latest results; render on the next event-loop turn."""
        if self.preview is None:
            return
        changed = self.preview.update(self.doc.graph, self.doc.results, prepared)
        self.preview.set_selected(self._selected & set(self.preview.nodes))
        if changed and self.picker is not None and self.picker.picked is not None:
            self.picker.show()  # the part in the new layout (a better nesting), by its ID
        has_geometry = bool(self.preview.actor_names())
        if has_geometry:
            changed = self._frame_or_follow() or changed
        if has_geometry or self.doc.solves.idle():  # not "nothing to preview" while results are due
            changed = self._update_hint(has_geometry) or changed
        if changed or not self.frames:
            self.schedule_render()

    def _sheet_previews(self) -> list:
        from torsal.app.gui.viewport.picking import sheet_previews
        from torsal.app.gui.viewport.preview import previewed

        return sheet_previews(self.doc.results, previewed(self.doc.graph, self.doc.results))

    def _frame_or_follow(self) -> bool:
        """A newly opened graph is framed once it shows geometry; later, geometry that leaves
        the view is followed (zoom extents) unless the user has moved the camera since the
        app last framed it. True if the camera moved."""
        if self.preview is None or self.preview.bounds() is None:
            return False
        if self._fit_pending:
            self._fit_pending = False
            self.set_view("perspective", render=False)
            return True
        if self.user_moved_camera() or self.bounds_in_view():
            return False
        self.zoom_extents()
        return True

    def _camera_state(self) -> np.ndarray:
        camera = self.plotter.renderer.GetActiveCamera()
        return np.array(
            [*camera.GetPosition(), *camera.GetFocalPoint(), *camera.GetViewUp(),
             camera.GetParallelScale(), camera.GetViewAngle(), float(camera.GetParallelProjection())]
        )

    def user_moved_camera(self) -> bool:
        """Whether the camera differs from where the app last put it (the user orbited,
        panned or zoomed since)."""
        if self._auto_camera is None or self.plotter is None:
            return False
        state = self._camera_state()
        scale = float(np.max(np.abs(self._auto_camera[:6]))) or 1.0
        return not np.allclose(state, self._auto_camera, rtol=1e-6, atol=1e-9 * scale)

    def bounds_in_view(self) -> bool:
        """Whether every corner of the previewed geometry's bounding box is inside the view."""
        bounds = self.preview.bounds() if self.preview is not None else None
        if bounds is None or self.plotter is None:
            return True
        renderer = self.plotter.renderer
        width, height = renderer.GetSize()
        if width <= 0 or height <= 0:
            return True
        for x in bounds[:, 0]:
            for y in bounds[:, 1]:
                for z in bounds[:, 2]:
                    renderer.SetWorldPoint(float(x), float(y), float(z), 1.0)
                    renderer.WorldToDisplay()
                    dx, dy, dz = renderer.GetDisplayPoint()
                    if not (0 <= dx <= width and 0 <= dy <= height and 0 <= dz <= 1):
                        return False
        return True

    def set_selected(self, node_ids: list[str]) -> None:
        self._selected = set(node_ids)
        if self.preview is not None:
            self.preview.set_selected(self._selected & set(self.preview.nodes))
            self.schedule_render()

    def schedule_render(self) -> None:
        """Repaint once on the next event-loop turn, however many updates come before it.

        The interactor renders VTK in its paint; asking Qt to repaint
        renders once, where calling ``plotter.render()`` would render, then paint (and
        render) again.
        """
        if self.interactor is not None:
            if self._render_asked is None and self.interactor.isVisible():
                self._render_asked = time.perf_counter()
            self.interactor.update()

    def frame_due(self) -> bool:
        """Whether a render has been asked for and not yet done (for at most
        :data:`FRAME_DUE_LIMIT`): what the viewport shows is behind the results."""
        asked = self._render_asked
        return asked is not None and time.perf_counter() - asked < FRAME_DUE_LIMIT

    def render(self) -> None:
        """Render now (a screenshot needs the picture at once)."""
        if self.plotter is not None:
            self.plotter.render()

    def _render_started(self, *_args: object) -> None:
        self._render_began = time.perf_counter()

    def _render_ended(self, *_args: object) -> None:
        """Count finished renders (the slider-drag rate measurement reads :attr:`frames`)."""
        self.render_seconds = time.perf_counter() - self._render_began
        self._render_asked = None
        self.frames += 1
        self.frame_rendered.emit()

    def _update_hint(self, has_geometry: bool) -> bool:
        """Show or hide the "nothing to preview" note; True if that changed the picture
        (the caller renders)."""
        if has_geometry == (not self._hint_shown):
            return False
        if has_geometry:
            self.plotter.remove_actor("decor:hint", render=False)
        else:
            self.plotter.add_text(
                "Nothing to preview: no node with preview on makes geometry",
                position="lower_left",
                font_size=8,
                color="#777777",
                name="decor:hint",
                render=False,
            )
        self._hint_shown = not has_geometry
        return True

    def _update_grid(self) -> None:
        """A ground grid around what is shown (rebuilt only when the extent changes much)."""
        from torsal.app.gui.viewport.preview import ground_grid

        bounds = self.preview.bounds() if self.preview is not None else None
        key = None if bounds is None else tuple(round(float(v), 1) for v in bounds.ravel())
        if key == self._grid_bounds and self.plotter.renderer.actors.get("decor:grid") is not None:
            return
        self._grid_bounds = key
        self.plotter.add_mesh(
            ground_grid(bounds),
            name="decor:grid",
            color=theme.VIEWPORT_GRID,
            line_width=1,
            pickable=False,
            reset_camera=False,
            render=False,
        )

    # -- views -----------------------------------------------------------------------
    def set_view(self, name: str, render: bool = True) -> None:
        """``extents``, ``top``, ``front``, ``right`` or ``perspective``."""
        if self.plotter is None:
            return
        renderer = self.plotter.renderer  # the renderer's methods do not render by themselves
        self._update_grid()
        if name in ("top", "front", "right"):
            renderer.enable_parallel_projection()
            {"top": renderer.view_xy, "front": renderer.view_xz, "right": renderer.view_yz}[name](
                render=False
            )
        elif name == "perspective":
            renderer.disable_parallel_projection()
            renderer.view_isometric(render=False)
        self.zoom_extents()
        if render:
            self.schedule_render()

    def zoom_extents(self) -> None:
        bounds = self.preview.bounds() if self.preview is not None else None
        if bounds is None:
            self.plotter.renderer.reset_camera(render=False)
        else:
            (x0, y0, z0), (x1, y1, z1) = bounds
            self.plotter.renderer.reset_camera(render=False, bounds=(x0, x1, y0, y1, z0, z1))
        self._auto_camera = self._camera_state()

    def screenshot(self, path: str | Path) -> Path:
        """Save what the viewport shows as a PNG."""
        path = Path(path)
        self.render()
        self.plotter.screenshot(str(path))
        return path

    def preview_actor_count(self) -> int:
        """How many preview actors are in the renderer (grid, axes and hints excluded)."""
        if self.plotter is None:
            return 0
        from torsal.app.gui.viewport.preview import PREFIX

        return sum(1 for name in self.plotter.renderer.actors if str(name).startswith(PREFIX))
