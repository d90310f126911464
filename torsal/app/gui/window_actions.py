"""The main window's menus, actions and keyboard shortcuts."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

from PySide6.QtCore import Qt
from PySide6.QtGui import QAction, QKeySequence
from PySide6.QtWidgets import QMenu, QMessageBox

from torsal.app.gui.hosts import MenuWindow
from torsal.app.gui.write_consent import toggle_writes
from torsal.engine import __version__

CANVAS_ACTIONS = (
    "cut",
    "copy",
    "paste",
    "duplicate",
    "delete",
    "select_all",
    "group",
    "ungroup",
    "cluster",
    "enable",
    "preview",
    "zoom_fit",
)


def build_menus(window: MenuWindow) -> dict[str, QAction]:
    """Create the menu bar; returns the actions by name (tests trigger them)."""
    actions: dict[str, QAction] = {}
    bar = window.menuBar()

    def add(
        menu: QMenu, name: str, text: str, slot: Callable[[], object], shortcut: object = None, tip: str = ""
    ) -> QAction:
        action = QAction(text, window)
        if shortcut is not None:
            action.setShortcut(QKeySequence(shortcut))
        if tip:
            action.setStatusTip(tip)
        action.triggered.connect(lambda _checked=False: slot())
        menu.addAction(action)
        actions[name] = action
        return action

    file_menu = bar.addMenu("&File")
    add(file_menu, "new", "&New", window.new_document, QKeySequence.StandardKey.New)
    add(file_menu, "open", "&Open…", window.open_dialog, QKeySequence.StandardKey.Open)
    recent = file_menu.addMenu("Open &Recent")
    recent.aboutToShow.connect(lambda: _fill_recent(window, recent))
    add(file_menu, "save", "&Save", window.save, QKeySequence.StandardKey.Save)
    add(file_menu, "save_as", "Save &As…", window.save_as, QKeySequence.StandardKey.SaveAs)
    file_menu.addSeparator()
    add(
        file_menu,
        "bake",
        "&Bake to Rhino (.3dm)…",
        window.bake,
        "Ctrl+B",
        "Write the geometry of every previewed node into one .3dm file, one layer per node",
    )
    add(file_menu, "screenshot", "Save Viewport Screenshot…", window.save_viewport_screenshot)
    allow = add(
        file_menu,
        "allow_writes",
        "Allow File &Writes",
        lambda: toggle_writes(window),
        tip="Let this graph's export nodes write their files (inside the graph's folder only)",
    )
    allow.setCheckable(True)
    file_menu.addSeparator()
    add(file_menu, "quit", "&Quit", window.close, QKeySequence.StandardKey.Quit)

    edit = bar.addMenu("&Edit")
    undo = window.doc.undo_group.createUndoAction(window, "&Undo")
    undo.setShortcut(QKeySequence.StandardKey.Undo)
    redo = window.doc.undo_group.createRedoAction(window, "&Redo")
    redo.setShortcuts([QKeySequence.StandardKey.Redo, QKeySequence("Ctrl+Y")])
    edit.addAction(undo)
    edit.addAction(redo)
    actions["undo"], actions["redo"] = undo, redo
    edit.addSeparator()
    add(edit, "cut", "Cu&t", window.cut_selection, QKeySequence.StandardKey.Cut)
    add(edit, "copy", "&Copy", window.copy_selection, QKeySequence.StandardKey.Copy)
    add(edit, "paste", "&Paste", window.paste, QKeySequence.StandardKey.Paste)
    add(edit, "duplicate", "D&uplicate", window.duplicate_selection, "Ctrl+D", "Copy and paste in one go")
    delete = add(edit, "delete", "&Delete", window.delete_selection, QKeySequence.StandardKey.Delete)
    delete.setShortcuts([QKeySequence.StandardKey.Delete, QKeySequence("Backspace")])
    add(edit, "select_all", "Select &All", window.select_all, QKeySequence.StandardKey.SelectAll)
    edit.addSeparator()
    add(edit, "group", "&Group", window.group_selection, "Ctrl+G")
    add(edit, "ungroup", "U&ngroup", window.ungroup_selection, "Ctrl+Shift+G")
    add(edit, "cluster", "Cl&uster", window.scene.cluster_selection, "Ctrl+Alt+G",
        "Collapse the selected nodes into one cluster node")
    align = edit.addMenu("A&lign")
    for how, text in (
        ("left", "Left edges"),
        ("right", "Right edges"),
        ("top", "Top edges"),
        ("bottom", "Bottom edges"),
        ("hcentre", "Centres (horizontally)"),
        ("vcentre", "Centres (vertically)"),
    ):
        add(align, f"align_{how}", text, lambda h=how: window.align_selection(h))
    edit.addSeparator()
    add(edit, "enable", "Enable / Disable", window.toggle_enabled, "Ctrl+E")
    add(edit, "preview", "Preview On / Off", window.toggle_preview, "Ctrl+Shift+P")

    view = bar.addMenu("&View")
    add(view, "zoom_fit", "Zoom Canvas to Fit", window.view.zoom_to_fit, "Home")
    for name, text in (
        ("extents", "Viewport: Zoom Extents"),
        ("top", "Viewport: Top"),
        ("front", "Viewport: Front"),
        ("right", "Viewport: Right"),
        ("perspective", "Viewport: Perspective"),
    ):
        add(view, f"view_{name}", text, lambda n=name: window.viewport.set_view(n))
    view.addSeparator()
    nicknames = QAction("Show &Nicknames Instead of Icons", window, checkable=True,
                        checked=window.settings.show_nicknames())
    nicknames.toggled.connect(window.set_show_nicknames)
    view.addAction(nicknames)
    actions["show_nicknames"] = nicknames
    view.addSeparator()
    for dock in (window.viewport_dock, window.inspector_dock, window.log_dock, window.profiler_dock):
        view.addAction(dock.toggleViewAction())

    solve = bar.addMenu("&Solve")
    add(solve, "solve_now", "Solve &Now", window.doc.solves.solve_now, "F5")
    cancel = add(solve, "cancel_solve", "&Cancel Solve", window.cancel_solve, "Esc")
    cancel.setShortcutContext(Qt.ShortcutContext.WindowShortcut)
    auto = QAction("&Solve After Every Edit", window, checkable=True, checked=True)
    auto.toggled.connect(lambda on: setattr(window.doc.solves, "auto", on))
    solve.addAction(auto)
    actions["auto_solve"] = auto
    solve.addSeparator()
    add(solve, "optimise", "&Optimise…", lambda: _open_optimise_window(window),
        tip="Search sliders for the best value of an output (runs beside the canvas)")

    help_menu = bar.addMenu("&Help")
    add(
        help_menu,
        "about",
        "&About Torsal",
        lambda: QMessageBox.about(
            window,
            "About Torsal",
            f"Torsal {__version__}\n\nDesign with developable surfaces in a node graph.\n\n"
            "Double-click the canvas to add a node; drag from port to port to wire; "
            "Shift adds a wire, Ctrl removes one.",
        ),
    )

    for name in CANVAS_ACTIONS:  # so they also show in the canvas's right-click menu
        actions[name].setShortcutContext(Qt.ShortcutContext.WidgetWithChildrenShortcut)
        window.view.addAction(actions[name])
    return actions


def _fill_recent(window: MenuWindow, menu: QMenu) -> None:
    menu.clear()
    files = window.settings.recent_files()
    for path in files:
        menu.addAction(str(path), lambda p=Path(path): window.open_file(p))
    if not files:
        menu.addAction("(none)").setEnabled(False)


def _open_optimise_window(window: MenuWindow) -> None:
    """Solve ▸ Optimise…: its window and the search it runs are imported on first use,
    not before the app's first frame."""
    from torsal.app.gui.optimise_window import open_optimise_window

    open_optimise_window(window)
