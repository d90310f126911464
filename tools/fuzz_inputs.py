"""Every numeric input of every node type, fed hostile numbers: the input-cap sweep.

For each node type in the registry and each of its numeric inputs (Number, Integer and
Domain ports, and numeric settings such as a slider's value), a case builds a graph of
that one node — with a small, valid value wired into every input that has no default
(a curve, a developable strip, its development, a rectangle for a pattern ...), so the
numbers reach the code that uses them — sets the input to one of :data:`HOSTILE`
(0, -1, 1e12, 1e308, NaN, ∞) and solves it.

A node must answer each with a clear message or a result: never an exception it did not
mean, never a stall, never a huge allocation (see tools/fuzz_pool.py for the guard).
``python -m tools.fuzz_inputs`` runs the sweep and prints the worst cases;
``--at-caps`` runs every capped input at its cap (nodes/limits.py), which must stay
under 20 s and 1 GB.
"""

from __future__ import annotations

import argparse
import math
import sys
from collections.abc import Iterator
from dataclasses import dataclass
from functools import cache
from typing import Any

#: The numbers every numeric input is fed (1e-9: a Scale that divides, as in issue 11).
HOSTILE: tuple[float, ...] = (0.0, -1.0, 1e-9, 1e12, 1e308, math.nan, math.inf)

NUMERIC_TYPES = ("Number", "Integer", "Domain")


@dataclass(frozen=True)
class InputCase:
    """One node type, one input (or setting) and one hostile value."""

    type_id: str
    name: str
    value: float
    setting: bool = False

    def __str__(self) -> str:
        where = "setting " if self.setting else ""
        return f"{self.type_id} {where}{self.name}={self.value!r}"


def cases() -> list[InputCase]:
    """Every node type's numeric inputs and settings, each with every hostile value."""
    from torsal.nodes.catalogue import default_registry

    found = []
    for cls in default_registry(plugins=False):
        names = [(p.name, False) for p in cls.inputs if p.type.name in NUMERIC_TYPES]
        names += [(s.name, True) for s in cls.settings_spec if s.kind in (int, float)]
        for name, setting in names:
            found += [InputCase(cls.type_id, name, value, setting) for value in HOSTILE]
    return found


# --------------------------------------------------------------------------- supplies


@cache
def _supplies() -> dict[str, Any]:
    """Small valid values to wire into inputs that have no default (made by the nodes)."""
    from torsal.engine.graph import Graph
    from torsal.engine.solver import Solver
    from torsal.engine.values import Point
    from torsal.nodes.catalogue import default_registry

    registry = default_registry(plugins=False)
    graph = Graph()

    def add(node_id: str, type_id: str, **values: Any) -> None:
        graph.add_node(registry.create(type_id), node_id)
        for port, value in values.items():
            graph.set_input_value(node_id, port, value)

    points = [{"type": "Point", "xyz": xyz} for xyz in ([0, 0, 0], [1, 0.4, 0], [2, 0.1, 0.3], [3, 0.5, 0.2])]
    above = [{"type": "Point", "xyz": [x, y, z + 1.0]} for x, y, z in (p["xyz"] for p in points)]
    corners = [{"type": "Point", "xyz": xyz} for xyz in ([0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0])]
    add("a", "curves.Interpolate", Vertices=points)
    add("b", "curves.Interpolate", Vertices=above)
    add("rect", "curves.Polyline", Vertices=corners, Closed=True)
    add("strip", "surfaces.RuledSurface")
    graph.connect("a", "Curve", "strip", "CurveA")
    graph.connect("b", "Curve", "strip", "CurveB")
    add("unroll", "analysis.IsoMapping", Segments=8)
    graph.connect("strip", "Surface", "unroll", "Surface")
    add("line", "curves.Line", Start={"type": "Point", "xyz": [0, 0, 0]},
        End={"type": "Point", "xyz": [1, 1, 0]})
    solver = Solver(graph)
    solver.solve()

    def first(node_id: str, port: str) -> Any:
        tree = solver.result(node_id).output(port)
        if tree.is_empty():
            raise RuntimeError(f"the supply {node_id}.{port} made nothing: "
                               f"{[m.text for m in solver.result(node_id).messages]}")
        return tree.first()

    import trimesh

    from torsal.engine.values import Plane, Vector

    curve = first("a", "Curve")
    surface = first("strip", "Surface")
    return {
        "Curve": curve,
        "Curve2": first("b", "Curve"),
        "Closed": first("rect", "Polyline"),
        "Surface": surface,
        "Development": first("unroll", "Map"),
        "Line": first("line", "Line"),
        "Mesh": trimesh.creation.box(),
        "Point": [Point(0, 0, 0), Point(1, 0.5, 0), Point(2, 0.2, 0.4), Point(3, 1, 0.1)],
        "Vector": [Vector(1, 0, 0), Vector(0, 1, 0), Vector(0, 0, 1), Vector(1, 1, 0)],
        "OneVector": [Vector(0, 0, 1)],
        "Plane": Plane(Point(0, 0, 0), Vector(1, 0, 0), Vector(0, 1, 0)),
        "Number": [0.1, 0.4, 0.7, 1.0],
        "Integer": 2,
        "Boolean": [True, False],
        "Text": "panel",
    }


#: Inputs that need a particular kind of value (by node type and port; "*" for any type).
_SPECIAL: dict[tuple[str, str], str] = {
    ("patching.SurfacePatching", "Pattern"): "Closed",
    ("io.ExportCutSheet", "Panels"): "Closed",  # cut sheets take closed flat outlines
    ("*", "CurveB"): "Curve2",
    ("developable.ParametricRuledSurface", "Directrix"): "Curve",
    ("developable.ParametricRuledSurface", "Direction"): "OneVector",  # so Segments counts
    ("analysis.SurfaceAnalysis", "Surface"): "Surface",
    ("surfaces.Area", "Geometry"): "Surface",
    ("surfaces.NurbsSurface", "Points"): "Point",
    ("*", "Geometry"): "Curve",
    ("io.Import3dm", "Path"): "Text",
    ("io.ImportMesh", "Path"): "Text",
}


#: Optional inputs left empty (a supply there would make the node refuse the case early).
_UNSUPPLIED = {
    ("patching.SurfacePatching", "Tile"),
    ("io.ExportCutSheet", "Surfaces"),  # the supply strip is not flat
    ("io.ExportCutSheet", "Strips"),
}


def _supply_for(type_id: str, port: Any) -> Any:
    supplies = _supplies()
    key = _SPECIAL.get((type_id, port.name)) or _SPECIAL.get(("*", port.name))
    if key is None:
        key = port.type.name if port.type.name in supplies else "Number"
        if port.type.name == "Generic":
            key = "Number"
    value = supplies[key]
    many = port.access.name != "ITEM"
    if isinstance(value, list) and not many:
        return value[0]
    if many and not isinstance(value, list):
        return [value]
    return value


def _supply_node(value: Any, type_name: str, access: Any) -> Any:
    from torsal.engine.node import Node, Out
    from torsal.engine.types import get_type

    class Supply(Node):
        type_id = "fuzz.Supply"
        outputs = (Out("Value", get_type(type_name), "V", "A fixed value.", access=access),)

        def solve(self) -> Any:
            return value

    return Supply()


def build(case: InputCase) -> tuple[Any, str]:
    """The one-node graph of ``case`` (with its supplies wired in) and the node's id."""
    from torsal.engine.graph import Graph
    from torsal.engine.node import ITEM, LIST
    from torsal.nodes.catalogue import default_registry

    registry = default_registry(plugins=False)
    graph = Graph()
    node = registry.create(case.type_id)
    graph.add_node(node, "node")
    for port in node.input_ports():
        if port.has_default or (port.name == case.name and not case.setting):
            continue
        if port.optional and port.type.name not in ("Curve", "Surface", "Development"):
            continue
        if (case.type_id, port.name) in _UNSUPPLIED:
            continue
        value = _supply_for(case.type_id, port)
        access = LIST if isinstance(value, list) else ITEM
        graph.add_node(_supply_node(value, port.type.name, access), f"supply_{port.name}")
        graph.connect(f"supply_{port.name}", "Value", "node", port.name)
    hostile: Any = case.value
    if case.setting:
        kind = next(s.kind for s in node.settings_spec if s.name == case.name)
        if kind is int and math.isfinite(hostile) and abs(hostile) < 1e300:
            hostile = int(hostile)
        graph.set_setting("node", case.name, hostile)
    else:
        port = node.input_port(case.name)
        if port.type.name == "Integer" and math.isfinite(hostile) and abs(hostile) < 1e300:
            hostile = int(hostile)
        graph.set_input_value("node", case.name, hostile)
    return graph, "node"


def solve_case(case: InputCase) -> dict[str, Any]:
    """Build and solve ``case`` (run inside a guarded worker)."""
    from tools.fuzz_pool import solve_guarded

    graph, node_id = build(case)
    solved = solve_guarded(graph)
    return {"state": solved["nodes"][node_id][0], "messages": solved["nodes"][node_id][1]}


def sweep(workers: int = 2, seconds: float = 10.0, memory_bytes: int = 1 << 30,
          only: str = "") -> Iterator[tuple[InputCase, Any]]:
    """Run every case (whose type id contains ``only``) in a :class:`GuardedPool`."""
    from tools.fuzz_pool import GuardedPool, node_modules

    pool = GuardedPool(workers=workers, memory_bytes=memory_bytes, seconds=seconds,
                       preload=(*node_modules(), "tools.fuzz_inputs"))
    chosen = [c for c in cases() if only in c.type_id]
    yield from pool.run(solve_case, chosen)


def at_caps() -> list[InputCase]:
    """Every capped input at its cap (from nodes/limits.py): the cap itself must be safe."""
    from torsal.nodes import limits

    capped = [  # (cap, inputs): several caps have equal values
        (limits.MAX_RULINGS, [(f"developable.{name}", "Segments") for name in (
            "CylindricalSurface", "ConicalSurface", "TangentDevelopable", "PaperStrip",
            "ParametricRuledSurface", "RulingDevelopable")]),
        (limits.MAX_ANALYSIS_SEGMENTS, [("analysis.IsoMapping", "Segments"),
                                        ("analysis.CurveOfRegression", "Segments")]),
        (limits.MAX_COUPLING_SEGMENTS, [("developable.SurfaceCoupling", "Segments")]),
        (limits.MAX_SPLINE_SEGMENTS, [("developable.SplineApproximation", "Segments")]),
        (limits.MAX_DIVISIONS, [("curves.DivideCurve", "Count")]),
        (limits.MAX_NUMBERS, [("maths.Series", "Count"), ("maths.Range", "Steps"),
                              ("maths.Random", "Number")]),
        (limits.MAX_COPIES, [("transform.Array", "Count"), ("transform.PolarArray", "Count")]),
        (limits.MAX_DENSITY, [("analysis.SurfaceAnalysis", "UDensity")]),
    ]
    return [InputCase(t, name, float(cap)) for cap, inputs in capped for t, name in inputs]


def main(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(prog="python -m tools.fuzz_inputs", description=__doc__.split("\n\n")[0])
    parser.add_argument("--at-caps", action="store_true",
                        help="run every capped input at its cap instead (each must stay under 20 s and 1 GB)")
    parser.add_argument("only", nargs="?", default="", help="only node types whose id contains this")
    args = parser.parse_args(argv)
    if args.at_caps:
        return _report(list(_run(at_caps(), seconds=20.0)), seconds=20.0, memory=1 << 30)
    return _report(list(sweep(only=args.only)), seconds=3.0, memory=256 << 20)


def _run(chosen: list[InputCase], seconds: float) -> Iterator[tuple[InputCase, Any]]:
    from tools.fuzz_pool import GuardedPool, node_modules

    pool = GuardedPool(workers=2, memory_bytes=(1 << 30) + (256 << 20), seconds=seconds,
                       preload=(*node_modules(), "tools.fuzz_inputs"))
    yield from pool.run(solve_case, chosen)


def _report(results: list[tuple[InputCase, Any]], seconds: float, memory: int) -> int:
    bad = 0
    for case, result in sorted(results, key=lambda r: -r[1].seconds):
        failed = result.unexpected or result.stalled or result.seconds > seconds or result.peak_bytes > memory
        bad += bool(failed)
        if failed or result.seconds > 0.5:
            print(f"{'FAIL' if failed else 'slow'} {case}: {result.seconds:.2f} s, "
                  f"{result.peak_bytes / 2**20:.0f} MiB, stalled={result.stalled}")
            for line in result.unexpected:
                print("    ", line)
            if result.info:
                print("    ", result.info.get("messages"))
    print(f"{len(results)} cases, {bad} failed, slowest {max(r.seconds for _, r in results):.2f} s")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
