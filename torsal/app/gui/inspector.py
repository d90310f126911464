"""The inspector: the selected node's settings (editable), ports, current output data, help,
and the plot a node drew (display.Plot, analysis.CurvatureHistogram, analysis.WarpChart)."""

from __future__ import annotations

import html
import inspect
import json
from pathlib import Path
from typing import Any

from PySide6.QtCore import Qt, QTimer
from PySide6.QtGui import QImage, QPixmap
from PySide6.QtWidgets import (
    QLabel,
    QTableWidget,
    QTableWidgetItem,
    QTabWidget,
    QTextBrowser,
    QTreeWidget,
    QTreeWidgetItem,
    QVBoxLayout,
    QWidget,
)

from torsal.app.gui.document import Document
from torsal.app.gui.editor import Editor
from torsal.app.gui.formatting import format_item
from torsal.app.gui.plot_view import PlotArea
from torsal.engine.bounds import bounds_text
from torsal.engine.cluster import is_cluster
from torsal.engine.datatree import DataTree, format_path
from torsal.engine.graph import Graph, is_placeholder
from torsal.engine.node import Node

MAX_ITEMS_SHOWN = 100
#: While a slider is dragged, a selected node is shown again at most this often (ms).
DRAG_REFRESH_MS = 1000
#: An output item that is a path to one of these is shown as an image on the Plot tab.
IMAGE_SUFFIXES = (".png",)


def plot_image(outputs: dict[str, DataTree] | None) -> Path | None:
    """The first image file among a node's text outputs (a plot node's ``Image``), or None."""
    for tree in (outputs or {}).values():
        for _path, branch in tree.items():
            value: Any = branch[0] if branch else None
            if isinstance(value, str) and value.lower().endswith(IMAGE_SUFFIXES):
                path = Path(value)
                if path.is_file():
                    return path
            break  # only the first item of each output is looked at
    return None


class Inspector(QWidget):
    """Everything about one node; settings are edited as JSON values (one undo step each)."""

    def __init__(self, doc: Document, editor: Editor, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.doc = doc
        self.editor = editor
        self.node_id: str | None = None
        self._filling = False
        self._empty = False  # the tables are empty and the header asks for a node
        layout = QVBoxLayout(self)
        layout.setContentsMargins(4, 4, 4, 4)
        self.header = QLabel("Select a node to inspect it.")
        self.header.setWordWrap(True)
        self.header.setTextFormat(Qt.TextFormat.RichText)
        layout.addWidget(self.header)
        self.tabs = QTabWidget()
        layout.addWidget(self.tabs, 1)
        self.settings = QTableWidget(0, 2)
        self.settings.setHorizontalHeaderLabels(["Setting", "Value (JSON)"])
        self.settings.horizontalHeader().setStretchLastSection(True)
        self.settings.verticalHeader().setVisible(False)
        self.settings.itemChanged.connect(self._setting_edited)
        self.ports = QTreeWidget()
        self.ports.setHeaderLabels(["Port", "Type", "Access", "Source / data"])
        self.ports.setColumnWidth(0, 110)
        self.data = QTreeWidget()
        self.data.setHeaderLabels(["Output data", "Value"])
        self.data.setColumnWidth(0, 150)
        self.help = QTextBrowser()
        # The Plot tab is shown only for a node that drew an image (the node drew it on
        # the solver's thread; here it is only read, once per new file).
        # A child of the inspector even while no tab shows it: Qt deletes it with the window.
        # Parentless, it was deleted by Python's garbage collector, on whichever thread
        # collected the inspector's reference cycles (a solver's worker thread too).
        self.plot_area = PlotArea(self)
        self.plot_area.hide()
        self.plot = self.plot_area.label
        self.plot_path: Path | None = None
        self._plot_key: tuple[str, int, int] | None = None
        self.tabs.addTab(self.settings, "Settings")
        self.tabs.addTab(self.ports, "Ports")
        self.tabs.addTab(self.data, "Data")
        self.tabs.addTab(self.help, "Help")
        doc.graph_changed.connect(lambda event: self.refresh() if event.node_id == self.node_id else None)
        doc.results_changed.connect(self._solved)
        # while a slider is dragged a selected node's tables are refilled once a second (a
        # strip's take a few ms, on every solve), and at once when the slider is let go
        self._due = False
        self._held = QTimer(self)
        self._held.setSingleShot(True)
        self._held.setInterval(DRAG_REFRESH_MS)
        self._held.timeout.connect(self._refresh_if_due)
        editor.drag_ended.connect(self._drag_ended)
        doc.graph_replaced.connect(lambda: self.show_node(None))

    def show_node(self, node_id: str | None) -> None:
        changed = node_id != self.node_id
        self.node_id = node_id
        self.refresh()
        if changed and self.plot_path is not None:
            self.tabs.setCurrentWidget(self.plot_area)

    def _solved(self, _outcome: object) -> None:
        if self._held.isActive():
            self._due = True
            return
        self.refresh()
        if self.editor.dragging and self.node_id is not None:
            self._held.start()

    def _refresh_if_due(self) -> None:
        if self._due:
            self._solved(None)

    def _drag_ended(self) -> None:
        self._held.stop()
        if self._due:
            self.refresh()

    def refresh(self) -> None:
        self._due = False
        graph = self.doc.graph
        if self.node_id not in graph.nodes:
            self.node_id = None
        if self.node_id is None and self._empty:
            return  # nothing selected, and nothing shown: a solve has nothing to change here
        self._empty = self.node_id is None
        self._filling = True
        try:
            self._fill(graph)
        finally:
            self._filling = False

    def _fill(self, graph: Graph) -> None:
        self.settings.setRowCount(0)
        self.ports.clear()
        self.data.clear()
        if self.node_id is None:
            self.header.setText("Select a node to inspect it.")
            self.help.clear()
            self._show_plot(None)
            return
        record = graph.nodes[self.node_id]
        result = self.doc.result(self.node_id)
        state = result.state if result else "not solved yet"
        seconds = f", {result.seconds * 1000:.2f} ms" if result else ""
        self.header.setText(
            f"<b>{html.escape(record.title)}</b> [{record.id}]<br><i>{record.type_id}</i> — {state}{seconds}"
        )
        node = record.node
        for name, value in node.settings.items():
            row = self.settings.rowCount()
            self.settings.insertRow(row)
            key = QTableWidgetItem(name)
            key.setFlags(key.flags() & ~Qt.ItemFlag.ItemIsEditable)
            self.settings.setItem(row, 0, key)
            self.settings.setItem(row, 1, QTableWidgetItem(json.dumps(value, ensure_ascii=False)))
        wires = graph.wires_into(record.id)
        for port in node.input_ports():
            feeding = [w for w in wires if w.target_port == port.name]
            inputs = record.inputs.get(port.name)
            if feeding:
                source = "from " + ", ".join(f"{w.source}.{w.source_port}" for w in feeding)
            elif inputs is not None and inputs.has_value:
                source = f"value {json.dumps(inputs.value)}"
            elif port.has_default:
                source = f"default {format_item(port.default)}"
            else:
                source = "optional" if port.optional else "needs data"
            if inputs is not None and inputs.modifiers:
                source += f"  [{', '.join(inputs.modifiers)}]"
            bounds = bounds_text(port)  # declared on the port, enforced by the solver
            kind = f"{port.type.name}, {bounds}" if bounds else port.type.name
            item = QTreeWidgetItem([f"▸ {port.name}", kind, port.access.value, source])
            item.setToolTip(0, f"{port.description} Takes {bounds}." if bounds else port.description)
            self.ports.addTopLevelItem(item)
        for port in node.output_ports():
            tree = result.outputs.get(port.name) if result else None
            summary = f"{tree.item_count} items, {tree.branch_count} branches" if tree is not None else "—"
            item = QTreeWidgetItem([f"◂ {port.name}", port.type.name, port.access.value, summary])
            item.setToolTip(0, port.description)
            self.ports.addTopLevelItem(item)
            if tree is not None:
                self._add_tree(port.name, tree)
        self.help.setMarkdown(self._help_markdown(node, is_placeholder(node), record.type_id))
        self._show_plot(plot_image(result.outputs if result else None))

    def _show_plot(self, path: Path | None) -> None:
        """Show the image at ``path`` on the Plot tab (added first), or remove the tab."""
        self.plot_path = path
        index = self.tabs.indexOf(self.plot_area)
        if path is None:
            if index >= 0:
                self.tabs.removeTab(index)
            self.plot_area.clear()
            self._plot_key = None
            return
        if index < 0:
            self.tabs.insertTab(0, self.plot_area, "Plot")
        try:
            stat = path.stat()
        except OSError:
            self.plot_area.set_text(f"The plot {path} cannot be read.")
            return
        key = (str(path), stat.st_mtime_ns, stat.st_size)
        if key == self._plot_key:
            return
        self._plot_key = key
        from torsal.nodes.common.charts import RECIPE_KEY, read_recipe

        image = QImage(str(path))
        if image.isNull():
            self.plot_area.set_text(f"The plot {path} is not a readable image.")
            return
        # a chart node's PNG carries its recipe: the tab draws the chart at its own size
        self.plot_area.set_image(QPixmap.fromImage(image), read_recipe(image.text(RECIPE_KEY)))

    def _add_tree(self, name: str, tree: DataTree) -> None:
        top = QTreeWidgetItem([name, f"{tree.item_count} items in {tree.branch_count} branches"])
        self.data.addTopLevelItem(top)
        shown = 0
        for path, branch in tree.items():
            branch_item = QTreeWidgetItem([format_path(path), f"{len(branch)} items"])
            top.addChild(branch_item)
            for index, value in enumerate(branch):
                if shown >= MAX_ITEMS_SHOWN:
                    break
                branch_item.addChild(QTreeWidgetItem([str(index), format_item(value)]))
                shown += 1
        top.setExpanded(True)
        if top.childCount() <= 4:
            for i in range(top.childCount()):
                top.child(i).setExpanded(True)

    @staticmethod
    @staticmethod
    def _help_markdown(node: Node, placeholder: bool, type_id: str) -> str:
        """The node's help as Markdown (its docstring is written in it: ``code``, *emphasis*,
        lists), rendered by the Help tab."""
        if placeholder:
            return f"The node type **{type_id}** is not installed; its data is kept unchanged."
        cls = type(node)
        nickname = getattr(cls, "nickname", "")
        known_as = f" — nickname **{nickname}**" if nickname else ""
        parts = [f"### {node.display_name()}", f"*{cls.type_id}*{known_as}"]
        parts.append(inspect.cleandoc(cls.__doc__ or ""))  # docstring lines lose their indent
        aliases = getattr(cls, "aliases", ())
        if aliases:
            parts.append("Also found as: " + ", ".join(f"*{a}*" for a in aliases))
        if is_cluster(node):
            parts.append("Double-click it to edit its definition; right-click for its ports "
                         "or to explode it.")
        for title, ports in (("Inputs", node.input_ports()), ("Outputs", node.output_ports())):
            if ports:
                rows = "\n".join(
                    f"- **{p.name}** ({p.nickname}, {p.type.name}, {p.access.value}): {p.description}"
                    for p in ports
                )
                parts.append(f"#### {title}\n\n{rows}")
        return "\n\n".join(parts)

    def _setting_edited(self, item: QTableWidgetItem) -> None:
        if self._filling or item.column() != 1 or self.node_id is None:
            return
        name = self.settings.item(item.row(), 0).text()
        text = item.text()
        try:
            value = json.loads(text)
        except ValueError:
            value = text
        self.editor.set_setting(self.node_id, name, value)
