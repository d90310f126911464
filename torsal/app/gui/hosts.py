"""What the main window's helpers need of it, as :class:`typing.Protocol` classes.

The helpers that fill the window's menus, export, bake, ask before writing and open the
Optimise… window are handed the window itself (:class:`torsal.app.gui.main_window.MainWindow`
satisfies every protocol here). Each names only the members its helper uses, so a helper
can be read and tested without the window, and the window's module imports the helpers
without the helpers importing it back (no import circle). Every host is also the QWidget
its helper's dialogs are parented to.

This module names the types it mentions only for type checkers and imports none of the
helpers, nor the window.
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Protocol

if TYPE_CHECKING:
    from PySide6.QtGui import QAction
    from PySide6.QtWidgets import QDockWidget, QMenuBar

    from torsal.app.bake import Baked
    from torsal.app.gui.app_settings import AppSettings
    from torsal.app.gui.canvas.scene import CanvasScene
    from torsal.app.gui.canvas.view import CanvasView
    from torsal.app.gui.document import Document
    from torsal.app.gui.message_log import MessageLog
    from torsal.app.gui.viewport.panel import ViewportPanel


class ReportingWindow(Protocol):
    """A window showing one document and a status line (what every helper needs)."""

    doc: Document

    def report(self, text: str, level: str = "info") -> None:
        """Say ``text`` in the status bar and the message log."""


class ExportingWindow(ReportingWindow, Protocol):
    """The window as :mod:`torsal.app.gui.exporting` sees it: it also warns in the log."""

    log: MessageLog


class ConsentWindow(ReportingWindow, Protocol):
    """The window as :mod:`torsal.app.gui.write_consent` sees it. ``actions_by_name`` (the
    menus' actions, holding ``allow_writes``) is looked up with ``hasattr``: it is there
    once the menus are built."""

    actions_by_name: dict[str, QAction]


class OptimiseOwner(Protocol):
    """The window as :mod:`torsal.app.gui.optimise_window` sees it: the document whose
    sliders are searched (the Optimise… window is kept on it, one per main window)."""

    doc: Document


class MenuWindow(ConsentWindow, OptimiseOwner, Protocol):
    """The window as :mod:`torsal.app.gui.window_actions` sees it: every action of its
    menus calls one of these."""

    settings: AppSettings
    scene: CanvasScene
    view: CanvasView
    viewport: ViewportPanel
    viewport_dock: QDockWidget
    inspector_dock: QDockWidget
    log_dock: QDockWidget
    profiler_dock: QDockWidget

    def menuBar(self) -> QMenuBar: ...
    def close(self) -> bool: ...
    def new_document(self) -> bool: ...
    def open_dialog(self) -> bool: ...
    def open_file(self, path: str | Path, ask: bool = True) -> bool: ...
    def save(self) -> bool: ...
    def save_as(self, path: str | Path | None = None) -> bool: ...
    def bake(self) -> Baked | None: ...
    def save_viewport_screenshot(self) -> None: ...
    def cut_selection(self) -> None: ...
    def copy_selection(self) -> bool: ...
    def paste(self) -> list[str]: ...
    def duplicate_selection(self) -> list[str]: ...
    def delete_selection(self) -> None: ...
    def select_all(self) -> None: ...
    def group_selection(self) -> None: ...
    def ungroup_selection(self) -> None: ...
    def align_selection(self, how: str) -> None: ...
    def toggle_enabled(self) -> None: ...
    def toggle_preview(self) -> None: ...
    def set_show_nicknames(self, show: bool) -> None: ...
    def cancel_solve(self) -> None: ...
