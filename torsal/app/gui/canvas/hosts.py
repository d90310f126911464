"""What the canvas's parts need of each other, as :class:`typing.Protocol` classes.

The scene holds node items, a node item holds its inline widgets, and the view builds
the canvas's right-click menu; each part hands itself to the one it holds. These
protocols name only what the held part uses of its holder, so the holder's module is
never imported back (no import circle): :class:`NodeCanvas` is the scene as a node item
sees it (:class:`~torsal.app.gui.canvas.scene.CanvasScene` satisfies it), :class:`WidgetHost`
the node item as an inline widget sees it (:class:`~torsal.app.gui.canvas.node_item.NodeItem`)
and :class:`MenuView` the view as :func:`~torsal.app.gui.canvas.context_menus.canvas_menu`
sees it (:class:`~torsal.app.gui.canvas.view.CanvasView`).

This module names the types it mentions only for type checkers and imports none of the
modules it describes.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, Protocol

if TYPE_CHECKING:
    from PySide6.QtCore import QPoint, QPointF
    from PySide6.QtGui import QAction, QFont

    from torsal.app.gui.document import Document
    from torsal.app.gui.editor import Editor
    from torsal.engine.graph import NodeRecord
    from torsal.engine.solver import NodeResult


class NodeCanvas(Protocol):
    """The scene as its node items (and their widgets) see it: the document shown, the
    editor every edit goes through, and what a node item reports or asks for."""

    doc: Document
    editor: Editor

    def node_item_moved(self, item: Any) -> None:
        """``item`` (a node item of this scene) was dragged to a new place."""

    def open_cluster(self, node_id: str) -> None: ...
    def rename_node(self, node_id: str) -> None: ...


class WidgetHost(Protocol):
    """The node item as its inline widget sees it: the node, its last result, the fonts
    it paints with, and its scene."""

    record: NodeRecord
    node_id: str
    result: NodeResult | None
    port_font: QFont
    mono_font: QFont

    def canvas(self) -> NodeCanvas: ...
    def scene(self) -> Any:
        """The item's scene (a :class:`NodeCanvas`), or None before it is added to one."""

    def update(self) -> None:
        """Repaint the item."""

    def update_widget(self) -> None:
        """Repaint the widget's part of the item, now."""


class ClusterCanvas(Protocol):
    """The scene as the canvas menu sees it: inside a cluster, it adds the cluster's ports."""

    doc: Document

    def add_cluster_port(self, kind: str, position: tuple[float, float]) -> str: ...


class MenuView(Protocol):
    """The view as :func:`~torsal.app.gui.canvas.context_menus.canvas_menu` sees it: where
    a scene point is on screen, the node search it opens there, and its own actions."""

    canvas: ClusterCanvas

    def open_search(self, scene_pos: QPointF, global_pos: QPoint) -> Any: ...
    def mapFromScene(self, point: QPointF) -> QPoint: ...
    def mapToGlobal(self, point: QPoint) -> QPoint: ...
    def actions(self) -> list[QAction]: ...
