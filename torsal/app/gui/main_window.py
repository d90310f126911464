"""The main window: palette, canvas, docks (viewport, inspector, log, profiler), menus.

It wires the parts together and owns the file operations (New, Open, Save, Save As,
recent files, drag-and-drop of ``.graph`` files, the unsaved-work prompt, autosave
recovery). Every file is read and written by :mod:`torsal.engine.graphfile`.
"""

from __future__ import annotations

import time
from pathlib import Path

from PySide6.QtCore import QBuffer, QByteArray, QIODevice, QMimeData, QPoint, QPointF, Qt, QTimer
from PySide6.QtGui import (
    QAction,
    QCloseEvent,
    QDragEnterEvent,
    QDropEvent,
    QGuiApplication,
    QImage,
    QKeyEvent,
    QPainter,
    QPixmap,
    QTransform,
)
from PySide6.QtWidgets import (
    QDialog,
    QDockWidget,
    QFileDialog,
    QMainWindow,
    QMessageBox,
    QTabBar,
    QTextBrowser,
    QVBoxLayout,
    QWidget,
)

from torsal.app.bake import Baked
from torsal.app.gui.app_settings import AppSettings, config_dir
from torsal.app.gui.autosave import Autosaver, find_recoveries
from torsal.app.gui.canvas.scene import CanvasScene
from torsal.app.gui.canvas.view import CanvasView
from torsal.app.gui.cluster_widgets import Breadcrumb
from torsal.app.gui.collections_policy import FullCollectionsHeld
from torsal.app.gui.document import Document
from torsal.app.gui.editor import Editor
from torsal.app.gui.exporting import bake_previewed, export_output
from torsal.app.gui.fragments import MIME_TYPE, looks_like_fragment
from torsal.app.gui.icons import set_show_nicknames
from torsal.app.gui.inspector import Inspector
from torsal.app.gui.message_log import MessageLog
from torsal.app.gui.palette import Palette
from torsal.app.gui.profiler import Profiler
from torsal.app.gui.qt_compat import defer
from torsal.app.gui.search_popup import SearchPopup
from torsal.app.gui.solve_controller import SolveOutcome
from torsal.app.gui.status import SolveStatus
from torsal.app.gui.viewport.panel import ViewportPanel
from torsal.app.gui.window_actions import build_menus
from torsal.app.gui.write_consent import ask_to_write, sync_action
from torsal.engine.graphfile import GraphFileError
from torsal.engine.registry import Registry
from torsal.engine.write_path import write_file

FILE_FILTER = "Torsal graphs (*.graph);;All files (*)"
#: The message log and profiler are refilled at most this often (ms) while solves stream
#: in, and at most this often while a slider is being dragged.
TABLES_INTERVAL_MS = 200
DRAG_TABLES_INTERVAL_MS = 1000


class MainWindow(QMainWindow):
    """One document in one window."""

    def __init__(self, registry: Registry | None = None, settings_folder: Path | None = None) -> None:
        super().__init__()
        if registry is None:
            from torsal.nodes.catalogue import default_registry

            registry = default_registry()
        self.registry = registry
        self.folder = settings_folder or config_dir()
        self.settings = AppSettings(self.folder)
        set_show_nicknames(self.settings.show_nicknames())
        self.doc = Document(registry, self)
        self.editor = Editor(self.doc, self)
        self.autosaver = Autosaver(self.doc, self.folder, parent=self)
        self.setObjectName("torsalMainWindow")
        self.setAcceptDrops(True)
        self.setDockNestingEnabled(True)
        self.resize(1500, 920)

        # canvas and palette in the middle
        self.scene = CanvasScene(self.doc, self.editor, self)
        self.popup = SearchPopup(registry, self)
        self.view = CanvasView(self.scene, self.popup)
        self.palette = Palette(registry)
        self.palette.place.connect(self.view.place_in_view)
        centre = QWidget()
        layout = QVBoxLayout(centre)
        layout.setContentsMargins(0, 0, 0, 0)
        layout.setSpacing(0)
        layout.addWidget(self.palette)
        self.breadcrumb = Breadcrumb(self.doc)
        layout.addWidget(self.breadcrumb)
        layout.addWidget(self.view, 1)
        self.setCentralWidget(centre)

        # docks
        self.viewport = ViewportPanel(self.doc)
        self.viewport.toolbar.addAction("Screenshot…", self.save_viewport_screenshot)
        self.inspector = Inspector(self.doc, self.editor)
        self.log = MessageLog()
        self.profiler = Profiler()
        self.viewport_dock = self._dock("Viewport", self.viewport, Qt.DockWidgetArea.RightDockWidgetArea)
        self.inspector_dock = self._dock("Inspector", self.inspector, Qt.DockWidgetArea.RightDockWidgetArea)
        self.log_dock = self._dock("Messages", self.log, Qt.DockWidgetArea.BottomDockWidgetArea)
        self.profiler_dock = self._dock("Profiler", self.profiler, Qt.DockWidgetArea.BottomDockWidgetArea)
        self.splitDockWidget(self.viewport_dock, self.inspector_dock, Qt.Orientation.Vertical)
        self.tabifyDockWidget(self.log_dock, self.profiler_dock)
        self.log_dock.raise_()
        self.resizeDocks([self.viewport_dock], [620], Qt.Orientation.Horizontal)
        self.resizeDocks([self.viewport_dock, self.inspector_dock], [560, 300], Qt.Orientation.Vertical)
        self.resizeDocks([self.log_dock], [150], Qt.Orientation.Vertical)
        self.status = SolveStatus()
        self.setStatusBar(self.status)

        # signals
        solves = self.doc.solves
        solves.started.connect(self.status.solve_started)
        solves.progress.connect(self.status.solve_progress)
        self.doc.improvements.progress.connect(self.status.search_progress)
        self.doc.improvements.improved.connect(self._result_taken_in)
        self.doc.results_changed.connect(self._solved)
        self.doc.dirty_changed.connect(lambda _dirty: self._update_title())
        self.doc.path_changed.connect(lambda _path: self._update_title())
        self.doc.path_changed.connect(lambda _path: sync_action(self))
        self.doc.writes_requested.connect(lambda requests: defer(self, lambda: ask_to_write(self, requests)))
        self.scene.selectionChanged.connect(self._selection_changed)
        self.scene.help_requested.connect(self.show_help)
        self.scene.export_requested.connect(self.export_output)
        self.scene.bake_requested.connect(lambda node_ids: bake_previewed(self, node_ids=node_ids))
        self.editor.refused.connect(lambda text: self.report(text, "warning"))
        self.view.escape_pressed.connect(self.cancel_solve)
        self._outer_views: list[tuple[QTransform, QPointF]] = []  # the view outside each open cluster
        self.doc.context_changed.connect(self._context_changed)
        self.log.node_activated.connect(self.focus_node)
        self.profiler.node_activated.connect(self.focus_node)
        self._tables_timer = QTimer(self)
        self._tables_timer.setSingleShot(True)
        self._tables_timer.timeout.connect(self._tables_due)
        self.editor.drag_ended.connect(self._drag_ended)
        # a slider drag's next solve waits for the viewport to draw the last one
        self.editor.frame_due = self.viewport.frame_due
        self.viewport.frame_rendered.connect(self.editor.frame_shown)
        # no full garbage collection (a pause of a frame or two) while a slider is dragged
        self._collections = FullCollectionsHeld()
        self.editor.drag_started.connect(self._collections.hold)
        self.editor.drag_ended.connect(self._collections.release)
        self.destroyed.connect(self._collections.release)
        self._tables_stale = False
        self._log_fitted = -1  # the Messages dock was last fitted to this fill of the log
        self._profiler_stale = False  # the profiler is refilled only while it is shown
        self._attention_pending = False  # a file just opened: show its first troubled node
        self.profiler_dock.visibilityChanged.connect(self._profiler_shown)
        self.actions_by_name: dict[str, QAction] = build_menus(self)
        self._update_title()
        self._help_dialogs: list[QDialog] = []

    def _context_changed(self) -> None:
        """Into a cluster: the canvas shows its definition, framed; back out: the view is
        where it was before going in."""
        depth = len(self.doc.frames)
        if depth > len(self._outer_views):
            centre = self.view.mapToScene(self.view.viewport().rect().center())
            self._outer_views.append((self.view.transform(), centre))
            self.view.resetTransform()
            defer(self, lambda: self.view.zoom_to_fit(readable=True))
            return
        saved = None
        while len(self._outer_views) > depth:
            saved = self._outer_views.pop()
        if saved is not None:
            transform, centre = saved
            self.view.setTransform(transform)
            self.view.centerOn(centre)

    def _dock(self, title: str, widget: QWidget, area: Qt.DockWidgetArea) -> QDockWidget:
        dock = QDockWidget(title, self)
        dock.setObjectName(f"dock:{title}")
        dock.setWidget(widget)
        self.addDockWidget(area, dock)
        return dock

    # -- start-up --------------------------------------------------------------------
    def start(self, path: Path | None = None, offer_recovery: bool = True, palette: bool = True) -> None:
        """After the window is shown: the palette, recovery of a crashed session, the file,
        then the 3D viewport. The file's solve starts at once on the worker thread, so it
        runs while pyvista is imported and VTK set up (a second or more), not after.
        ``palette=False`` leaves the palette's buttons to the caller (``torsal gui`` fills
        them after the first solved frame: :func:`torsal.app.gui.main.launch`)."""
        if palette:
            self.palette.populate()
        for problem in self.registry.problems:  # a broken or refused plug-in (docs/plugins.md)
            self.report(problem[:1].upper() + problem[1:], "warning")
        try:
            if offer_recovery and self.offer_recovery():
                return
            if path is not None:
                self.open_file(path, ask=False)
                if not self.doc.solves.idle():
                    self.doc.solves.solve_now()
            else:
                self.doc.solves.request()
        finally:
            self.viewport.create_plotter()

    def offer_recovery(self) -> bool:
        """Ask whether to restore an autosave a crashed session left; True if restored."""
        recoveries = find_recoveries(self.folder)
        if not recoveries:
            return False
        latest = recoveries[0]
        when = time.strftime("%Y-%m-%d %H:%M", time.localtime(latest.saved_at))
        name = latest.original.name if latest.original else "an untitled graph"
        answer = QMessageBox.question(
            self,
            "Recover unsaved work?",
            f"Torsal did not close properly last time. Unsaved work on {name} was autosaved at {when}.\n\n"
            "Restore it?",
            QMessageBox.StandardButton.Yes | QMessageBox.StandardButton.No,
        )
        restored = False
        if answer == QMessageBox.StandardButton.Yes:
            try:
                from torsal.engine.graphfile import read_graph

                graph = read_graph(latest.graph_path, self.registry)
            except GraphFileError as exc:
                self.error("Cannot recover", f"The autosave could not be read: {exc}")
            else:
                self.doc.replace(graph, latest.original, clean=False)
                self.report(f"Restored unsaved work on {name} from {when}")
                restored = True
        for recovery in recoveries:
            recovery.discard()
        if restored:
            self.autosaver.autosave()
        return restored

    # -- files -----------------------------------------------------------------------
    def maybe_save(self) -> bool:
        """Before the document is replaced or the window closes: True to go ahead."""
        if not self.doc.dirty:
            return True
        answer = QMessageBox.question(
            self,
            "Unsaved changes",
            f"{self.doc.title} has unsaved changes. Save them first?",
            QMessageBox.StandardButton.Save
            | QMessageBox.StandardButton.Discard
            | QMessageBox.StandardButton.Cancel,
        )
        if answer == QMessageBox.StandardButton.Save:
            return self.save()
        return answer == QMessageBox.StandardButton.Discard

    def new_document(self) -> bool:
        if not self.maybe_save():
            return False
        self.doc.new()
        self.autosaver.discard()
        self.log.clear_messages()
        self.view.resetTransform()
        return True

    def open_dialog(self) -> bool:
        start = str(self.doc.path.parent) if self.doc.path else ""
        path, _ = QFileDialog.getOpenFileName(self, "Open graph", start, FILE_FILTER)
        return bool(path) and self.open_file(Path(path))

    def open_file(self, path: str | Path, ask: bool = True) -> bool:
        """Open ``path``; a file that cannot be used leaves the current document untouched."""
        path = Path(path)
        if ask and not self.maybe_save():
            return False
        try:
            self.doc.open(path)
        except GraphFileError as exc:
            self.error("Cannot open graph", f"{path.name} cannot be opened:\n\n{exc}")
            return False
        self.autosaver.discard()
        self.settings.add_recent(path)
        self.log.clear_messages()  # the last document's messages do not belong to this one
        self.report(f"Opened {path}")
        self._attention_pending = True
        self.view.resetTransform()
        defer(self, self.view.frame_opened)
        return True

    def save(self) -> bool:
        if self.doc.path is None:
            return self.save_as()
        return self._write(self.doc.path)

    def save_as(self, path: str | Path | None = None) -> bool:
        if path is None:
            start = str(self.doc.path) if self.doc.path else "untitled.graph"
            chosen, _ = QFileDialog.getSaveFileName(self, "Save graph as", start, FILE_FILTER)
            if not chosen:
                return False
            path = Path(chosen)
            if path.suffix != ".graph":
                path = path.with_suffix(".graph")
        return self._write(Path(path))

    def _write(self, path: Path) -> bool:
        try:
            self.doc.save(path)
        except (GraphFileError, OSError) as exc:
            self.error("Cannot save graph", f"{path.name} was not saved:\n\n{exc}")
            return False
        self.autosaver.discard()
        self.settings.add_recent(path)
        self.report(f"Saved {path}")
        return True

    def export_output(self, node_id: str, port: str) -> list[Path]:
        """Export… one output's current data tree to a file (see :mod:`torsal.app.gui.exporting`)."""
        return export_output(self, node_id, port)

    def bake(self) -> Baked | None:
        """Bake the previewed geometry into one .3dm (see :mod:`torsal.app.bake`); the Baked or None."""
        return bake_previewed(self)

    def dragEnterEvent(self, event: QDragEnterEvent) -> None:
        if any(url.toLocalFile().endswith(".graph") for url in event.mimeData().urls()):
            event.acceptProposedAction()
        else:
            event.ignore()

    def dropEvent(self, event: QDropEvent) -> None:
        files = [url.toLocalFile() for url in event.mimeData().urls() if url.toLocalFile().endswith(".graph")]
        if files:
            event.acceptProposedAction()
            defer(self, lambda: self.open_file(Path(files[0])))

    def closeEvent(self, event: QCloseEvent) -> None:
        if not self.maybe_save():
            event.ignore()
            return
        self.settings.save_window_state(self.saveGeometry(), self.saveState())
        self.scene.blockSignals(True)  # its items go before the window: no selection signals then
        self.doc.close()
        self.autosaver.timer.stop()
        self.autosaver.discard()
        self.viewport.close_plotter()
        event.accept()

    def set_show_nicknames(self, show: bool) -> None:
        """Nicknames on tiles instead of the node icons, in the palette, search and nodes."""
        self.settings.set_show_nicknames(show)
        set_show_nicknames(show)
        self.palette.refresh_icons()
        for item in self.scene.nodes.values():
            item.update()

    # -- messages --------------------------------------------------------------------
    def report(self, text: str, level: str = "info") -> None:
        self.log.add(text, level)
        self.status.showMessage(text, 6000)

    def error(self, title: str, text: str) -> None:
        self.log.add(text.replace("\n\n", " "), "error")
        QMessageBox.critical(self, title, text)

    def _update_title(self) -> None:
        self.setWindowTitle(f"{self.doc.title}[*] — Torsal")
        self.setWindowModified(self.doc.dirty)

    def _show_attention(self, outcome: SolveOutcome) -> None:
        """After an opened file's first solve: when the graph does not all fit at a readable
        zoom, bring the first node with an error or warning (in graph order) into view."""
        if not self._attention_pending or outcome.cancelled:
            return
        self._attention_pending = False
        shown = self.view.mapToScene(self.view.viewport().rect()).boundingRect()
        for node_id in self.doc.graph.nodes:
            result = outcome.results.get(node_id)
            item = self.scene.nodes.get(node_id)
            if result is None or item is None or result.state not in ("error", "warning"):
                continue
            if not shown.contains(item.sceneBoundingRect()):
                self.view.centerOn(item)
            return

    def _result_taken_in(self, node_id: str) -> None:
        record = self.doc.graph.nodes.get(node_id)
        self.status.result_taken_in(record.title if record else node_id)

    def _solved(self, outcome: SolveOutcome) -> None:
        self.status.solve_finished(outcome)
        defer(self, lambda: self._show_attention(outcome))  # after the view has fitted the graph
        if outcome.error:
            self.report(outcome.error, "error")
        # The message log and profiler are tables: refilled at once, then at most ~5 times
        # a second (once a second while a slider is dragged, and again when it is let go),
        # so a slider drag's stream of solves is not slowed by them.
        if self._tables_timer.isActive():
            self._tables_stale = True
        else:
            self._fill_tables_and_wait()

    def _fill_tables_and_wait(self) -> None:
        """Fill the tables now, and not again before the interval is over."""
        self._fill_tables()
        self._tables_timer.start(DRAG_TABLES_INTERVAL_MS if self.editor.dragging else TABLES_INTERVAL_MS)

    def _drag_ended(self) -> None:
        """A slider was let go: the tables show the drag's last solve now, and the solve of
        its last value (if one follows) as soon as it comes."""
        self._tables_timer.stop()
        if self._tables_stale:
            self._fill_tables()

    def _fit_log_dock(self) -> None:
        """Grow the Messages dock until it shows every message (up to ten rows; never shrunk,
        so a dock the user made taller stays so)."""
        self._log_fitted = -1
        if self.log_dock.isFloating() or not self.log_dock.isVisible():
            return
        self._log_fitted = self.log.fills
        wanted = self.log.wanted_height()
        if self.log.viewport().height() < wanted - self.log.header().height() - 6:
            title = self.log_dock.height() - self.log.height()
            tabs = 0  # Qt counts the tab bar of tabified docks in the size asked for
            if self.tabifiedDockWidgets(self.log_dock):
                bars = [
                    bar for bar in self.findChildren(QTabBar)
                    if bar.isVisible() and any(bar.tabText(i) == "Messages" for i in range(bar.count()))
                ]
                tabs = bars[0].height() if bars else 0
            self.resizeDocks([self.log_dock], [wanted + title + tabs], Qt.Orientation.Vertical)

    def _tables_due(self) -> None:
        if self._tables_stale:
            self._fill_tables_and_wait()

    def _fill_tables(self) -> None:
        self._tables_stale = False
        outcome = self.doc.last_outcome
        if outcome is not None:
            self.log.show_solve(outcome, self.doc.graph)
            if self.log.fills != self._log_fitted:
                self._fit_log_dock()
            # a dock behind another's tab counts as visible, but shows nothing
            self._profiler_stale = not self.profiler.isVisible() or self.profiler.visibleRegion().isEmpty()
            if not self._profiler_stale:
                self.profiler.show_solve(outcome, self.doc.graph)

    def _profiler_shown(self, visible: bool) -> None:
        if visible and self._profiler_stale and self.doc.last_outcome is not None:
            self._profiler_stale = False
            self.profiler.show_solve(self.doc.last_outcome, self.doc.graph)

    def _selection_changed(self) -> None:
        ids = self.scene.selected_node_ids()
        self.inspector.show_node(ids[0] if len(ids) == 1 else None)
        self.viewport.set_selected(ids)

    def focus_node(self, node_id: str) -> None:
        item = self.scene.nodes.get(node_id)
        if item is not None:
            self.scene.select_nodes([node_id])
            self.view.centerOn(item)

    def show_help(self, node_id: str) -> None:
        """A non-modal window with the node's help (also shown in the inspector)."""
        self.focus_node(node_id)
        self.inspector.show_node(node_id)
        dialog = QDialog(self)
        record = self.doc.graph.nodes[node_id]
        dialog.setWindowTitle(f"Help — {record.node.display_name()}")
        browser = QTextBrowser()
        browser.setHtml(self.inspector.help.toHtml())
        layout = QVBoxLayout(dialog)
        layout.addWidget(browser)
        dialog.resize(480, 420)
        dialog.show()
        self._help_dialogs = [d for d in self._help_dialogs if d.isVisible()] + [dialog]

    # -- edit commands ---------------------------------------------------------------
    def selected(self) -> list[str]:
        return self.scene.selected_node_ids()

    def copy_selection(self) -> bool:
        ids = self.selected()
        if not ids:
            return False
        text = self.editor.copy(ids)
        mime = QMimeData()
        mime.setData(MIME_TYPE, text.encode("utf-8"))
        mime.setText(text)
        QGuiApplication.clipboard().setMimeData(mime)
        return True

    def cut_selection(self) -> None:
        if self.copy_selection():
            self.editor.delete(self.selected())

    def paste(self) -> list[str]:
        mime = QGuiApplication.clipboard().mimeData()
        if mime is None:
            return []
        text = bytes(mime.data(MIME_TYPE)).decode("utf-8") if mime.hasFormat(MIME_TYPE) else mime.text()
        if not text or not looks_like_fragment(text):
            return []
        cursor = self.view.mapToScene(self.view.mapFromGlobal(QPoint(*self._cursor())))
        inside = self.view.viewport().rect().contains(self.view.mapFromGlobal(QPoint(*self._cursor())))
        try:
            ids = self.editor.paste(text, anchor=(cursor.x(), cursor.y()) if inside else None)
        except GraphFileError as exc:
            self.report(f"Cannot paste: {exc}", "warning")
            return []
        self.scene.select_nodes(ids)
        return ids

    @staticmethod
    def _cursor() -> tuple[int, int]:
        from PySide6.QtGui import QCursor

        pos = QCursor.pos()
        return pos.x(), pos.y()

    def duplicate_selection(self) -> list[str]:
        ids = self.editor.duplicate(self.selected())
        self.scene.select_nodes(ids)
        return ids

    def delete_selection(self) -> None:
        self.editor.delete(self.selected())

    def select_all(self) -> None:
        self.scene.select_nodes(list(self.scene.nodes))

    def group_selection(self) -> None:
        self.editor.group(self.selected())

    def ungroup_selection(self) -> None:
        chosen = set(self.selected())
        for group in list(self.doc.graph.groups):
            if chosen & set(group.nodes):
                self.editor.ungroup(group.id)

    def align_selection(self, how: str) -> None:
        self.editor.align(self.scene.sizes(self.selected()), how)

    def toggle_enabled(self) -> None:
        ids = self.selected()
        if ids:
            self.editor.set_enabled(ids, not all(self.doc.graph.nodes[n].enabled for n in ids))

    def toggle_preview(self) -> None:
        ids = self.selected()
        if ids:
            self.editor.set_preview(ids, not all(self.doc.graph.nodes[n].preview for n in ids))

    def keyPressEvent(self, event: QKeyEvent) -> None:
        if event.key() == Qt.Key.Key_Escape:
            self.cancel_solve()
            event.accept()
            return
        super().keyPressEvent(event)

    def cancel_solve(self) -> None:
        if self.doc.solves.cancel():
            self.status.showMessage("Cancelling the solve…", 3000)
        if self.doc.improvements.stop():  # background searches keep their best (nesting)
            self.status.showMessage("Stopping the background search: its best result so far is kept", 3000)

    # -- screenshots -----------------------------------------------------------------
    def grab_window(self, path: str | Path) -> Path:
        """Save the whole window as a PNG, with the 3D viewport's picture put in its place."""
        path = Path(path)
        pixmap: QPixmap = self.grab()
        plotter, interactor = self.viewport.plotter, self.viewport.interactor
        if plotter is not None and interactor is not None and interactor.isVisible():
            self.viewport.render()
            image = plotter.screenshot(return_img=True)
            height, width = image.shape[:2]
            qimage = QImage(image.tobytes(), width, height, width * 3, QImage.Format.Format_RGB888)
            top_left = interactor.mapTo(self, QPoint(0, 0))
            painter = QPainter(pixmap)
            ratio = pixmap.devicePixelRatio()
            target = qimage.scaled(int(interactor.width() * ratio), int(interactor.height() * ratio))
            painter.drawImage(top_left, target)
            painter.end()
        data = QByteArray()
        buffer = QBuffer(data)
        buffer.open(QIODevice.OpenModeFlag.WriteOnly)
        pixmap.save(buffer, "PNG")
        buffer.close()
        write_file(path, bytes(data.data()))  # the one write path: never through a link
        return path

    def save_viewport_screenshot(self) -> None:
        chosen, _ = QFileDialog.getSaveFileName(
            self, "Save viewport screenshot", "viewport.png", "PNG (*.png)"
        )
        if chosen:
            self.viewport.screenshot(chosen)
            self.report(f"Saved {chosen}")
