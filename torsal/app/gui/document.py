"""The open document: one engine graph, its file, undo history, solver and results.

:class:`Document` is the only place the GUI's graph lives. Widgets never edit the
graph directly: they push undo commands (:mod:`torsal.app.gui.commands`), which edit through
:meth:`Document.editing` so the worker thread is paused first. Engine change events
are relayed as the Qt signal :attr:`Document.graph_changed`.
"""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path

from PySide6.QtCore import QObject, Signal
from PySide6.QtGui import QUndoGroup, QUndoStack

from torsal.app.gui.improvements import Improvements
from torsal.app.gui.solve_controller import SolveController, SolveOutcome
from torsal.engine.cluster import ClusterInput
from torsal.engine.cluster_edits import cluster_graph, definition_of
from torsal.engine.graph import Graph, GraphEvent
from torsal.engine.graphfile import read_graph, write_graph
from torsal.engine.registry import Registry
from torsal.engine.solver import NodeResult, Solver
from torsal.engine.writes import WriteAccess, WriteRequest


@dataclass
class ClusterFrame:
    """A graph the canvas left to edit a cluster definition inside it: what coming back
    restores, and which definition the edits inside go to."""

    graph: Graph
    solver: Solver
    undo_stack: QUndoStack
    results: dict[str, NodeResult]
    last_outcome: SolveOutcome | None
    definition_id: str
    instance_id: str
    name: str


class Document(QObject):
    """A graph being edited, with its path, dirty state and latest solve results.

    Clusters are edited in place: :meth:`enter_cluster` shows a copy of a cluster's
    definition (fed with the instance's input data) with an undo history of its own;
    :meth:`leave_cluster` goes back and commits the edits, if any, to the definition as
    one undo step of the graph outside ("Edit cluster"), which updates every instance.
    ``frames`` holds the graphs outside, outermost first; :attr:`undo_group` follows the
    history of the graph shown (the window's Undo and Redo act on it).
    """

    graph_replaced = Signal()
    graph_changed = Signal(object)  # engine.graph.GraphEvent
    groups_changed = Signal()  # group edits the engine does not report (see graph_order)
    results_changed = Signal(object)  # SolveOutcome
    dirty_changed = Signal(bool)
    path_changed = Signal(object)  # Path | None
    #: nodes want to write files and this document has not been asked yet: list[WriteRequest]
    writes_requested = Signal(object)
    #: the canvas went into or out of a cluster definition (see :attr:`breadcrumb`)
    context_changed = Signal()

    def __init__(self, registry: Registry, parent: QObject | None = None) -> None:
        super().__init__(parent)
        self.registry = registry
        self.undo_group = QUndoGroup(self)
        self.undo_stack = QUndoStack(self)
        self.undo_group.addStack(self.undo_stack)
        self.undo_group.setActiveStack(self.undo_stack)
        self.undo_group.cleanChanged.connect(lambda _clean: self.dirty_changed.emit(self.dirty))
        self.frames: list[ClusterFrame] = []
        self.solves = SolveController(self)
        self.solves.finished.connect(self._on_solved)
        self.path: Path | None = None
        self.results: dict[str, NodeResult] = {}
        self.last_outcome: SolveOutcome | None = None
        self.graph = Graph()
        #: where this document's nodes may write, and whether the user has said they may
        self.writes = WriteAccess()
        self.writes_asked = False
        self.solver = Solver(self.graph, self.writes, anytime=True)
        #: results that improve after the solve, searched in the background (nesting)
        self.improvements = Improvements(self.solves, lambda: self.solver, self)
        self._unsubscribe = self.graph.subscribe(self._relay)
        self.solves.set_solver(self.solver)

    # -- documents -------------------------------------------------------------------
    def replace(self, graph: Graph, path: Path | None, *, clean: bool = True) -> None:
        """Show ``graph`` instead of the current one (undo history is cleared)."""
        self.solves.pause()
        self.improvements.stop()
        self._drop_frames()
        self._unsubscribe()
        self.graph = graph
        self.writes = WriteAccess(path.parent if path is not None else None)  # a new document: not allowed
        self.writes_asked = False
        self.solver = Solver(graph, self.writes, anytime=True)
        self.solves.set_solver(self.solver)
        self._unsubscribe = graph.subscribe(self._relay)
        self.results = {}
        self.last_outcome = None
        self.undo_stack.clear()
        if clean:
            self.undo_stack.setClean()
        else:
            self.undo_stack.resetClean()
        self.dirty_changed.emit(self.dirty)
        self.set_path(path)
        self.graph_replaced.emit()
        self.solves.request()

    def new(self) -> None:
        self.replace(Graph(), None)

    def open(self, path: str | Path) -> None:
        """Read ``path``; on :class:`~torsal.engine.graphfile.GraphFileError` nothing changes."""
        path = Path(path)
        graph = read_graph(path, self.registry)
        self.replace(graph, path.resolve())

    def save(self, path: str | Path | None = None) -> Path:
        """Write the graph (atomically, keeping ``.bak``) to ``path`` or its own file."""
        target = Path(path) if path is not None else self.path
        if target is None:
            raise ValueError("the document has no file yet: give a path")
        self.leave_to(0)  # a cluster being edited: its edits go into the file too
        write_graph(self.graph, target)
        self.undo_stack.setClean()
        self.set_path(target.resolve())
        return target

    def set_path(self, path: Path | None) -> None:
        if path != self.path:
            self.path = path
        folder = path.parent if path is not None else None
        if folder != self.writes.folder:
            # consent was for the old folder: files now go elsewhere, so ask again
            self.writes.folder, self.writes.allowed, self.writes_asked = folder, False, False
        self.path_changed.emit(path)

    # -- writing files (see engine.writes) --------------------------------------------
    def answer_writes(self, allow: bool) -> None:
        """The user's answer to "may this graph write files?"; allowing solves the nodes
        that were waiting again, so they write now."""
        self.writes_asked = True
        if self.writes.allowed == allow:
            return
        waiting = [r.node_id for r in self.writes.pending()]
        self.writes.allowed = allow
        self.writes.clear_requests()
        if allow:
            with self.editing() as graph:
                for node_id in waiting:
                    if node_id in graph.nodes:
                        graph.expire(node_id)

    def pending_writes(self) -> list[WriteRequest]:
        return [r for r in self.writes.pending() if r.node_id in self.graph.nodes]

    @property
    def dirty(self) -> bool:
        return any(not stack.isClean() for stack in self._stacks())

    def _stacks(self) -> list[QUndoStack]:
        return [*(frame.undo_stack for frame in self.frames), self.undo_stack]

    @property
    def root_graph(self) -> Graph:
        """The document's own graph (the outermost, while a cluster is being edited)."""
        return self.frames[0].graph if self.frames else self.graph

    @property
    def breadcrumb(self) -> list[str]:
        """Where the canvas is: ``["Document", "Cluster name", ...]``."""
        return ["Document", *(frame.name for frame in self.frames)]

    # -- clusters --------------------------------------------------------------------
    def enter_cluster(self, node_id: str) -> None:
        """Show cluster node ``node_id``'s definition for editing, its inputs fed with the
        data that instance received last."""
        self.solves.pause()
        outer = self.graph
        definition = definition_of(outer, node_id)
        edited = cluster_graph(outer, definition.id)
        for input_id, tree in self.solver.cluster_inputs(node_id).items():
            record = edited.nodes.get(input_id)
            if record is not None and isinstance(record.node, ClusterInput):
                record.node.feed = tree
                edited.expire(input_id)
        frame = ClusterFrame(
            outer, self.solver, self.undo_stack, self.results, self.last_outcome,
            definition.id, node_id, definition.name or "Cluster",
        )
        self.frames.append(frame)
        stack = QUndoStack(self)
        self._show(edited, Solver(edited, self.writes, anytime=True), stack, {}, None)

    def leave_cluster(self) -> bool:
        """Back to the graph outside; edits made inside are committed to the definition as
        one undo step there. False when the canvas shows the document's own graph."""
        if not self.frames:
            return False
        from torsal.app.gui.commands import EditClusterDefinition

        self.solves.pause()
        frame = self.frames.pop()
        edited, inner = self.graph, self.undo_stack
        changed = not inner.isClean()
        self._show(frame.graph, frame.solver, frame.undo_stack, frame.results, frame.last_outcome)
        self.undo_group.removeStack(inner)
        inner.deleteLater()
        if changed:
            self.push(EditClusterDefinition(self, frame.definition_id, edited, f"Edit cluster {frame.name}"))
        return True

    def leave_to(self, depth: int) -> None:
        """Go back out until ``depth`` clusters are open (0: the document's own graph)."""
        while len(self.frames) > depth:
            self.leave_cluster()

    def _show(
        self,
        graph: Graph,
        solver: Solver,
        stack: QUndoStack,
        results: dict[str, NodeResult],
        outcome: SolveOutcome | None,
    ) -> None:
        self._unsubscribe()
        self.graph, self.solver, self.results, self.last_outcome = graph, solver, results, outcome
        self.solves.set_solver(solver)
        self._unsubscribe = graph.subscribe(self._relay)
        if stack not in self.undo_group.stacks():
            self.undo_group.addStack(stack)
        self.undo_stack = stack
        self.undo_group.setActiveStack(stack)
        self.graph_replaced.emit()
        self.context_changed.emit()
        self.dirty_changed.emit(self.dirty)
        self.solves.request()

    def _drop_frames(self) -> None:
        """Forget the clusters being edited (a document replaced): back to the root history."""
        if not self.frames:
            return
        root = self.frames[0]
        for stack in [*(f.undo_stack for f in self.frames[1:]), self.undo_stack]:
            self.undo_group.removeStack(stack)
            stack.deleteLater()
        self.frames.clear()
        self.undo_stack = root.undo_stack
        self.undo_group.setActiveStack(root.undo_stack)
        self.context_changed.emit()

    @property
    def title(self) -> str:
        return self.path.name if self.path else "Untitled"

    # -- editing ---------------------------------------------------------------------
    @contextmanager
    def editing(self, affects_solve: bool = True) -> Iterator[Graph]:
        """Edit the graph: pauses the worker first and asks for a solve afterwards."""
        if affects_solve:
            self.solves.pause()
        try:
            yield self.graph
        finally:
            if affects_solve:
                self.solves.request()

    def push(self, command: object) -> None:
        """Run an undo command and keep it in the history."""
        self.undo_stack.push(command)

    # -- results ---------------------------------------------------------------------
    def result(self, node_id: str) -> NodeResult | None:
        return self.results.get(node_id)

    def _on_solved(self, outcome: SolveOutcome) -> None:
        self.results = {k: v for k, v in outcome.results.items() if k in self.graph.nodes}
        self.last_outcome = outcome
        self.results_changed.emit(outcome)
        if not self.writes_asked and not self.writes.allowed and not outcome.cancelled:
            pending = self.pending_writes()
            if pending:
                self.writes_asked = True
                self.writes_requested.emit(pending)

    def _relay(self, event: GraphEvent) -> None:
        self.graph_changed.emit(event)

    def close(self) -> None:
        """Stop the worker (the app is closing): cancel, and wait a little for it. A node
        that never checks for cancellation is left to finish on its daemon thread, its
        results going nowhere (:meth:`SolveController.shutdown`)."""
        self.improvements.stop()
        self.solves.shutdown(timeout=1.0)
