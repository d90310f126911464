"""Which nodes a wire dropped on empty canvas most likely wants, most likely first.

A Number wire dropped on the canvas should offer Series, Expression or Point before
BendingCheck. Nodes are ranked by how they take the wire's type:

1. the node's **first** input (or, for a wire dragged from an input, its first output)
   takes exactly that type — the port a Grasshopper component is usually fed by;
2. its first port takes the type by a cast (an Integer into a Number input);
3. another port takes it exactly, 4. another port by a cast;

and within each tier by how often the bundled examples wire that type into (or out of)
that node type — a count of real use, read once from ``torsal/resources/examples`` —
then in palette order. The search popup preselects the first row.
"""

from __future__ import annotations

import json
from collections import Counter
from collections.abc import Callable, Iterable
from functools import lru_cache
from importlib.resources import files
from typing import Any

from torsal.engine.types import ValueType, can_cast

EXAMPLES = "torsal.resources.examples"


def _ports_by_type(classes: Iterable[type]) -> dict[str, tuple[dict[str, str], dict[str, str]]]:
    """Each node type's inputs and outputs, by name, with their value types' names."""
    ports = {}
    for cls in classes:
        ports[cls.type_id] = (
            {p.name: p.type.name for p in getattr(cls, "inputs", ())},
            {p.name: p.type.name for p in getattr(cls, "outputs", ())},
        )
    return ports


def usage_counts(classes: Iterable[type]) -> Counter[tuple[str, str, str]]:
    """How many wires of the examples carry each type into a node type ("in") or out of
    one ("out"): ``{(type name, "in", type id): count}``. Cached per catalogue."""
    return Counter(dict(_usage(tuple(sorted(classes, key=lambda c: c.type_id)))))


@lru_cache(maxsize=4)
def _usage(classes: tuple[type, ...]) -> tuple[tuple[tuple[str, str, str], int], ...]:
    ports = _ports_by_type(classes)
    counts: Counter[tuple[str, str, str]] = Counter()
    for resource in files(EXAMPLES).iterdir():
        if not resource.name.endswith(".graph"):
            continue
        try:
            data = json.loads(resource.read_text(encoding="utf-8"))
        except (OSError, ValueError):
            continue
        _count_graph(data, ports, counts)
    return tuple(counts.items())


def _count_graph(data: Any, ports: dict, counts: Counter) -> None:
    if not isinstance(data, dict):
        return
    types = {n.get("id"): n.get("type") for n in data.get("nodes", ()) if isinstance(n, dict)}
    for wire in data.get("wires", ()):
        try:
            (source, out_port), (target, in_port) = wire["from"], wire["to"]
        except (KeyError, TypeError, ValueError):
            continue
        source_type, target_type = types.get(source), types.get(target)
        if source_type not in ports or target_type not in ports:
            continue
        carried = ports[source_type][1].get(out_port)
        taken = ports[target_type][0].get(in_port)
        if carried is not None and taken is not None:
            counts[(carried, "in", target_type)] += 1
            counts[(taken, "out", source_type)] += 1
    for definition in data.get("clusters", ()) or ():
        if isinstance(definition, dict):
            _count_graph(definition.get("graph", definition), ports, counts)


def rank_for_wire(
    value_type: ValueType, from_output: bool, classes: Iterable[type], order: Callable[[str], int]
) -> Callable[[Any], tuple]:
    """A sort key for search entries: the likeliest node for a wire of ``value_type``
    first. ``from_output``: the wire was dragged from an output (nodes that take it);
    ``order``: a palette's place in the palette bar."""
    counts = usage_counts(classes)
    direction = "in" if from_output else "out"

    def key(entry: Any) -> tuple:
        cls = entry.cls
        if from_output:
            fits = [(can_cast(value_type, p.type), p.type is value_type) for p in cls.inputs]
        else:
            fits = [(can_cast(p.type, value_type), p.type is value_type) for p in cls.outputs]
        tier = 4
        if fits and fits[0][0]:
            tier = 0 if fits[0][1] else 1
        elif any(exact for _, exact in fits):
            tier = 2
        elif any(ok for ok, _ in fits):
            tier = 3
        used = counts.get((value_type.name, direction, entry.type_id), 0)
        return (tier, -used, order(entry.palette), entry.name)

    return key
