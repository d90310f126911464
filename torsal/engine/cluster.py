"""Clusters: a sub-graph packaged as one node, as in Grasshopper.

API (what a front-end uses; each edit is a function of :mod:`torsal.engine.cluster_edits`
that takes the graph and works through its public methods, one edit, one undo step)::

    from torsal.engine.cluster import ClusterNode, ClusterInput, ClusterOutput, is_cluster
    from torsal.engine.cluster_edits import make_cluster, explode_cluster, definition_of, ...

    cid = make_cluster(graph, node_ids, name="Panels")    # -> the new cluster node's id
    did = graph.nodes[cid].node.definition.id            # its definition's id
        # undo: explode_cluster(graph, cid) (puts back the same ids, records, wires, groups)
        # redo: make_cluster(graph, node_ids, name, node_id=cid, definition_id=did)
    info = cluster_instance(graph, cid)                   # capture before exploding (for undo)
    ids = explode_cluster(graph, cid)                     # -> ids of the restored nodes
        # undo: restore_cluster(graph, info, ids)
    other = add_cluster_instance(graph, did, position=(x, y))   # a second instance (undo: remove it)
    definition = definition_of(graph, cid_or_definition_id)    # ClusterDefinition
    graph.clusters                                       # {definition id: ClusterDefinition}
    definition.name, definition.id, definition.input_names(), definition.output_names()
    editable = cluster_graph(graph, definition_id)        # a copy of the inner Graph to edit
    change = set_cluster_graph(graph, definition_id, editable)   # commit: every instance updates
        # undo: set_cluster_graph(graph, definition_id, change.previous, change.previous_inputs,
        #       change.previous_outputs), then reconnect change.dropped (outer wires to ports
        #       that vanished)
    old = rename_cluster_port(graph, definition_id, "input", "Step", "Width")   # undo: swap names
        # (a port's name is its boundary node's label: renaming the node in an edited copy
        # and committing it does the same)
    old_order = reorder_cluster_ports(graph, definition_id, "output", ["B", "A"])   # undo: old_order
    rename_cluster(graph, definition_id, "New name")      # -> old name
    solver.cluster_solver(cid)                           # the inner Solver of one instance (or None)
    feed_inputs(editable, solver.cluster_inputs(cid))    # show an instance's values while editing
    fragment_clusters(graph, ids) / adopt_clusters(graph, records)   # engine.graphfile: copy, paste

Inside a definition's graph the ports are nodes: one :class:`ClusterInput` per input
(``cluster.Input``, no inputs, one tree output ``Value``) and one :class:`ClusterOutput`
per output (``cluster.Output``, a tree input ``Value`` passed through). A port's *name*
is its boundary node's label (``Input``/``Output`` when empty; repeats get `` 2``,
`` 3``...); the *order* of the ports is the definition's ``inputs``/``outputs`` list of
boundary node ids. So editing the definition in the ordinary canvas (add an Input node,
rename it, delete it) edits the ports; :meth:`Graph.set_cluster_graph` carries that to
every instance (outer wires follow a renamed port; wires to a vanished port are dropped
and returned).

Edits that change an instance's ports tell listeners with ``SettingChanged(instance,
"definition", id, id)`` (the canvas redraws the node); the rest are the usual node and
wire events. Edits the file could not hold are refused with :class:`GraphError`: a
definition containing itself, nesting past :data:`MAX_NESTING`, or clusters expanding
past :data:`MAX_EXPANDED_NODES` nodes.

A :class:`ClusterNode` (``cluster.Cluster``) refers to its definition by id (its
``settings["definition"]``); several instances share one definition object. Its ports are
tree-access ports, so the inner graph sees the very trees (paths, branches) the expanded
graph would; modifiers set on a cluster port (graft...) apply before the tree goes in.
A cluster input neither wired nor given a value is left out of the instance's inner copy,
so the inner inputs it feeds use their own values or defaults, as in the expanded graph.
An input port's type is the type of the inner ports it feeds when they agree (else
Generic); an output's the type of the inner output wired to it.

Definitions live in ``graph.clusters``, a dict shared by the document's graph and every
inner graph (so clusters nest; a definition may not contain itself, and nesting stops at
:data:`MAX_NESTING`).

Solving (see :mod:`torsal.engine.solver`): each instance gets, per solver, a private copy of the
definition's graph with its own inner solver, so an instance re-solves only the inner
nodes downstream of the inputs whose trees changed; a committed definition (its
``revision`` moves on) rebuilds the copy and solves it afresh. The cluster node ends in
the worst state of its inner nodes, shows that worst message naming the inner node
("Panel heights: ..."), and keeps the outputs the inner graph produced. Outside, a node
fed only by cluster outputs that came out as the very same trees keeps its result.

The cluster types are not in the node catalogue: :mod:`torsal.engine.graphfile` builds them,
and front-ends make them with :meth:`Graph.make_cluster` (and, for a port added while
editing a definition, ``edited.add_node(ClusterInput(), label="Width")`` or
``ClusterOutput()``).
"""

from __future__ import annotations

import copy
from collections.abc import Iterable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from torsal.engine.datatree import DataTree
from torsal.engine.node import TREE, In, Node, NodeError, Out
from torsal.engine.types import GENERIC, ValueType

if TYPE_CHECKING:
    from torsal.engine.graph import Graph, Group, NodeRecord, Wire

CLUSTER_TYPE = "cluster.Cluster"
INPUT_TYPE = "cluster.Input"
OUTPUT_TYPE = "cluster.Output"
BUILTIN_TYPES = (CLUSTER_TYPE, INPUT_TYPE, OUTPUT_TYPE)
#: How deeply clusters may sit inside clusters (a file nesting deeper is refused).
MAX_NESTING = 16
PORT = "Value"  # the one port of a boundary node
#: The most nodes a file's clusters may expand to (each instance solves its own copy of
#: its definition, so a small file nesting many instances could otherwise ask for
#: millions of solves).
MAX_EXPANDED_NODES = 200_000


class ClusterInput(Node):
    """One input of a cluster, inside its definition: gives the tree the cluster receives."""

    type_id = INPUT_TYPE
    outputs = (Out(PORT, GENERIC, "V", "The tree wired into this input of the cluster.", access=TREE),)

    def __init__(self, settings: dict[str, Any] | None = None) -> None:
        super().__init__(settings)
        self.feed = DataTree()  # set by the instance's solve (on its private copy only)

    def solve(self) -> DataTree:
        return self.feed


class ClusterOutput(Node):
    """One output of a cluster, inside its definition: what is wired here leaves the cluster."""

    type_id = OUTPUT_TYPE
    inputs = (In(PORT, GENERIC, "V", "The tree this output of the cluster gives.", access=TREE,
                 optional=True),)
    outputs = (Out(PORT, GENERIC, "V", access=TREE),)

    def solve(self, tree: DataTree) -> DataTree:
        return tree


@dataclass(eq=False)
class ClusterDefinition:
    """A cluster's inner graph and its ordered ports (ids of its boundary nodes)."""

    id: str
    name: str
    graph: Graph
    inputs: list[str] = field(default_factory=list)
    outputs: list[str] = field(default_factory=list)
    #: the point of the inner canvas that sits at an instance's position (explode keeps
    #: the inner layout relative to it)
    anchor: tuple[float, float] = (0.0, 0.0)
    #: moves on at every committed change: instances' solvers rebuild their copies
    revision: int = 0
    raw: dict[str, Any] = field(default_factory=dict)
    _in_ports: tuple[In, ...] = field(default=(), repr=False)
    _out_ports: tuple[Out, ...] = field(default=(), repr=False)

    def __post_init__(self) -> None:
        self.refresh()

    # -- ports ----------------------------------------------------------------------
    def refresh(self) -> None:
        """Recompute the ports from the boundary nodes (after the inner graph changed)."""
        self._in_ports = tuple(
            In(name, self._input_type(node_id), access=TREE, optional=True,
               description=f"Into the cluster's {name!r}.")
            for name, node_id in zip(self.input_names(), self.inputs, strict=True)
        )
        self._out_ports = tuple(
            Out(name, self._output_type(node_id), access=TREE, description=f"The cluster's {name!r}.")
            for name, node_id in zip(self.output_names(), self.outputs, strict=True)
        )

    def input_ports(self) -> tuple[In, ...]:
        return self._in_ports

    def output_ports(self) -> tuple[Out, ...]:
        return self._out_ports

    def input_names(self) -> list[str]:
        return _unique_names([self._label(n, "Input") for n in self.inputs])

    def output_names(self) -> list[str]:
        return _unique_names([self._label(n, "Output") for n in self.outputs])

    def port_nodes(self, kind: str) -> dict[str, str]:
        """``{port name: boundary node id}`` of the ``"input"`` or ``"output"`` ports."""
        if kind == "input":
            return dict(zip(self.input_names(), self.inputs, strict=True))
        if kind == "output":
            return dict(zip(self.output_names(), self.outputs, strict=True))
        raise ValueError(f"a cluster port is an 'input' or an 'output', not {kind!r}")

    def _label(self, node_id: str, fallback: str) -> str:
        record = self.graph.nodes.get(node_id)
        return (record.label.strip() if record is not None else "") or fallback

    def _input_type(self, node_id: str) -> ValueType:
        graph = self.graph
        types = []
        for wire in graph.wires_from(node_id):
            port = graph.nodes[wire.target].node.input_port(wire.target_port)
            if port is not None:
                types.append(port.type)
        return types[0] if types and all(t is types[0] for t in types) else GENERIC

    def _output_type(self, node_id: str) -> ValueType:
        graph = self.graph
        wires = graph.wires_into(node_id) if node_id in graph.nodes else []
        if len(wires) != 1:
            return GENERIC
        port = graph.nodes[wires[0].source].node.output_port(wires[0].source_port)
        return port.type if port is not None else GENERIC

    def used_definitions(self) -> set[str]:
        """Ids of the definitions whose instances sit directly in this one's graph."""
        return {r.node.definition.id for r in self.graph.nodes.values() if isinstance(r.node, ClusterNode)}


def _unique_names(names: list[str]) -> list[str]:
    seen: set[str] = set()
    out = []
    for name in names:
        candidate, n = name, 2
        while candidate in seen:
            candidate = f"{name} {n}"
            n += 1
        seen.add(candidate)
        out.append(candidate)
    return out


class ClusterNode(Node):
    """An instance of a cluster: its ports are its definition's; the solver solves its
    inner graph (see the module docstring)."""

    type_id = CLUSTER_TYPE
    # ``settings["definition"]`` names the definition in the file; it has no Setting entry,
    # so an inspector does not offer it for editing (``definition`` is the object itself)

    def __init__(self, definition: ClusterDefinition, settings: dict[str, Any] | None = None) -> None:
        super().__init__({**(settings or {}), "definition": definition.id})
        self.definition = definition
        #: groups each node was in when clustered (explode puts them back; not saved)
        self.origin_groups: dict[str, list[str]] = {}
        self.origin_members: dict[str, list[str]] = {}  # those groups' members, in order
        #: the graph's node ids and wires, in order, when this cluster was made
        self.origin_order: tuple[list[str], list[Any]] | None = None
        self.origin_group_order: list[str] = []  # and its groups' ids

    def name(self) -> str:  # type: ignore[override]
        return self.definition.name or "Cluster"

    def input_ports(self) -> tuple[In, ...]:
        return self.definition.input_ports()

    def output_ports(self) -> tuple[Out, ...]:
        return self.definition.output_ports()

    def solve(self, *args: Any) -> Any:
        raise NodeError("a cluster is solved by the solver, through its inner graph")


def is_cluster(node: Node) -> bool:
    return isinstance(node, ClusterNode)


def is_boundary(node: Node) -> bool:
    return isinstance(node, ClusterInput | ClusterOutput)


def feed_inputs(graph: Graph, trees: dict[str, DataTree]) -> None:
    """Give the Input nodes of ``graph`` (a definition's copy being edited) the trees an
    instance receives (``solver.cluster_inputs(cluster_id)``), so the editor shows that
    instance's values. A committed definition never keeps them."""
    for node_id, tree in trees.items():
        record = graph.nodes.get(node_id)
        if record is not None and isinstance(record.node, ClusterInput):
            record.node.feed = tree
            graph.expire(node_id)


# --------------------------------------------------------------------------- copies

def clone_node(node: Node) -> Node:
    """A copy of a node object with its own settings (a cluster keeps its definition)."""
    twin = copy.copy(node)
    twin.settings = copy.deepcopy(node.settings)
    twin._own = None
    if isinstance(twin, ClusterInput):
        twin.feed = DataTree()
    if isinstance(twin, ClusterNode):
        twin.origin_groups, twin.origin_members, twin.origin_order = {}, {}, None
        twin.origin_group_order = []
    return twin


def clone_record(record: NodeRecord, node_id: str | None = None) -> NodeRecord:
    from torsal.engine.graph_records import InputState, NodeRecord

    inputs = {
        name: InputState(copy.deepcopy(s.value), s.has_value, list(s.modifiers), copy.deepcopy(s.raw))
        for name, s in record.inputs.items()
    }
    return NodeRecord(
        node_id or record.id, clone_node(record.node), record.type_id, record.label, record.position,
        inputs, record.preview, record.enabled, copy.deepcopy(record.raw),
    )


def clone_graph(graph: Graph) -> Graph:
    """A copy of ``graph`` (nodes, wires, groups) sharing its cluster definitions."""
    from torsal.engine.graph_records import Group, Wire

    twin = type(graph)()
    twin.clusters = graph.clusters
    twin.units, twin.meta, twin.raw = graph.units, copy.deepcopy(graph.meta), copy.deepcopy(graph.raw)
    for record in graph.nodes.values():
        twin.add_record(clone_record(record))
    for wire in graph.wires:
        twin.connect_wire(Wire(wire.source, wire.source_port, wire.target, wire.target_port, raw=wire.raw),
                          check_loops=False)
    twin.groups = [Group(g.id, g.title, g.colour, list(g.nodes), copy.deepcopy(g.raw)) for g in graph.groups]
    twin.expire_all()
    return twin


# --------------------------------------------------------------------------- instances

def instances(graph: Graph, definition_id: str) -> list[str]:
    """Ids of the nodes of ``graph`` that are instances of ``definition_id``."""
    return [n for n, r in graph.nodes.items()
            if isinstance(r.node, ClusterNode) and r.node.definition.id == definition_id]


def used_anywhere(graph: Graph, definition_id: str, besides: str | None = None) -> bool:
    """Whether ``graph`` (or a definition's graph) holds an instance of ``definition_id``
    other than the node ``besides`` of ``graph``."""
    if any(n != besides for n in instances(graph, definition_id)):
        return True
    return any(instances(d.graph, definition_id) for d in graph.clusters.values() if d.id != definition_id)


def containing(clusters: dict[str, ClusterDefinition], definition_id: str) -> set[str]:
    """Ids of the definitions that contain ``definition_id``, directly or deeper."""
    found: set[str] = set()
    frontier = {definition_id}
    while frontier:
        frontier = {d.id for d in clusters.values()
                    if d.id not in found and d.used_definitions() & frontier}
        found |= frontier
    return found


def nesting_problem(clusters: dict[str, ClusterDefinition]) -> str | None:
    """A sentence if a definition contains itself or clusters nest deeper than
    :data:`MAX_NESTING`; None when all is well."""
    return nesting_problem_of({d.id: d.used_definitions() for d in clusters.values()})


def nesting_problem_of(uses: dict[str, set[str]]) -> str | None:
    """:func:`nesting_problem` from ``{definition id: ids of the definitions it uses}``
    (ids not in ``uses`` are ignored). Walks without recursion."""
    depth: dict[str, int] = {}
    for root in sorted(uses):
        if root in depth:
            continue
        path = [root]
        stack = [iter(sorted(uses[root]))]
        while stack:
            child = next(stack[-1], None)
            if child is None:
                done = path.pop()
                stack.pop()
                depth[done] = 1 + max((depth[c] for c in uses[done] if c in depth), default=0)
                if depth[done] > MAX_NESTING:
                    return f"clusters are nested more than {MAX_NESTING} deep (through {done!r})"
                continue
            if child not in uses or child in depth:
                continue
            if child in path:
                loop = [*path[path.index(child):], child]
                return f"cluster definition {child!r} contains itself ({' → '.join(loop)})"
            path.append(child)
            stack.append(iter(sorted(uses[child])))
    return None


def expanded_size(graph: Graph) -> int:
    """How many nodes ``graph`` would have with every cluster expanded (instances inside
    instances multiply; each instance counts one besides its contents, so a nest of empty
    definitions is counted too), counted only to one past :data:`MAX_EXPANDED_NODES`."""
    size: dict[int, int] = {}

    def of(nodes: Iterable[NodeRecord]) -> int:
        total = 0
        for record in nodes:
            node = record.node
            if isinstance(node, ClusterNode):
                key = id(node.definition)
                if key not in size:
                    size[key] = MAX_EXPANDED_NODES + 1  # a loop (refused elsewhere) counts as too many
                    size[key] = of(node.definition.graph.nodes.values())
                total += 1 + size[key]  # an instance costs one, even of an empty definition
            else:
                total += 1
            if total > MAX_EXPANDED_NODES:
                return MAX_EXPANDED_NODES + 1
        return total

    return of(graph.nodes.values())


def definition_depth(definition: ClusterDefinition) -> int:
    """1 for a definition holding no clusters, one more per level of clusters inside."""
    inner = [r.node.definition for r in definition.graph.nodes.values() if isinstance(r.node, ClusterNode)]
    return 1 + max((definition_depth(d) for d in {id(d): d for d in inner}.values()), default=0)


def dependency_order(uses: dict[str, set[str]]) -> list[str]:
    """Definition ids so that each comes after those it uses (call after
    :func:`nesting_problem_of` found no loop)."""
    order: list[str] = []
    placed: set[str] = set()

    def place(def_id: str) -> None:
        stack = [(def_id, iter(sorted(uses[def_id])))]
        while stack:
            current, children = stack[-1]
            child = next(children, None)
            if child is None:
                stack.pop()
                if current not in placed:
                    placed.add(current)
                    order.append(current)
            elif child in uses and child not in placed:
                stack.append((child, iter(sorted(uses[child]))))

    for def_id in sorted(uses):
        place(def_id)
    return order


def reachable_definitions(graph: Graph) -> list[ClusterDefinition]:
    """The definitions ``graph``'s clusters use, directly or inside others, sorted by id."""
    found: dict[str, ClusterDefinition] = {}
    stack = [r.node.definition for r in graph.nodes.values() if isinstance(r.node, ClusterNode)]
    while stack:
        definition = stack.pop()
        if definition.id in found:
            continue
        found[definition.id] = definition
        stack.extend(r.node.definition for r in definition.graph.nodes.values()
                     if isinstance(r.node, ClusterNode))
    return [found[k] for k in sorted(found)]


@dataclass
class ClusterInstance:
    """What :meth:`Graph.restore_cluster` needs to undo an explode: the cluster's record,
    its wires, its definition and groups (capture it with :meth:`Graph.cluster_instance`)."""

    record: NodeRecord
    wires: list[Wire]
    definition: ClusterDefinition
    groups: list[Group]
    group_ids: list[str] = field(default_factory=list)  # every group of the graph then
    order: tuple[list[str], list[Wire]] = ([], [])  # the graph's nodes and wires, in order
    members: dict[str, list[str]] = field(default_factory=dict)  # ``groups``' members, in order


@dataclass
class DefinitionChange:
    """What :meth:`Graph.set_cluster_graph` replaced: the previous inner graph and ports,
    and the outer wires it dropped (their port vanished)."""

    previous: Graph
    previous_inputs: list[str]
    previous_outputs: list[str]
    dropped: list[Wire] = field(default_factory=list)


def ordered_unique(items: Iterable[str]) -> list[str]:
    return list(dict.fromkeys(items))
