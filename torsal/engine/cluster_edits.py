"""The cluster edits of a :class:`~torsal.engine.graph.Graph`: make, explode, restore, commit a
definition, rename and reorder its ports (the :class:`Graph` methods of those names call
these; see :mod:`torsal.engine.cluster` for the model).

Each edit checks everything it can before it changes anything, then makes its change
through the graph's own validated edits, so listeners hear the usual events (nodes and
wires removed and added) plus a ``SettingChanged(node, "definition", id, id)`` for every
instance whose ports may have changed (the canvas redraws a node on it).
"""

from __future__ import annotations

import copy
from typing import TYPE_CHECKING

from torsal.engine.cluster import (
    CLUSTER_TYPE,
    INPUT_TYPE,
    MAX_EXPANDED_NODES,
    MAX_NESTING,
    OUTPUT_TYPE,
    PORT,
    ClusterDefinition,
    ClusterInput,
    ClusterInstance,
    ClusterNode,
    ClusterOutput,
    DefinitionChange,
    _unique_names,
    clone_graph,
    clone_record,
    containing,
    definition_depth,
    expanded_size,
    instances,
    is_boundary,
    nesting_problem,
    ordered_unique,
    reachable_definitions,
    used_anywhere,
)
from torsal.engine.events import SettingChanged

if TYPE_CHECKING:
    from torsal.engine.graph import Graph, InputState, NodeRecord, Wire

#: how far the boundary nodes sit left and right of the inner nodes, and apart
_MARGIN_X, _STEP_Y = 260.0, 90.0


def _error(text: str) -> Exception:
    from torsal.engine.graph_records import GraphError

    return GraphError(text)


def _touching(graph: Graph, node_ids: list[str]) -> list[Wire]:
    """The wires into or out of any of ``node_ids``, in the graph's wire order."""
    found: dict[Wire, None] = {}
    for node_id in node_ids:
        for wire in graph.wires_into(node_id):
            found[wire] = None
        for wire in graph.wires_from(node_id):
            found[wire] = None
    serial = {wire: i for i, wire in enumerate(graph.wires)}
    return sorted(found, key=serial.__getitem__)


def _check_closed(graph: Graph, chosen: set[str]) -> None:
    """Refuse a selection that outside nodes both take from and feed (collapsing it would
    make a loop through the cluster)."""
    stack = [w.target for n in chosen for w in graph.wires_from(n) if w.target not in chosen]
    reached: set[str] = set()
    while stack:
        current = stack.pop()
        if current in reached:
            continue
        reached.add(current)
        for wire in graph.wires_from(current):
            if wire.target in chosen:
                raise _error(
                    f"{graph.nodes[current].title} takes data from the selection and feeds it back: "
                    "put it in the cluster too, or leave out the nodes it feeds"
                )
            stack.append(wire.target)


def _fresh_definition_id(graph: Graph, name: str) -> str:
    """An id no definition in ``graph.clusters`` or used by ``graph``'s clusters has."""
    stem = "".join(c for c in name.lower() if c.isalnum() or c in "_-") or "cluster"
    taken = set(graph.clusters) | {d.id for d in reachable_definitions(graph)}
    candidate, n = stem, 2
    while candidate in taken:
        candidate = f"{stem}{n}"
        n += 1
    return candidate


def _port_orders(graph: Graph, wires: list[Wire],
                 replaced: dict[Wire, list[Wire]]) -> dict[tuple[str, str], list[Wire]]:
    """For each outside input port some of ``replaced`` run into and that takes more than
    one wire: the order its wires should have after the replacement."""
    orders: dict[tuple[str, str], list[Wire]] = {}
    for wire in wires:
        key = (wire.target, wire.target_port)
        if key in orders:
            continue
        feeding = graph.wires_into(wire.target, wire.target_port)
        if len(feeding) > 1:
            orders[key] = [new for old in feeding for new in replaced.get(old, [old])]
    return orders


def _restore_orders(graph: Graph, orders: dict[tuple[str, str], list[Wire]]) -> None:
    """Reconnect the wires into each port in the order given (merges depend on it)."""
    for (target, port), wanted in orders.items():
        wanted = ordered_unique_wires(wanted)
        if graph.wires_into(target, port) == wanted:
            continue
        for wire in graph.wires_into(target, port):
            graph.disconnect(wire)
        for wire in wanted:
            graph.connect_wire(wire)


def _exposed_names(graph: Graph, ports: list[tuple[str, str]]) -> list[str]:
    """The names of a new cluster's ports, after the inner ports they expose: the port's
    own name ("Factor") when no other port of that side shares it, else the inner node's
    title before it ("Copied up Geometry", "Scaled inwards Geometry"), so two outputs are
    never "Geometry" and "Geometry 2". Renamed later in the cluster's ports dialog."""
    counts: dict[str, int] = {}
    for _node, port in ports:
        counts[port] = counts.get(port, 0) + 1
    names = []
    for node_id, port in ports:
        if counts[port] == 1:
            names.append(port)
            continue
        title = graph.nodes[node_id].title
        names.append(port if title == port else f"{title} {port}")
    return _unique_names(names)


def ordered_unique_wires(wires: list[Wire]) -> list[Wire]:
    return list(dict.fromkeys(wires))


# --------------------------------------------------------------------------- make

def make_cluster(graph: Graph, node_ids: list[str], name: str = "Cluster", *, node_id: str | None = None,
                 definition_id: str | None = None) -> str:
    """Collapse ``node_ids`` into one new cluster node; returns its id.

    One input per distinct outside output (node and port) that feeds the selection,
    named after the first inner input it feeds; one output per inner output that feeds
    outside nodes, named after that output; repeated names get `` 2``, `` 3``. Inputs
    are ordered by the position of their outside source (top to bottom), outputs by that
    of their first outside target. The inner nodes keep their ids, settings, values and
    positions (the cluster sits at the centre of their bounding box, the definition's
    anchor); groups wholly inside the selection go inside; the cluster joins the groups
    the selection shared with other nodes.
    """
    from torsal.engine.graph_records import Wire

    ids = ordered_unique(node_ids)
    if not ids:
        raise _error("select the nodes to put in the cluster")
    records = [graph.record(n) for n in ids]
    chosen = set(ids)
    for record in records:
        if is_boundary(record.node):
            raise _error(f"{record.title} is a port of the cluster being edited; it cannot go into a cluster")
    name = name.strip() or "Cluster"
    if node_id is not None and node_id in graph.nodes and node_id not in chosen:
        raise _error(f"there is already a node with id {node_id!r}")
    if definition_id is not None and definition_id in graph.clusters:
        raise _error(f"there is already a cluster definition with id {definition_id!r}")
    _check_closed(graph, chosen)
    inner_depth = max((definition_depth(r.node.definition) for r in records
                       if isinstance(r.node, ClusterNode)), default=0)
    if inner_depth + 1 > MAX_NESTING:
        raise _error(f"clusters may nest {MAX_NESTING} deep; this one would nest {inner_depth + 1} deep")

    touching = _touching(graph, ids)
    incoming = [w for w in touching if w.source not in chosen]
    outgoing = [w for w in touching if w.target not in chosen]
    order_of = {w: i for i, w in enumerate(touching)}

    def position(node_id: str) -> tuple[float, float]:
        return graph.nodes[node_id].position

    in_keys = ordered_unique((w.source, w.source_port) for w in incoming)
    first_in = {k: next(w for w in incoming if (w.source, w.source_port) == k) for k in in_keys}
    in_keys.sort(key=lambda k: (position(first_in[k].source)[1], position(first_in[k].source)[0],
                                order_of[first_in[k]]))
    out_keys = ordered_unique((w.source, w.source_port) for w in outgoing)
    first_out = {k: next(w for w in outgoing if (w.source, w.source_port) == k) for k in out_keys}

    def out_place(key: tuple[str, str]) -> tuple[float, float, int]:
        targets = [w for w in outgoing if (w.source, w.source_port) == key]
        top = min(targets, key=lambda w: (position(w.target)[1], position(w.target)[0]))
        return (position(top.target)[1], position(top.target)[0], order_of[first_out[key]])

    out_keys.sort(key=out_place)
    in_names = _exposed_names(graph, [(first_in[k].target, first_in[k].target_port) for k in in_keys])
    out_names = _exposed_names(graph, [(k[0], k[1]) for k in out_keys])

    xs = [r.position[0] for r in records]
    ys = [r.position[1] for r in records]
    centre = ((min(xs) + max(xs)) / 2.0, (min(ys) + max(ys)) / 2.0)
    feeding_orders = _port_orders(graph, outgoing, {})  # outside ports: their wire order before
    groups_of = {n: [g.id for g in graph.groups if n in g.nodes] for n in ids}
    inside_groups = [g for g in graph.groups if g.nodes and set(g.nodes) <= chosen]
    shared_groups = [g for g in graph.groups if g not in inside_groups and chosen & set(g.nodes)]
    members_before = {g.id: list(g.nodes) for g in shared_groups}
    nodes_before, wires_before, groups_before = list(graph.nodes), graph.wires, [g.id for g in graph.groups]

    # -- the change: nothing above has touched the graph
    graph.remove_many(ids)
    inner = type(graph)()
    inner.clusters = graph.clusters
    inner.units = graph.units
    for record in records:
        inner.add_record(record)
    in_ids: dict[tuple[str, str], str] = {}  # (outside source node, port) → its Input node
    for index, (key, port_name) in enumerate(zip(in_keys, in_names, strict=True)):
        place = (min(xs) - _MARGIN_X, min(ys) + index * _STEP_Y)
        boundary = inner.add_node(ClusterInput(), inner.new_id(f"input_{port_name}"), label=port_name,
                                  position=place, type_id=INPUT_TYPE)
        in_ids[key] = boundary.id
    out_ids: dict[tuple[str, str], str] = {}  # (inner source node, port) → its Output node
    for index, (key, port_name) in enumerate(zip(out_keys, out_names, strict=True)):
        place = (max(xs) + _MARGIN_X, min(ys) + index * _STEP_Y)
        boundary = inner.add_node(ClusterOutput(), inner.new_id(f"output_{port_name}"), label=port_name,
                                  position=place, type_id=OUTPUT_TYPE)
        out_ids[key] = boundary.id
    wired_out: set[tuple[str, str]] = set()
    for wire in touching:
        key = (wire.source, wire.source_port)
        if wire.source in chosen and wire.target in chosen:
            inner.connect_wire(wire, check_loops=False)
        elif wire.source not in chosen:
            inner.connect_wire(Wire(in_ids[key], PORT, wire.target, wire.target_port), check_loops=False)
        elif key not in wired_out:
            wired_out.add(key)
            inner.connect_wire(Wire(wire.source, wire.source_port, out_ids[key], PORT), check_loops=False)
    inner.order()
    for group in inside_groups:
        graph.remove_group(group.id)
        group.nodes = [n for n in ids if group.id in groups_of[n]]
        inner.groups.append(group)

    definition_id = definition_id or _fresh_definition_id(graph, name)
    definition = ClusterDefinition(definition_id, name, inner, [in_ids[k] for k in in_keys],
                                   [out_ids[k] for k in out_keys], anchor=centre)
    graph.clusters[definition_id] = definition
    node = ClusterNode(definition)
    cluster_id = node_id or graph.new_id(name)
    graph.add_node(node, cluster_id, position=centre, type_id=CLUSTER_TYPE)
    # the cluster takes its first node's place in the node order (and the file's)
    first = min(nodes_before.index(n) for n in ids)
    _reorder_nodes(graph, [*(n for n in nodes_before[:first]), cluster_id,
                           *(n for n in nodes_before[first:] if n not in chosen)])
    in_name = dict(zip(in_keys, in_names, strict=True))
    out_name = dict(zip(out_keys, out_names, strict=True))
    replaced: dict[Wire, list[Wire]] = {}
    connected: set[tuple[str, str]] = set()
    for wire in touching:
        key = (wire.source, wire.source_port)
        if wire.source not in chosen and key not in connected:
            connected.add(key)
            graph.connect_wire(Wire(wire.source, wire.source_port, cluster_id, in_name[key]))
        elif wire.target not in chosen:
            new = Wire(cluster_id, out_name[key], wire.target, wire.target_port)
            graph.connect_wire(new)
            replaced[wire] = [new]
    _restore_orders(graph, {key: [new for old in wires for new in replaced.get(old, [old])]
                            for key, wires in feeding_orders.items()})
    kept_groups = {g.id for g in shared_groups}
    for group in shared_groups:  # in each group, the cluster takes its first member's place
        before = members_before[group.id]
        first = min(before.index(n) for n in chosen if n in before)
        group.nodes.insert(len([n for n in before[:first] if n not in chosen]), cluster_id)
    node.origin_groups = {n: [g for g in groups_of[n] if g in kept_groups] for n in ids}
    node.origin_members = members_before
    node.origin_order = (nodes_before, wires_before)
    node.origin_group_order = groups_before
    return cluster_id


def add_cluster_instance(graph: Graph, definition_id: str, node_id: str | None = None,
                         position: tuple[float, float] = (0.0, 0.0)) -> str:
    """Add another instance of a definition (it shares the definition); returns its id.
    Undo: ``graph.remove_node(id)``."""
    definition = definition_of(graph, definition_id)
    if definition.id not in graph.clusters:
        graph.clusters[definition.id] = definition
    record = graph.add_node(ClusterNode(definition), node_id or graph.new_id(definition.name),
                            position=position, type_id=CLUSTER_TYPE)
    if expanded_size(graph) > MAX_EXPANDED_NODES:
        graph.remove_node(record.id)
        raise _error(f"with another {definition.name!r} the graph would expand to more than "
                     f"{MAX_EXPANDED_NODES:,} nodes (a file Torsal refuses to open)")
    return record.id


# --------------------------------------------------------------------------- explode

def cluster_instance(graph: Graph, node_id: str) -> ClusterInstance:
    """What :func:`restore_cluster` needs to undo :func:`explode_cluster` of ``node_id``."""
    record = _cluster_record(graph, node_id)
    wires = _touching(graph, [node_id])
    groups = [g for g in graph.groups if node_id in g.nodes]
    return ClusterInstance(record, wires, record.node.definition, groups, [g.id for g in graph.groups],
                           (list(graph.nodes), graph.wires), {g.id: list(g.nodes) for g in groups})


def _cluster_record(graph: Graph, node_id: str) -> NodeRecord:
    record = graph.record(node_id)
    if not isinstance(record.node, ClusterNode):
        raise _error(f"{record.title} is not a cluster")
    return record


def _free_id(graph: Graph, wanted: str, taken: set[str], leaving: str) -> str:
    def free(candidate: str) -> bool:
        return (candidate not in graph.nodes or candidate == leaving) and candidate not in taken

    if free(wanted):
        return wanted
    n = 2
    while not free(f"{wanted}{n}"):
        n += 1
    return f"{wanted}{n}"


def explode_cluster(graph: Graph, node_id: str) -> list[str]:
    """Put a cluster's inner nodes in its place (their layout kept relative to the cluster's
    position), wired as the cluster was; remove the cluster node, and its definition when
    nothing else uses it. Returns the new nodes' ids (their inner ids where free).

    Modifiers set on a cluster input (graft...), and the value of an unwired one, move onto
    the inner inputs it feeds that take nothing else.
    """
    from torsal.engine.graph_records import GraphError, Wire

    record = _cluster_record(graph, node_id)
    node: ClusterNode = record.node  # type: ignore[assignment]
    definition = node.definition
    inner = definition.graph
    dx, dy = record.position[0] - definition.anchor[0], record.position[1] - definition.anchor[1]
    body = [r for r in inner.nodes.values() if not is_boundary(r.node)]
    mapping: dict[str, str] = {}
    for inner_record in body:  # the cluster goes before its nodes come: its id is free for them
        mapping[inner_record.id] = _free_id(graph, inner_record.id, set(mapping.values()), node_id)
    new_records = []
    for inner_record in body:
        clone = clone_record(inner_record, mapping[inner_record.id])
        if dx or dy:
            clone.position = (inner_record.position[0] + dx, inner_record.position[1] + dy)
        new_records.append(clone)
    input_names = {n: name for name, n in definition.port_nodes("input").items()}
    output_names = {n: name for name, n in definition.port_nodes("output").items()}
    outer_in: dict[str, list[Wire]] = {}
    for wire in graph.wires_into(node_id):
        outer_in.setdefault(wire.target_port, []).append(wire)

    def sources(inner_wire: Wire) -> list[tuple[str, str]]:
        """The outer (node, port) ends an inner wire's source stands for."""
        if inner_wire.source in input_names:
            return [(w.source, w.source_port) for w in outer_in.get(input_names[inner_wire.source], [])]
        if inner_wire.source in output_names:  # an Output node wired on inside: what feeds it
            return [end for w in inner.wires_into(inner_wire.source) for end in sources(w)]
        return [(mapping[inner_wire.source], inner_wire.source_port)]

    wires: list[Wire] = []
    for inner_wire in inner.wires:
        if inner_wire.target in output_names or inner_wire.target not in mapping:
            continue
        for source, port in sources(inner_wire):
            raw = inner_wire.raw if inner_wire.source in mapping else {}
            wires.append(Wire(source, port, mapping[inner_wire.target], inner_wire.target_port, raw=raw))
    outgoing = graph.wires_from(node_id)
    replaced: dict[Wire, list[Wire]] = {}
    late: list[Wire] = []
    for wire in outgoing:
        out_node = definition.port_nodes("output").get(wire.source_port)
        ends = []
        for inner_wire in inner.wires_into(out_node) if out_node in inner.nodes else []:
            ends.extend(Wire(s, p, wire.target, wire.target_port) for s, p in sources(inner_wire))
        replaced[wire] = ends
        late.extend(ends)
    # a cluster input's modifiers, and its value when unwired, go onto the inner inputs it
    # alone feeds
    carried: dict[tuple[str, str], tuple[InputState, bool]] = {}
    for name, state in record.inputs.items():
        boundary = definition.port_nodes("input").get(name)
        unwired_value = state.has_value and not outer_in.get(name)
        if not (state.modifiers or unwired_value) or boundary not in inner.nodes:
            continue
        for inner_wire in inner.wires_from(boundary):
            if inner_wire.target in mapping and len(
                    inner.wires_into(inner_wire.target, inner_wire.target_port)) == 1:
                carried[(mapping[inner_wire.target], inner_wire.target_port)] = (state, unwired_value)
    for clone in new_records:
        for (target, port), (state, unwired_value) in carried.items():
            if target == clone.id:
                mine = clone.input_state(port)
                mine.modifiers = [*state.modifiers, *mine.modifiers]
                if unwired_value:
                    mine.value, mine.has_value = copy.deepcopy(state.value), True
    feeding_orders = _port_orders(graph, outgoing, replaced)
    cluster_groups = [g for g in graph.groups if node_id in g.nodes]
    info = cluster_instance(graph, node_id)
    nodes_before = list(graph.nodes)
    members_before = {g.id: list(g.nodes) for g in cluster_groups}

    graph.remove_node(node_id)
    try:
        graph.add_many(new_records, ordered_unique_wires(wires))
        for wire in ordered_unique_wires(late):
            if not graph.has_wire(wire):
                graph.connect_wire(wire)
    except GraphError:
        for wire in ordered_unique_wires(late):
            if graph.has_wire(wire):
                graph.disconnect(wire)
        if all(r.id in graph.nodes for r in new_records):
            graph.remove_many([r.id for r in new_records])
        graph.add_many([info.record], info.wires)
        for group in cluster_groups:
            group.nodes.append(node_id)
        raise
    _restore_orders(graph, feeding_orders)
    from torsal.engine.graph_records import Group

    for group in inner.groups:
        members = [mapping[n] for n in group.nodes if n in mapping]
        group_id = group.id
        n = 2
        while any(g.id == group_id for g in graph.groups):
            group_id = f"{group.id}{n}"
            n += 1
        graph.add_group(Group(group_id, group.title, group.colour, members, dict(group.raw)))
    for old_id, new_id in mapping.items():
        wanted = node.origin_groups.get(old_id)
        targets = [g for g in graph.groups if g.id in wanted] if wanted is not None else cluster_groups
        for group in targets:
            if new_id not in group.nodes:
                group.nodes.append(new_id)
    if node.origin_order is not None:  # undoing a make_cluster: the file's order comes back too
        _restore_order(graph, node.origin_order, mapping)
        group_rank = {g: i for i, g in enumerate(node.origin_group_order)}
        graph.groups.sort(key=lambda g: group_rank.get(g.id, len(group_rank)))
    else:  # the inner nodes stand where the cluster stood in the node order (and the file's)
        _reorder_nodes(graph, [m for n in nodes_before
                               for m in ([mapping[r.id] for r in body] if n == node_id else [n])])
    for group in graph.groups:  # members back in the order they had before clustering
        before = node.origin_members.get(group.id)
        if before is None and group.id in members_before:  # the inner nodes where the cluster was
            before = [m for n in members_before[group.id]
                      for m in ([r.id for r in body] if n == node_id else [n])]
        if before is not None:
            rank = {mapping.get(m, m): i for i, m in enumerate(before)}
            group.nodes.sort(key=lambda m: rank.get(m, len(rank)))
    if not used_anywhere(graph, definition.id):
        graph.clusters.pop(definition.id, None)
    return [mapping[r.id] for r in body]


def _reorder_nodes(graph: Graph, nodes: list[str]) -> None:
    """Put the graph's nodes in the order of ``nodes`` (those not named go last, in their
    order); the node order is the file's, it never changes the solve."""
    rank = {n: i for i, n in enumerate(nodes)}
    graph.reorder_nodes(sorted(graph.nodes, key=lambda n: rank.get(n, len(rank))))


def _restore_order(graph: Graph, before: tuple[list[str], list[Wire]], mapping: dict[str, str]) -> None:
    """Put nodes and wires back in the order they had before clustering (those added since
    go last); wires are reconnected only from the first one out of place."""
    from torsal.engine.graph_records import Wire

    nodes, wires = before
    _reorder_nodes(graph, [mapping.get(n, n) for n in nodes])

    def renamed(wire: Wire) -> Wire:
        return Wire(mapping.get(wire.source, wire.source), wire.source_port,
                    mapping.get(wire.target, wire.target), wire.target_port)

    wire_rank = {renamed(w): i for i, w in enumerate(wires)}
    current = graph.wires
    wanted = sorted(current, key=lambda w: wire_rank.get(w, len(wire_rank)))
    first = next((i for i, (a, b) in enumerate(zip(current, wanted, strict=True)) if a is not b), None)
    if first is None:
        return
    for wire in current[first:]:
        graph.disconnect(wire)
    for wire in wanted[first:]:
        graph.connect_wire(wire)


def restore_cluster(graph: Graph, info: ClusterInstance, node_ids: list[str]) -> None:
    """Undo an explode: take out ``node_ids`` (and the groups it added), put the cluster back."""
    graph.remove_many([n for n in node_ids if n in graph.nodes])
    for group in list(graph.groups):
        if group.id not in info.group_ids:
            graph.remove_group(group.id)
    graph.clusters.setdefault(info.definition.id, info.definition)
    graph.add_many([info.record], list(info.wires))
    _restore_order(graph, info.order, {})
    for group in info.groups:
        if group in graph.groups and info.record.id not in group.nodes:
            group.nodes.append(info.record.id)
        rank = {m: i for i, m in enumerate(info.members.get(group.id, []))}
        group.nodes.sort(key=lambda m: rank.get(m, len(rank)))


# --------------------------------------------------------------------------- definitions

def definition_of(graph: Graph, key: str) -> ClusterDefinition:
    """The definition with id ``key``, or that of the cluster node ``key``."""
    if key in graph.clusters:
        return graph.clusters[key]
    record = graph.nodes.get(key)
    if record is not None and isinstance(record.node, ClusterNode):
        return record.node.definition
    raise _error(f"there is no cluster definition or cluster node {key!r}")


def boundary_order(graph: Graph, kind: type, current: list[str]) -> list[str]:
    """The boundary nodes of ``kind`` in ``graph``: those in ``current`` in that order,
    then any new ones top to bottom."""
    present = [n for n, r in graph.nodes.items() if isinstance(r.node, kind)]
    kept = [n for n in current if n in present]
    new = sorted((n for n in present if n not in kept),
                 key=lambda n: (graph.nodes[n].position[1], graph.nodes[n].position[0]))
    return kept + new


def cluster_graph(graph: Graph, definition_id: str) -> Graph:
    """A copy of a definition's inner graph, to edit and commit with :func:`set_cluster_graph`."""
    return clone_graph(definition_of(graph, definition_id).graph)


def set_cluster_graph(graph: Graph, definition_id: str, edited: Graph, inputs: list[str] | None = None,
                      outputs: list[str] | None = None) -> DefinitionChange:
    """Commit an edited copy of a definition's graph: every instance updates.

    The definition keeps a copy of ``edited`` (the caller may go on editing its own). The
    ports are the Input and Output nodes of ``edited``: in ``inputs``/``outputs`` order
    when given, else those already ports keep their place and new ones follow (top to
    bottom). Outer wires follow a renamed port; wires to a port that has gone are dropped
    and returned in the change (with the previous graph and ports, to undo).
    """
    definition = definition_of(graph, definition_id)
    new = clone_graph(edited)
    new.clusters = graph.clusters
    new_inputs = boundary_order(new, ClusterInput, definition.inputs if inputs is None else inputs)
    new_outputs = boundary_order(new, ClusterOutput, definition.outputs if outputs is None else outputs)
    change = DefinitionChange(definition.graph, list(definition.inputs), list(definition.outputs))
    change.dropped = _commit(graph, definition, new, new_inputs, new_outputs)
    return change


def _commit(graph: Graph, definition: ClusterDefinition, new: Graph, inputs: list[str],
            outputs: list[str]) -> list[Wire]:
    """Replace ``definition``'s graph and ports; carry renamed ports to every instance's
    wires and values, drop wires to vanished ports (returned), and expire the instances."""
    from torsal.engine.graph_records import GraphError, Wire

    old_in = dict(zip(definition.inputs, definition.input_names(), strict=True))
    old_out = dict(zip(definition.outputs, definition.output_names(), strict=True))
    saved = (definition.graph, definition.inputs, definition.outputs)
    definition.graph, definition.inputs, definition.outputs = new, list(inputs), list(outputs)
    definition.refresh()
    problem = nesting_problem(graph.clusters)
    if not problem and expanded_size(graph) > MAX_EXPANDED_NODES:
        problem = (f"the graph would expand to more than {MAX_EXPANDED_NODES:,} nodes "
                   "(a file Torsal refuses to open)")
    if problem:
        definition.graph, definition.inputs, definition.outputs = saved
        definition.refresh()
        raise GraphError(problem)
    new_in = dict(zip(definition.inputs, definition.input_names(), strict=True))
    new_out = dict(zip(definition.outputs, definition.output_names(), strict=True))
    rename_in = {name: new_in.get(n) for n, name in old_in.items()}
    rename_out = {name: new_out.get(n) for n, name in old_out.items()}
    dropped: list[Wire] = []
    graphs = [graph] + [d.graph for d in graph.clusters.values() if d is not definition]
    touched: set[str] = set()
    for owner in graphs:
        for instance in instances(owner, definition.id):
            record = owner.nodes[instance]
            changed = []
            for wire in _touching(owner, [instance]):
                into = wire.target == instance
                port = wire.target_port if into else wire.source_port
                renamed = (rename_in if into else rename_out).get(port, port)
                if renamed == port:
                    continue
                if into:
                    changed.append((wire, Wire(wire.source, wire.source_port, instance, renamed or "")))
                else:
                    changed.append((wire, Wire(instance, renamed or "", wire.target, wire.target_port)))
            for old, _ in changed:
                owner.disconnect(old)
            for old, replacement in changed:
                port = replacement.target_port if replacement.target == instance else replacement.source_port
                try:
                    if not port:
                        raise GraphError("the port has gone")
                    owner.connect_wire(replacement)
                except GraphError:
                    if owner is graph:
                        dropped.append(old)
            states = {}
            for name, state in record.inputs.items():
                renamed = rename_in.get(name, name)
                states[renamed or name] = state
            record.inputs = states
            owner.expire(instance)
            if owner is graph:
                touched.add(instance)
    for def_id in {definition.id} | containing(graph.clusters, definition.id):
        graph.clusters[def_id].revision += 1
        graph.clusters[def_id].refresh()
        for instance in instances(graph, def_id):
            graph.expire(instance)
            touched.add(instance)
    for instance in sorted(touched):
        graph.emit(SettingChanged, instance, "definition", definition.id, definition.id)
    return dropped


def rename_cluster_port(graph: Graph, definition_id: str, kind: str, old: str, new: str) -> str:
    """Rename one port of a definition (its boundary node's label); returns the old name."""
    definition = definition_of(graph, definition_id)
    nodes = definition.port_nodes(kind)
    new = new.strip()
    if old not in nodes:
        raise _error(f"cluster {definition.name!r} has no {kind} called {old!r}")
    if not new:
        raise _error("a cluster port needs a name")
    if new != old and new in nodes:
        raise _error(f"cluster {definition.name!r} already has an {kind} called {new!r}")
    edited = clone_graph(definition.graph)
    edited.nodes[nodes[old]].label = new
    _commit(graph, definition, edited, list(definition.inputs), list(definition.outputs))
    return old


def reorder_cluster_ports(graph: Graph, definition_id: str, kind: str, names: list[str]) -> list[str]:
    """Put a definition's ``kind`` ports in the order of ``names``; returns the old order."""
    definition = definition_of(graph, definition_id)
    nodes = definition.port_nodes(kind)
    if sorted(names) != sorted(nodes):
        raise _error(f"the new order must name each {kind} of cluster {definition.name!r} once: "
                     f"{', '.join(nodes)}")
    old = list(nodes)
    order = [nodes[n] for n in names]
    inputs = order if kind == "input" else list(definition.inputs)
    outputs = order if kind == "output" else list(definition.outputs)
    _commit(graph, definition, definition.graph, inputs, outputs)
    return old


def rename_cluster(graph: Graph, definition_id: str, name: str) -> str:
    """Rename a definition (every instance's title); returns the old name."""
    definition = definition_of(graph, definition_id)
    name = name.strip()
    if not name:
        raise _error("a cluster needs a name")
    old, definition.name = definition.name, name
    for instance in instances(graph, definition.id):
        graph.emit(SettingChanged, instance, "definition", definition.id, definition.id)
    return old
