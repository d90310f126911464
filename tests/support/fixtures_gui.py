"""Fixtures and helpers for the GUI tests (imported by conftest when Qt is available)."""

from __future__ import annotations

import shutil
from collections.abc import Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, ClassVar

import pytest
from PySide6.QtCore import QPoint, QPointF, Qt, QTimer
from PySide6.QtTest import QTest
from PySide6.QtWidgets import QApplication, QMenu, QMessageBox

from tests.support.showcase_nodes import showcase_registry
from torsal.app.gui.main_window import MainWindow
from torsal.engine.registry import Registry

ROOT = Path(__file__).resolve().parents[2]
HERE = ROOT / "tests" / "app" / "gui"  # the GUI tests' folder: their fixtures and screenshots
EXAMPLES = ROOT / "torsal" / "resources" / "examples"
FIXTURES = HERE / "fixtures"
SCREENSHOTS = HERE / "screenshots"
#: Long enough for rationalise-canopy (its Rationalise takes 14 s of CPU) on a busy machine.
SOLVE_TIMEOUT_MS = 60000


@dataclass
class Dialogs:
    """Records every QMessageBox shown; answers questions with :attr:`answer`."""

    calls: list[tuple[str, str, str]] = field(default_factory=list)
    answer: QMessageBox.StandardButton = QMessageBox.StandardButton.Discard

    def kinds(self) -> list[str]:
        return [c[0] for c in self.calls]


@pytest.fixture(autouse=True)
def dialogs(monkeypatch: pytest.MonkeyPatch) -> Dialogs:
    """No test may block on a dialog: message boxes are recorded instead of shown."""
    record = Dialogs()

    def fake(kind: str) -> Any:
        def show(parent: Any, title: str, text: str, *args: Any, **kwargs: Any) -> Any:
            record.calls.append((kind, title, text))
            return record.answer if kind == "question" else QMessageBox.StandardButton.Ok

        return staticmethod(show)

    for kind in ("critical", "warning", "information", "question"):
        monkeypatch.setattr(QMessageBox, kind, fake(kind))
    monkeypatch.setattr(
        QMessageBox, "about", staticmethod(lambda *a, **k: record.calls.append(("about", "", "")))
    )
    return record


@pytest.fixture(scope="session")
def registry() -> Registry:
    return showcase_registry()


@pytest.fixture
def config_folder(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    folder = tmp_path / "config"
    folder.mkdir()
    monkeypatch.setenv("TORSAL_CONFIG_DIR", str(folder))
    return folder


def make_window(qtbot: Any, registry: Registry, folder: Path) -> MainWindow:
    window = MainWindow(registry=registry, settings_folder=folder)
    qtbot.addWidget(window)
    window.resize(1500, 920)
    window.show()
    qtbot.waitExposed(window)
    window.activateWindow()  # keyboard shortcuts need the active window
    qtbot.waitActive(window)
    window.start(None, offer_recovery=False)
    return window


def close_window(window: MainWindow) -> None:
    """Close a test's window once its solve has stopped: a test that failed mid-solve must
    not leave a worker running into the next test (on a loaded machine a solve can
    outlast the document's one-second wait at close)."""
    window.doc.solves.cancel()
    window.doc.solves.wait(30.0)
    window.doc.undo_stack.setClean()
    window.close()
    QApplication.processEvents()


@pytest.fixture
def window(qtbot: Any, registry: Registry, config_folder: Path) -> Iterator[MainWindow]:
    """A shown main window with its real 3D viewport, on an empty document."""
    win = make_window(qtbot, registry, config_folder)
    wait_solved(qtbot, win)
    yield win
    close_window(win)


def wait_solved(qtbot: Any, window: MainWindow, timeout: int = SOLVE_TIMEOUT_MS) -> None:
    """Wait until every requested solve has finished and its results reached the GUI."""
    qtbot.waitUntil(window.doc.solves.idle, timeout=timeout)
    QApplication.processEvents()


def downstream_of(graph, node_id: str) -> set[str]:
    """The nodes a change of ``node_id`` reaches through wires."""
    seen, stack = set(), [node_id]
    while stack:
        for wire in graph.wires_from(stack.pop()):
            if wire.target not in seen:
                seen.add(wire.target)
                stack.append(wire.target)
    return seen


def copy_fixture(source: Path, folder: Path) -> Path:
    target = folder / source.name
    shutil.copyfile(source, target)
    return target


# -- mouse helpers ------------------------------------------------------------------
def view_point(window: MainWindow, scene_pos: QPointF) -> QPoint:
    return window.view.mapFromScene(scene_pos)


def slider_handle(window: MainWindow, node_id: str) -> tuple[QPoint, int, int]:
    """Where the slider's handle is on screen, and the left and right ends of its track."""
    item = window.scene.nodes[node_id]
    window.view.centerOn(item)
    rect = item.layout.widget_rect
    track = item.widget.track(rect)
    y = rect.center().y()
    start = view_point(window, item.mapToScene(QPointF(item.widget.handle_x(rect), y)))
    left = view_point(window, item.mapToScene(QPointF(track.left() + 2, y))).x()
    right = view_point(window, item.mapToScene(QPointF(track.right() - 2, y))).x()
    return start, left, right


def port_point(window: MainWindow, node_id: str, port: str, is_input: bool) -> QPoint:
    item = window.scene.nodes[node_id]
    port_item = item.input_port(port) if is_input else item.output_port(port)
    assert port_item is not None, f"{node_id} has no {'input' if is_input else 'output'} {port}"
    return view_point(window, port_item.scenePos())


def drag(
    window: MainWindow,
    start: QPoint,
    end: QPoint,
    steps: int = 8,
    modifiers: Qt.KeyboardModifier = Qt.KeyboardModifier.NoModifier,
) -> None:
    """Press at ``start``, move to ``end`` in ``steps``, release — on the canvas viewport."""
    viewport = window.view.viewport()
    QTest.mousePress(viewport, Qt.MouseButton.LeftButton, modifiers, start)
    for i in range(1, steps + 1):
        point = start + (end - start) * (i / steps)
        QTest.mouseMove(viewport, point)
    QTest.mouseRelease(viewport, Qt.MouseButton.LeftButton, modifiers, end)


def double_click(window: MainWindow, point: QPoint) -> None:
    """A real double-click on the canvas: a click, then the double-click (QTest's
    double-click alone sends no first press, which QGraphicsScene then takes for a press)."""
    viewport = window.view.viewport()
    QTest.mouseClick(viewport, Qt.MouseButton.LeftButton, Qt.KeyboardModifier.NoModifier, point)
    QTest.mouseDClick(viewport, Qt.MouseButton.LeftButton, Qt.KeyboardModifier.NoModifier, point)


def place_by_search(qtbot: Any, window: MainWindow, query: str, scene_pos: QPointF) -> str:
    """Double-click empty canvas at ``scene_pos``, type ``query``, press Enter; the new node's id."""
    before = set(window.doc.graph.nodes)
    QTest.mouseDClick(
        window.view.viewport(),
        Qt.MouseButton.LeftButton,
        Qt.KeyboardModifier.NoModifier,
        view_point(window, scene_pos),
    )
    qtbot.waitUntil(window.popup.isVisible, timeout=3000)
    QTest.keyClicks(window.popup.query, query)
    QTest.keyClick(window.popup.query, Qt.Key.Key_Return)
    qtbot.waitUntil(lambda: bool(set(window.doc.graph.nodes) - before), timeout=3000)
    (node_id,) = set(window.doc.graph.nodes) - before
    return node_id


NONE = Qt.KeyboardModifier.NoModifier


class MenuCatcher:
    """Polls for the popup a gesture opens; reads its entries, then picks ``pick`` with a
    mouse click on it (or closes the menu with Esc)."""

    live: ClassVar[list[MenuCatcher]] = []  # stopped when the test ends (see :func:`stop_menu_catchers`)

    def __init__(self, pick: str | tuple[str, ...] | None = None) -> None:
        self.pick = [pick] if isinstance(pick, str) else list(pick or [])
        self.menus: list[list[str]] = []
        self._seen: list[QMenu] = []
        self.polls = 0
        self.stopped = False
        MenuCatcher.live.append(self)
        QTimer.singleShot(10, self._poll)

    def stop(self) -> None:
        """Poll no more (a catcher outliving its test would pick from the next test's menus)."""
        self.stopped = True

    def _poll(self) -> None:
        if self.stopped:
            return
        menu = QApplication.activePopupWidget()
        if not isinstance(menu, QMenu):
            self.polls += 1
            if self.polls < 200:
                QTimer.singleShot(10, self._poll)
            return
        if menu in self._seen:  # a submenu is still opening
            QTimer.singleShot(10, self._poll)
            return
        actions = [a for a in menu.actions() if not a.isSeparator()]
        self._seen.append(menu)
        if len(self._seen) == 1:
            self.menus.append([a.text() for a in actions])
        want = self.pick.pop(0) if self.pick else None
        chosen = next((a for a in actions if a.text() == want), None)
        if chosen is None:
            QTest.keyClick(menu, Qt.Key.Key_Escape)
            return
        QTest.mouseClick(menu, Qt.MouseButton.LeftButton, NONE, menu.actionGeometry(chosen).center())
        if chosen.menu() is not None:  # a submenu: pick on in it
            self.polls = 0
            QTimer.singleShot(10, self._poll)

    @property
    def entries(self) -> list[str]:
        assert len(self.menus) == 1, f"expected one menu, saw {self.menus}"
        return self.menus[0]


def right_click(window: MainWindow, point: QPoint, pick: str | tuple[str, ...] | None = None) -> MenuCatcher:
    """A right-click (press and release, no drag) on the canvas at ``point``; the menu it
    opens is read and ``pick`` chosen from it (a path of entries for a submenu)."""
    catcher = MenuCatcher(pick)
    viewport = window.view.viewport()
    QTest.mousePress(viewport, Qt.MouseButton.RightButton, NONE, point)
    QTest.mouseRelease(viewport, Qt.MouseButton.RightButton, NONE, point)
    QApplication.processEvents()
    catcher.stop()  # the menu's exec has returned: it was handled, or none opened
    return catcher


@pytest.fixture(autouse=True)
def stop_menu_catchers() -> Iterator[None]:
    yield
    for catcher in MenuCatcher.live:
        catcher.stop()
    MenuCatcher.live.clear()
    while (popup := QApplication.activePopupWidget()) is not None:  # none may outlive its test
        popup.close()
        QApplication.processEvents()


@pytest.fixture
def first_steps(qtbot, window):
    """The window with the first-steps example open and solved."""
    assert window.open_file(EXAMPLES / "first-steps.graph", ask=False)
    wait_solved(qtbot, window)
    qtbot.wait(50)
    return window


def title_point(window: MainWindow, node_id: str) -> QPoint:
    """The point of the view on node ``node_id``'s title bar."""
    item = window.scene.nodes[node_id]
    return view_point(window, item.mapToScene(QPointF(item.size()[0] / 2, 8)))
