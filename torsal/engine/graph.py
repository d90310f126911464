"""The graph: nodes, wires and groups, with validated edits and change events.

Every edit goes through a method here. Edits that change what a node computes
*expire* that node and everything downstream of it, so the solver re-solves only
those. Listeners (a GUI, an undo stack) receive one event per edit, a small frozen dataclass
per kind (see :mod:`torsal.engine.events`).

Each edit costs what it touches, not the size of the graph: the wires into and out of
every node are indexed, and a topological rank of every node is kept up to date as
wires are added (the Pearce–Kelly method: a wire that runs forward in the ranks costs
nothing; one that runs backward re-ranks only the nodes between its ends). The rank
answers "would this wire make a loop?" by searching only between the two ends, and
lets the solver put its expired nodes in order without walking the whole graph.
"""

from __future__ import annotations

import copy
from collections.abc import Callable, Iterable
from typing import Any

from torsal.engine.datatree import MODIFIERS
from torsal.engine.events import (
    EnabledChanged,
    GraphEvent,
    GroupAdded,
    GroupRemoved,
    InputChanged,
    LabelChanged,
    ModifiersChanged,
    NodeAdded,
    NodeMoved,
    NodeRemoved,
    PreviewChanged,
    SettingChanged,
    WireAdded,
    WireRemoved,
)
from torsal.engine.graph_records import (  # the records, exported here under their usual home
    GraphError,
    Group,
    InputState,  # noqa: F401 - exported
    NodeRecord,
    Wire,
)
from torsal.engine.node import Node
from torsal.engine.types import can_cast

Listener = Callable[[GraphEvent], None]


class Graph:
    """Nodes by id, wires between their ports, groups, and the set of expired nodes."""

    def __init__(self) -> None:
        self.nodes: dict[str, NodeRecord] = {}
        self.groups: list[Group] = []
        self.units: str = "m"
        self.meta: dict[str, Any] = {}
        self.raw: dict[str, Any] = {}
        #: cluster definitions by id, shared with the inner graph of every definition
        #: (see :mod:`torsal.engine.cluster`)
        self.clusters: dict[str, Any] = {}
        self.expired: set[str] = set()
        #: the expired nodes that were themselves edited (the rest are expired only because
        #: something upstream was): the solver may keep the result of a node that is not
        #: here when everything re-solved upstream of it gave the very same outputs
        self.touched: set[str] = set()
        #: how many nodes have been removed so far (lets a solver forget their results cheaply)
        self.removals = 0
        self._listeners: list[Listener] = []
        self._id_hints: dict[str, int] = {}  # stem → a number below which new_id finds no gap
        # every wire, in wire order, with a serial number that only grows
        self._wires: dict[Wire, int] = {}
        self._serial = 0
        self._into: dict[str, dict[Wire, None]] = {}  # node → wires into it, in wire order
        self._from: dict[str, dict[Wire, None]] = {}  # node → wires out of it, in wire order
        # topological rank of every node (None: to be computed from scratch by order())
        self._rank: dict[str, int] | None = {}
        self._next_rank = 0
        self._order: list[str] | None = None

    # -- events ---------------------------------------------------------------------
    def subscribe(self, listener: Listener) -> Callable[[], None]:
        """Call ``listener`` on every edit; returns a function that unsubscribes."""
        self._listeners.append(listener)
        return lambda: self._listeners.remove(listener)

    def emit(self, event_type: type[GraphEvent], *fields: Any) -> None:
        """Tell the listeners of an edit: the event is made only when someone listens.
        The graph's own edits call it; so do edits made beside it on its public records
        (the cluster edits of :mod:`torsal.engine.cluster_edits`)."""
        if not self._listeners:  # a graph being loaded or built by a script: no one listens
            return
        event = event_type(*fields)
        for listener in list(self._listeners):
            listener(event)

    # -- nodes ----------------------------------------------------------------------
    def new_id(self, base: str) -> str:
        """A fresh id from ``base`` (``slider``, ``slider2``, ``slider3`` ...)."""
        stem = "".join(c for c in base.lower() if c.isalnum() or c in "_-") or "node"
        if stem not in self.nodes:
            return stem
        # every number below the hint is taken (hints are forgotten when a node goes)
        n = self._id_hints.get(stem, 2)
        while f"{stem}{n}" in self.nodes:
            n += 1
        self._id_hints[stem] = n
        return f"{stem}{n}"

    def add_node(
        self,
        node: Node,
        node_id: str | None = None,
        *,
        label: str = "",
        position: tuple[float, float] = (0.0, 0.0),
        type_id: str | None = None,
    ) -> NodeRecord:
        """Add ``node`` under ``node_id`` (made up from its name when not given)."""
        node_id = node_id or self.new_id(node.name())
        if node_id in self.nodes:
            raise GraphError(f"there is already a node with id {node_id!r}")
        record = NodeRecord(node_id, node, type_id or node.type_id, label, tuple(position))
        return self.add_record(record)

    def add_record(self, record: NodeRecord) -> NodeRecord:
        if record.id in self.nodes:
            raise GraphError(f"there is already a node with id {record.id!r}")
        self.nodes[record.id] = record
        if self._rank is not None:  # a node without wires may go last in the order
            self._rank[record.id] = self._next_rank
            self._next_rank += 1
            if self._order is not None:
                self._order.append(record.id)
        self.expired.add(record.id)
        self.touched.add(record.id)
        self.emit(NodeAdded, record.id)
        return record

    def remove_node(self, node_id: str) -> NodeRecord:
        """Remove a node and every wire touching it."""
        return self._remove_node(node_id, None)

    def _remove_node(self, node_id: str, groups_of: dict[str, list[Group]] | None) -> NodeRecord:
        record = self.record(node_id)
        for wire in self._wires_touching(node_id):
            self.disconnect(wire)
        self.expire(node_id)
        del self.nodes[node_id]
        self.expired.discard(node_id)
        self.touched.discard(node_id)
        self._into.pop(node_id, None)
        self._from.pop(node_id, None)
        if self._rank is not None:
            del self._rank[node_id]
        self._order = None
        self.removals += 1
        self._id_hints.clear()
        for group in self.groups if groups_of is None else groups_of.get(node_id, ()):
            if node_id in group.nodes:
                group.nodes.remove(node_id)
        self.emit(NodeRemoved, node_id, record)
        return record

    # -- bulk edits -------------------------------------------------------------------
    def add_many(self, records: Iterable[NodeRecord], wires: Iterable[Wire] = ()) -> None:
        """Add node records, then wires, as one edit (a paste, a duplicate, an undone delete).

        The events are those of :meth:`add_record` and :meth:`connect_wire` called in turn.
        Wires are checked one by one except for loops, which one search at the end finds
        (cheaper than a search per wire when many wires run against the current order).
        If any record or wire cannot be added, what was added is taken out again (in
        reverse) and the :class:`GraphError` is raised: the graph is left as it was.
        """
        added_records: list[NodeRecord] = []
        added_wires: list[Wire] = []
        try:
            for record in records:
                added_records.append(self.add_record(record))
            for wire in wires:
                added_wires.append(self.connect_wire(wire, check_loops=False))
            self._ranks()  # a loop among the new wires: GraphError
        except GraphError:
            for wire in reversed(added_wires):
                self.disconnect(wire)
            for record in reversed(added_records):
                self.remove_node(record.id)
            raise

    def remove_many(self, node_ids: Iterable[str]) -> list[NodeRecord]:
        """Remove several nodes with their wires (a deletion), in the order given.

        The events are those of :meth:`remove_node` called for each id in turn; ids that
        are not in the graph raise :class:`GraphError` before anything is removed.
        """
        ids = list(dict.fromkeys(node_ids))
        for node_id in ids:
            self.record(node_id)
        doomed = set(ids)
        groups_of: dict[str, list[Group]] = {}
        for group in self.groups:
            for member in doomed.intersection(group.nodes):
                groups_of.setdefault(member, []).append(group)
        return [self._remove_node(node_id, groups_of) for node_id in ids]

    def record(self, node_id: str) -> NodeRecord:
        """The record of node ``node_id``; a :class:`GraphError` names an unknown id."""
        try:
            return self.nodes[node_id]
        except KeyError:
            raise GraphError(f"there is no node with id {node_id!r}") from None

    # -- wires ----------------------------------------------------------------------
    def connect(self, source: str, source_port: str, target: str, target_port: str) -> Wire:
        """Wire an output to an input, after checking types, cycles and wire counts."""
        return self.connect_wire(Wire(source, source_port, target, target_port))

    def connect_wire(self, wire: Wire, check_loops: bool = True) -> Wire:
        """Add ``wire`` (see :meth:`connect`).

        ``check_loops=False`` is for loading many wires at once: the caller then finds
        loops with one :meth:`order` call instead of a search per wire.
        """
        self.check_wire(wire, check_loops)
        self._wires[wire] = self._serial
        self._serial += 1
        source, target = wire.source, wire.target
        into, out = self._into.get(target), self._from.get(source)
        if into is None:
            into = self._into[target] = {}
        if out is None:
            out = self._from[source] = {}
        into[wire] = out[wire] = None
        rank = self._rank
        if rank is not None and rank[wire.source] > rank[wire.target]:
            if check_loops:
                self._rerank(wire.source, wire.target)
            else:  # unchecked (a file being loaded): order() sorts afresh and finds any loop
                self._rank = self._order = None
        self.expire(wire.target)
        self.emit(WireAdded, wire)
        return wire

    def check_wire(self, wire: Wire, check_loops: bool = True) -> None:
        """Raise :class:`GraphError` saying why ``wire`` cannot be added."""
        src, dst = self.record(wire.source), self.record(wire.target)
        out_port = src.node.output_port(wire.source_port)
        in_port = dst.node.input_port(wire.target_port)
        if out_port is None and not is_placeholder(src.node):
            raise GraphError(f"{src.title} has no output called {wire.source_port!r}")
        if in_port is None and not is_placeholder(dst.node):
            raise GraphError(f"{dst.title} has no input called {wire.target_port!r}")
        if wire in self._wires:
            raise GraphError(f"{wire} is already connected")
        if out_port and in_port and not can_cast(out_port.type, in_port.type):
            raise GraphError(
                f"{src.title}.{out_port.name} gives {out_port.type.name}, "
                f"which {dst.title}.{in_port.name} ({in_port.type.name}) cannot take"
            )
        if in_port and not in_port.accepts_several_wires and self._fed(wire.target, wire.target_port):
            raise GraphError(
                f"{dst.title}.{in_port.name} takes one wire; disconnect the other first "
                "(or hold Shift to add to a list input)"
            )
        if wire.source == wire.target or (check_loops and self.reaches(wire.target, wire.source)):
            raise GraphError(f"{wire} would make a loop: {wire.target} already feeds {wire.source}")

    def _fed(self, node_id: str, port: str) -> bool:
        """Whether a wire runs into ``port`` of ``node_id``."""
        return any(w.target_port == port for w in self._into.get(node_id, ()))

    def disconnect(self, wire: Wire) -> None:
        if wire not in self._wires:
            raise GraphError(f"{wire} is not connected")
        del self._wires[wire]
        del self._into[wire.target][wire]
        del self._from[wire.source][wire]
        if wire.target in self.nodes:
            self.expire(wire.target)
        self.emit(WireRemoved, wire)

    @property
    def wires(self) -> list[Wire]:
        """Every wire, in wire order (the order of the file; a new wire goes last). A copy:
        edit through :meth:`connect` and :meth:`disconnect`."""
        return list(self._wires)

    def has_wire(self, wire: Wire) -> bool:
        return wire in self._wires

    def wires_into(self, node_id: str, port: str | None = None) -> list[Wire]:
        """Wires into ``node_id`` (into one of its ports when ``port`` is given), in wire order."""
        wires = self._into.get(node_id, ())
        return list(wires) if port is None else [w for w in wires if w.target_port == port]

    def wires_from(self, node_id: str) -> list[Wire]:
        """Wires out of ``node_id``, in wire order."""
        return list(self._from.get(node_id, ()))

    def _wires_touching(self, node_id: str) -> list[Wire]:
        """Wires into or out of ``node_id``, in wire order."""
        into, out = self._into.get(node_id, {}), self._from.get(node_id, {})
        if not into or not out:
            return list(into or out)
        return sorted([*into, *out], key=self._wires.__getitem__)

    # -- node state -------------------------------------------------------------------
    def set_setting(self, node_id: str, name: str, value: Any) -> None:
        record = self.record(node_id)
        old = record.node.settings.get(name)
        record.node.settings[name] = value
        self.expire(node_id)
        self.emit(SettingChanged, node_id, name, old, value)
        self._drop_wires_to_vanished_ports(record)

    def _drop_wires_to_vanished_ports(self, record: NodeRecord) -> None:
        """A setting may remove ports (an Expression variable renamed): unplug their wires."""
        if is_placeholder(record.node):
            return
        inputs = {p.name for p in record.node.input_ports()}
        outputs = {p.name for p in record.node.output_ports()}
        for wire in self._wires_touching(record.id):
            if (wire.target == record.id and wire.target_port not in inputs) or (
                wire.source == record.id and wire.source_port not in outputs
            ):
                self.disconnect(wire)

    def set_input_value(self, node_id: str, port: str, value: Any, present: bool = True) -> None:
        """Set (or with ``present=False`` clear) an input's persistent JSON value."""
        record = self.record(node_id)
        state = record.input_state(port)
        old = (state.has_value, copy.deepcopy(state.value))
        state.value, state.has_value = (value, True) if present else (None, False)
        self.expire(node_id)
        self.emit(InputChanged, node_id, port, old, (present, value))

    def set_modifiers(self, node_id: str, port: str, modifiers: Iterable[str]) -> None:
        modifiers = list(modifiers)
        unknown = [m for m in modifiers if m not in MODIFIERS]
        if unknown:
            raise GraphError(f"unknown input modifier {unknown[0]!r} (use {', '.join(MODIFIERS)})")
        state = self.record(node_id).input_state(port)
        old, state.modifiers = state.modifiers, modifiers
        self.expire(node_id)
        self.emit(ModifiersChanged, node_id, port, old, modifiers)

    def set_enabled(self, node_id: str, enabled: bool) -> None:
        record = self.record(node_id)
        record.enabled = enabled
        self.expire(node_id)
        self.emit(EnabledChanged, node_id, enabled)

    def set_preview(self, node_id: str, preview: bool) -> None:
        self.record(node_id).preview = preview
        self.emit(PreviewChanged, node_id, preview)

    def move_node(self, node_id: str, position: tuple[float, float]) -> None:
        record = self.record(node_id)
        old, record.position = record.position, (float(position[0]), float(position[1]))
        self.emit(NodeMoved, node_id, old, record.position)

    def set_label(self, node_id: str, label: str) -> None:
        record = self.record(node_id)
        old, record.label = record.label, label
        self.emit(LabelChanged, node_id, old, label)

    # -- groups ---------------------------------------------------------------------
    def add_group(self, group: Group) -> Group:
        if any(g.id == group.id for g in self.groups):
            raise GraphError(f"there is already a group with id {group.id!r}")
        self.groups.append(group)
        self.emit(GroupAdded, group)
        return group

    def remove_group(self, group_id: str) -> Group:
        group = next((g for g in self.groups if g.id == group_id), None)
        if group is None:
            raise GraphError(f"there is no group with id {group_id!r}")
        self.groups.remove(group)
        self.emit(GroupRemoved, group)
        return group

    # -- topology -------------------------------------------------------------------
    def expire(self, node_id: str) -> None:
        """Mark ``node_id`` and everything downstream of it for re-solving."""
        out = self._from
        stack = [node_id]
        expired = self.expired
        expired.add(node_id)
        self.touched.add(node_id)
        while stack:
            for wire in out.get(stack.pop(), ()):
                target = wire.target
                if target not in expired:
                    expired.add(target)
                    stack.append(target)

    def expire_all(self) -> None:
        self.expired.update(self.nodes)
        self.touched.update(self.nodes)

    def upstream(self, node_id: str) -> set[str]:
        """Every node whose output reaches ``node_id`` (not including it)."""
        into = self._into
        seen: set[str] = set()
        stack = [w.source for w in into.get(node_id, ())]
        while stack:
            current = stack.pop()
            if current not in seen:
                seen.add(current)
                stack.extend(w.source for w in into.get(current, ()))
        return seen

    def reaches(self, start: str, goal: str) -> bool:
        """Whether wires lead from ``start`` down to ``goal`` (a node reaches itself).

        ``connect(goal, …, start, …)`` would make a loop exactly when this is true. With
        the ranks up to date only the nodes ranked between the two are searched.
        """
        if start == goal:
            return True
        rank = self._current_rank()
        if rank is not None and rank[start] > rank[goal]:
            return False  # every wire runs forward in the ranks
        limit = rank[goal] if rank is not None else None
        out = self._from
        seen = {start}
        stack = [start]
        while stack:
            for wire in out.get(stack.pop(), ()):
                target = wire.target
                if target == goal:
                    return True
                if target not in seen and (limit is None or rank[target] < limit):
                    seen.add(target)
                    stack.append(target)
        return False

    def _current_rank(self) -> dict[str, int] | None:
        """The ranks, computed afresh if unchecked wires made them stale (None: a loop)."""
        try:
            return self._ranks()
        except GraphError:
            return None

    def _ranks(self) -> dict[str, int]:
        """The ranks, computed afresh if unchecked wires made them stale (GraphError: a loop)."""
        if self._rank is None:
            self._rank = self._sort()
            self._next_rank = len(self._rank)
            self._order = None
        return self._rank

    def _rerank(self, source: str, target: str) -> None:
        """A new wire ``source → target`` runs backward in the ranks: move what ``target``
        feeds (up to ``source``'s rank) after what feeds ``source`` (down to ``target``'s),
        reusing the same ranks. The caller has checked there is no loop."""
        rank = self._rank
        lower, upper = rank[target], rank[source]
        forward = self._search(target, self._from, "target", lambda n: rank[n] < upper)
        backward = self._search(source, self._into, "source", lambda n: rank[n] > lower)
        moved = sorted(backward, key=rank.__getitem__) + sorted(forward, key=rank.__getitem__)
        for node_id, new_rank in zip(moved, sorted(rank[n] for n in moved), strict=True):
            rank[node_id] = new_rank
        self._order = None

    @staticmethod
    def _search(
        start: str, index: dict[str, dict[Wire, None]], end: str, inside: Callable[[str], bool]
    ) -> list[str]:
        """``start`` and the nodes reached from it through ``index`` while ``inside`` holds."""
        seen = {start}
        stack = [start]
        while stack:
            for wire in index.get(stack.pop(), ()):
                node_id = getattr(wire, end)
                if node_id not in seen and inside(node_id):
                    seen.add(node_id)
                    stack.append(node_id)
        return list(seen)

    def order(self) -> list[str]:
        """Node ids in a topological order (sources first)."""
        if self._order is None:
            rank = self._ranks()
            self._order = sorted(self.nodes, key=rank.__getitem__)
        return self._order

    def in_order(self, node_ids: Iterable[str]) -> list[str]:
        """``node_ids`` sorted into topological order (ids not in the graph are left out);
        costs what it sorts, not the graph."""
        rank = self._ranks()
        return sorted((n for n in node_ids if n in rank), key=rank.__getitem__)

    def reorder_nodes(self, order: list[str]) -> None:
        """Put the node records in ``order`` (every node id once), as a file lists them;
        the order of records never changes a solve."""
        if order != list(self.nodes):
            records = dict(self.nodes)
            self.nodes.clear()
            self.nodes.update((n, records[n]) for n in order)
            self._order = None

    def _sort(self) -> dict[str, int]:
        """Ranks from scratch (Kahn's algorithm); raises :class:`GraphError` on a loop."""
        indegree = {n: len(self._into.get(n, ())) for n in self.nodes}
        ready = [n for n, d in indegree.items() if d == 0]
        rank: dict[str, int] = {}
        while ready:
            current = ready.pop()
            rank[current] = len(rank)
            for wire in self._from.get(current, ()):
                t = wire.target
                indegree[t] -= 1
                if indegree[t] == 0:
                    ready.append(t)
        if len(rank) != len(self.nodes):
            stuck = sorted(n for n, d in indegree.items() if d > 0)
            raise GraphError(f"the wires form a loop through {', '.join(stuck[:5])}")
        return rank


class PlaceholderNode(Node):
    """Stands in for a node type that is not installed: keeps its data, solves nothing."""

    def __init__(self, type_id: str, settings: dict[str, Any] | None = None) -> None:
        super().__init__(settings)
        self.missing_type = type_id

    def name(self) -> str:  # type: ignore[override]
        return self.missing_type.split(".", 1)[-1]

    def solve(self, *args: Any) -> Any:
        return None


def is_placeholder(node: Node) -> bool:
    return isinstance(node, PlaceholderNode)
