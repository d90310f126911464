"""Hypothesis strategies for the graph-file fuzz corpus: arbitrary JSON, plausible graphs
with wrong types mixed in, and canonical files as Torsal writes them."""

from __future__ import annotations

from typing import Any

from hypothesis import HealthCheck, settings
from hypothesis import strategies as st

from tests.support.graphfile_fuzz_harness import paths_in, replaced
from tests.support.nodekit import NODE_CLASSES

HYPOTHESIS = settings(
    deadline=None,
    database=None,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large, HealthCheck.large_base_example],
)

NASTY_SCALARS = [
    10**400,
    -(10**400),
    2**63,
    -(2**63) - 1,
    2**64,
    1e308,
    -1e308,
    5e-324,
    -0.0,
    "",
    "\x00",
    "é",
    "😀",
    "\u2028",
    "{0;1}",
    "graft",
    "Value",
    "params.NumberSlider",
    "x" * 300,
]
scalars = st.one_of(
    st.none(),
    st.booleans(),
    st.integers(),
    st.floats(allow_nan=False, allow_infinity=False),
    st.text(max_size=12),
    st.sampled_from(NASTY_SCALARS),
)
json_values = st.recursive(
    scalars,
    lambda kids: st.lists(kids, max_size=5) | st.dictionaries(st.text(max_size=8), kids, max_size=5),
    max_leaves=15,
)

TYPE_IDS = [cls.type_id for cls in NODE_CLASSES]
PORT_NAMES = sorted(
    {p.name for cls in NODE_CLASSES for p in (*cls.inputs, *cls.outputs)}
    | {"x", "y", "u", "Result", "In", "Out", "", "Nope"}
)
SETTING_NAMES = sorted({s.name for cls in NODE_CLASSES for s in cls.settings_spec} | {"other"})
MODIFIER_NAMES = ["graft", "flatten", "simplify", "reverse", "graft", "sort", ""]

ids = st.sampled_from(["a", "b", "c", "d", "e", "f", "", "é"])
types = st.sampled_from([*TYPE_IDS, *TYPE_IDS, "plugin.Missing", "developable.CylindricalSurface", "", "x"])
ports = st.sampled_from(PORT_NAMES)
coordinates = st.floats(-1e16, 1e16, allow_nan=False) | st.integers(-(10**16), 10**16)
encoded_values = st.one_of(
    st.fixed_dictionaries(
        {"type": st.sampled_from(["Point", "Vector", "Domain", "Plane", "Number", "Generic", "Nope"])},
        optional={
            "xyz": st.lists(scalars, max_size=4),
            "min": scalars,
            "max": scalars,
            "origin": st.lists(scalars, max_size=4),
            "x": st.lists(scalars, max_size=4),
            "y": st.lists(scalars, max_size=4),
        },
    ),
    st.lists(st.floats(-1e6, 1e6) | st.integers(-100, 100), max_size=6),
)
setting_values = st.one_of(
    json_values,
    st.floats(allow_nan=False, allow_infinity=False),
    st.lists(st.sampled_from(["x", "y", "u", "v", "1bad", ""]), max_size=4),  # variables
    st.dictionaries(  # tree branches
        st.sampled_from(["{0}", "{1}", "{0;1}", "{-1}", "{}", "bad"]),
        st.lists(st.integers(-5, 5) | st.floats(-10, 10) | st.text(max_size=2), max_size=4),
        max_size=3,
    ),
)


input_entries = st.fixed_dictionaries(
    {},
    optional={
        "value": encoded_values | scalars,
        "modifiers": st.lists(st.sampled_from(MODIFIER_NAMES), max_size=3),
        "x_hint": scalars,
    },
)
nodes = st.fixed_dictionaries(
    {"id": ids, "type": types},
    optional={
        "label": st.text(max_size=10),
        "position": st.lists(coordinates, min_size=2, max_size=2),
        "settings": st.dictionaries(st.sampled_from(SETTING_NAMES), setting_values, max_size=4),
        "inputs": st.dictionaries(ports, input_entries, max_size=3),
        "preview": st.booleans(),
        "enabled": st.booleans(),
        "x_unknown": scalars,
        "x": scalars,  # version 0 positions
        "y": scalars,
    },
)
wires = st.fixed_dictionaries(
    {"from": st.tuples(ids, ports).map(list), "to": st.tuples(ids, ports).map(list)},
    optional={"x_style": scalars},
)
v0_wires = st.fixed_dictionaries(
    {"source": st.tuples(ids, ports).map(".".join), "target": st.tuples(ids, ports).map(".".join)}
)
groups = st.fixed_dictionaries(
    {"id": ids},
    optional={
        "title": st.text(max_size=5),
        "colour": st.text(max_size=7),
        "nodes": st.lists(ids, max_size=4),
        "x_locked": scalars,
    },
)
plausible_files = st.fixed_dictionaries(
    {
        "format": st.sampled_from(["torsal.graph"] * 15 + ["torsal.graph ", "other"]),
        "version": st.sampled_from([1] * 10 + [0, 0, 0, 2, -1, True, "1"]),
        "nodes": st.lists(nodes, max_size=7, unique_by=lambda n: n["id"]) | st.lists(nodes, max_size=4),
    },
    optional={
        "wires": st.lists(wires | v0_wires, max_size=8),
        "groups": st.lists(groups, max_size=2),
        "meta": st.dictionaries(st.text(max_size=6), scalars, max_size=3),
        "units": st.sampled_from(["m", "mm", "cm", "in", "ft", "km", ""]),
        "x_top": scalars,
    },
)
# wrong types: up to three values anywhere in a generated file replaced by any JSON value
corruptions = st.lists(st.tuples(st.integers(0, 10**6), json_values), max_size=3)


def corrupt(document: dict, changes: list[tuple[int, Any]]) -> Any:
    for where, value in changes:
        paths = paths_in(document)
        path = paths[where % len(paths)]
        document = value if not path else replaced(document, path, value)
    return document


finite_json = st.recursive(
    st.none()
    | st.booleans()
    | st.integers()
    | st.floats(allow_nan=False, allow_infinity=False)
    | st.text(max_size=10)
    | st.sampled_from([10**400, 1e308, 5e-324, -0.0, "é😀\u2028"]),
    lambda kids: st.lists(kids, max_size=4) | st.dictionaries(st.text(max_size=6), kids, max_size=4),
    max_leaves=10,
)
unknown_keys = st.text(max_size=6).map(lambda s: "x_" + s)


@st.composite
def canonical_files(draw: st.DrawFn) -> dict:
    """Files as Torsal writes them (every field Torsal always writes is present)."""
    count = draw(st.integers(0, 6))
    node_ids = draw(st.lists(st.text(min_size=1, max_size=8), min_size=count, max_size=count, unique=True))
    file_nodes = []
    for node_id in node_ids:
        node = {
            "id": node_id,
            "type": draw(
                st.sampled_from(
                    [
                        "params.NumberSlider",
                        "maths.Add",
                        "lists.ListLength",
                        "plugin.Missing",
                        "other.Thing",
                        "x",
                    ]
                )
            ),
            "position": draw(
                st.lists(st.floats(-1e15, 1e15) | st.integers(-(10**15), 10**15), min_size=2, max_size=2)
            ),
        }
        optional = {
            "label": st.text(max_size=12),
            "settings": st.dictionaries(st.text(max_size=8), finite_json, max_size=4),
            "inputs": st.dictionaries(
                st.text(max_size=6),
                st.fixed_dictionaries(
                    {},
                    optional={
                        "value": finite_json,
                        "modifiers": st.lists(
                            st.sampled_from(["graft", "flatten", "simplify", "reverse"]), max_size=3
                        ),
                        "x_hint": finite_json,
                    },
                ),
                max_size=3,
            ),
            "preview": st.booleans(),
            "enabled": st.booleans(),
        }
        for key, strategy in optional.items():
            if draw(st.booleans()):
                node[key] = draw(strategy)
        for key in draw(st.lists(unknown_keys, max_size=2)):
            node[key] = draw(finite_json)
        file_nodes.append(node)
    placeholders = [n["id"] for n in file_nodes if n["type"] in ("plugin.Missing", "other.Thing", "x")]
    file_wires, seen = [], set()
    for _ in range(draw(st.integers(0, 6))):
        if len(placeholders) < 2:
            break
        i, j = sorted(
            draw(st.lists(st.integers(0, len(placeholders) - 1), min_size=2, max_size=2, unique=True))
        )
        ends = (
            placeholders[i],
            draw(st.text(min_size=1, max_size=5)),
            placeholders[j],
            draw(st.text(min_size=1, max_size=5)),
        )
        if ends in seen:
            continue
        seen.add(ends)
        entry = {"from": [ends[0], ends[1]], "to": [ends[2], ends[3]]}
        for key in draw(st.lists(unknown_keys, max_size=1)):
            entry[key] = draw(finite_json)
        file_wires.append(entry)
    file_groups = [
        {
            "id": draw(st.text(min_size=1, max_size=5)),
            "title": draw(st.text(max_size=8)),
            "colour": draw(st.text(max_size=8)),
            "nodes": draw(st.lists(st.sampled_from(node_ids), max_size=3)) if node_ids else [],
        }
        for _ in range(draw(st.integers(0, 2)))
    ]
    data = {
        "format": "torsal.graph",
        "version": 1,
        "nodes": file_nodes,
        "wires": file_wires,
        "groups": file_groups,
        "meta": draw(st.dictionaries(st.text(max_size=8), finite_json, max_size=3)),
    }
    if draw(st.booleans()):
        data["units"] = draw(st.sampled_from(["m", "mm", "cm", "in", "ft"]))
    for key in draw(st.lists(unknown_keys, max_size=2)):
        data[key] = draw(finite_json)
    return data
