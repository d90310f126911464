"""Every example graph moved to site coordinates: the shift, and the comparison with the
original (shared by ``tests/app/test_site_coordinates.py`` and its benchmark).

The model is moved at its sources: every Point, Plane and Line value stored in an input
gets the offset, and the nodes that make geometry from plain numbers (``params.Point``,
``surfaces.ParametricSurface``, ``developable.PaperStrip``) and the geometry read from a
file (``io.Import3dm``) get a ``transform.Move`` on their geometry outputs. Developments
are drawn flat about the origin whatever the surface's position, so the nodes downstream
of one (and their stored points, such as a scale centre) are left as they are and their
outputs are expected unchanged.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import trimesh

from torsal.engine import graphfile
from torsal.engine.graph import Graph
from torsal.engine.solver import ERROR, Solver
from torsal.engine.types import encode_value
from torsal.engine.values import Plane, Point, Vector
from torsal.engine.writes import WriteAccess
from torsal.nodes.catalogue import default_registry
from torsal.nodes.geometry.curve_base import Curve
from torsal.nodes.geometry.surface_base import Surface

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = sorted((ROOT / "torsal" / "resources" / "examples").glob("*.graph"))
#: The test suite's own graphs (engine fixtures, the GUI's showcase): moved like the examples.
TEST_GRAPHS = sorted(
    [
        *(ROOT / "tests" / "fixtures").glob("*.graph"),
        *(ROOT / "tests" / "app" / "gui" / "fixtures").glob("*.graph"),
    ]
)
GRAPHS = EXAMPLES + TEST_GRAPHS
REGISTRY = default_registry(plugins=False)

SITE = (1e6, 2e6, 300.0)  # a national-grid site, in metres
FAR = (1e9, 1e9, 1e9)

#: Nodes that make geometry from numbers: their geometry outputs are moved.
SOURCES = {
    "params.Point": ("Point",),
    "surfaces.ParametricSurface": ("Surface",),
    "developable.PaperStrip": ("Surface", "Rulings"),
    # a design read from a file (rationalise-canopy's canopy.3dm): what it reads is moved
    "io.Import3dm": ("Curves", "Surfaces", "Meshes"),
}
#: Outputs laid flat in the XY plane about the origin, wherever the input is.
FLAT = {
    "analysis.IsoMapping": ("Development", "Rulings", "Map"),
    "developable.PaperStrip": ("Development",),
    "patching.SurfacePatching": ("PanelsFlat", "DevelopmentBounds", "PatternBounds"),
    # cut sheets are laid out in mm on the sheet, wherever the 3D strips (Strips, for the
    # seams) are
    "io.ExportCutSheet": ("Paths", "Layout", "Cuts", "Sheets", "Usage", "Seams", "SeamDifferences"),
}
#: Of those, the outputs a Placement input lays beside the model (0, the default) or on a
#: stored Plane (2, whose origin the shift moves): they move with the model unless
#: Placement is 1 (Origin) or 2 with no Plane (the world XY plane).
PLACED = {
    "analysis.IsoMapping": ("Development", "Rulings"),
    "patching.SurfacePatching": ("PanelsFlat", "DevelopmentBounds", "PatternBounds"),
}
MOVED_SUFFIX = "__site"

SAMPLES = np.linspace(0.0, 1.0, 9)


def _laid_flat(record: Any) -> tuple[str, ...]:
    """The outputs of a node that stay flat about the origin, whatever its input's position."""
    names = FLAT.get(record.type_id, ())
    if record.type_id not in PLACED:
        return names

    def stored(port: str, default: Any) -> Any:
        state = record.inputs.get(port)
        return state.value if state is not None and state.has_value else default

    placement = stored("Placement", 0)
    if placement == 1 or (placement == 2 and stored("Plane", None) is None):
        return names
    return tuple(name for name in names if name not in PLACED[record.type_id])


def moving_outputs(graph: Graph) -> tuple[set[tuple[str, str]], set[str]]:
    """Which outputs move with the model, and which nodes are flat (left as they are).

    A node is flat when what it is wired from is flat and none of it moves (a scale of a
    development about the origin); otherwise its outputs move when any input moves or it
    holds points (a source), except the outputs laid flat (:data:`FLAT`)."""
    moving: set[tuple[str, str]] = set()
    flat_ports: set[tuple[str, str]] = set()
    flat: set[str] = set()
    for node_id in graph.order():
        record = graph.nodes[node_id]
        sources = {(w.source, w.source_port) for w in graph.wires_into(node_id)}
        moved_in = bool(sources & moving)
        if sources & flat_ports and not moved_in:
            flat.add(node_id)
            flat_ports |= {(node_id, port.name) for port in record.node.output_ports()}
            continue
        holds_points = any(state.has_value and _shift_data(state.value, (1.0, 1.0, 1.0)) != state.value
                           for state in record.inputs.values())
        for port in record.node.output_ports():
            if port.name in _laid_flat(record):
                flat_ports.add((node_id, port.name))
            elif moved_in or holds_points or port.name in SOURCES.get(record.type_id, ()):
                moving.add((node_id, port.name))
    return moving, flat


def _shift_data(value: Any, offset: tuple[float, float, float]) -> Any:
    """Stored input data (JSON) with its points moved by ``offset``."""
    if isinstance(value, list):
        return [_shift_data(v, offset) for v in value]
    if isinstance(value, dict):
        def moved(xyz: list[float]) -> list[float]:
            return [c + o for c, o in zip(xyz, offset, strict=True)]

        kind = value.get("type")
        if kind == "Point":
            return {**value, "xyz": moved(value["xyz"])}
        if kind == "Plane":
            return {**value, "origin": moved(value["origin"])}
        if kind == "Line":
            return {**value, "from": moved(value["from"]), "to": moved(value["to"])}
    return value


def shifted(path: Path, offset: tuple[float, float, float]) -> Graph:
    """The example at ``path`` with its geometry moved by ``offset`` at the sources."""
    graph = graphfile.read_graph(path, REGISTRY)
    _, flat = moving_outputs(graph)
    for node_id, record in list(graph.nodes.items()):
        if node_id in flat:
            continue
        for port, state in record.inputs.items():
            if state.has_value:
                moved = _shift_data(state.value, offset)
                if moved != state.value:
                    graph.set_input_value(node_id, port, moved)
        for port in SOURCES.get(record.type_id, ()):
            outgoing = [w for w in graph.wires_from(node_id) if w.source_port == port]
            if not outgoing:
                continue
            mover = graph.add_node(REGISTRY.create("transform.Move"), f"{node_id}__{port}{MOVED_SUFFIX}").id
            graph.set_input_value(mover, "Motion", encode_value(Vector(*offset)))
            graph.connect(node_id, port, mover, "Geometry")
            for wire in outgoing:
                graph.disconnect(wire)
                graph.connect(mover, "Geometry", wire.target, wire.target_port)
    return graph


@dataclass
class Figures:
    """What is compared of one output item: its kind, sample positions and scalars."""

    kind: str
    positions: np.ndarray | None = None
    lengths: list[float] = field(default_factory=list)  # compared relative to the model's size
    areas: list[float] = field(default_factory=list)  # compared relative to themselves
    numbers: list[float] = field(default_factory=list)  # relative to max(|x|, 1)


def measure(value: Any) -> Figures:
    """The figures of one output item (evaluating lengths, areas and bounding boxes, as the JSON
    summary does)."""
    if value is None or isinstance(value, bool | str):
        return Figures("other")
    if isinstance(value, int | float):
        return Figures("number", numbers=[float(value)])
    if isinstance(value, Point):
        return Figures("point", np.array([value], dtype=float))
    if isinstance(value, Vector):
        return Figures("vector", numbers=list(value))
    if isinstance(value, Plane):
        return Figures("plane", np.array([value.origin], dtype=float),
                       numbers=[*value.x, *value.y, *value.z])
    if isinstance(value, Curve):
        return Figures("curve", value.point_at(SAMPLES), lengths=[value.length])
    if isinstance(value, Surface):  # samples and, as the JSON summary gives it, the bounding box
        u, v = (a.ravel() for a in np.meshgrid(SAMPLES, SAMPLES))
        positions = np.vstack([value.point_at(u, v), value.bounding_box()])
        return Figures("surface", positions, areas=[value.area()])
    if isinstance(value, trimesh.Trimesh):
        return Figures("mesh", np.asarray(value.vertices, dtype=float), areas=[float(value.area)])
    return Figures(type(value).__name__)


@dataclass
class Solved:
    """One solve of an example: every output item's figures, and how long it all took."""

    figures: dict[tuple[str, str, str, int], Figures]
    seconds: float
    errors: dict[str, list[str]]
    evaluations: int = 0
    #: every node's output trees, for the comparisons the figures cannot make
    outputs: dict[str, dict[str, Any]] = field(default_factory=dict)


def solve(graph: Graph, folder: Path | None = None) -> Solved:
    """Solve ``graph`` and measure every output (the time covers both); files it reads are
    found from ``folder`` (its file's folder), as ``torsal run`` finds them."""
    solver = Solver(graph, WriteAccess(folder) if folder is not None else None)
    start = time.perf_counter()
    solver.solve()
    figures = {}
    for node_id in graph.nodes:
        if node_id.endswith(MOVED_SUFFIX):
            continue
        for port, tree in solver.results[node_id].outputs.items():
            for path, items in tree.to_dict().items():
                for index, item in enumerate(items):
                    figures[(node_id, port, str(path), index)] = measure(item)
    seconds = time.perf_counter() - start
    errors = {n: [m.text for m in r.messages] for n, r in solver.results.items() if r.state == ERROR}
    outputs = {n: r.outputs for n, r in solver.results.items()}
    return Solved(figures, seconds, errors, outputs=outputs)


def model_size(solved: Solved) -> float:
    """The diagonal of the box around every position the example outputs (1 if none)."""
    positions = [f.positions for f in solved.figures.values() if f.positions is not None]
    if not positions:
        return 1.0
    stacked = np.vstack(positions)
    return float(np.linalg.norm(stacked.max(axis=0) - stacked.min(axis=0))) or 1.0


def expected_moving(path: Path) -> set[tuple[str, str]]:
    """The outputs of the example at ``path`` that move with its sources (the sources'
    own outputs do not: the Move nodes after them carry the offset)."""
    graph = graphfile.read_graph(path, REGISTRY)
    moving, _ = moving_outputs(graph)
    return {(n, p) for n, p in moving if p not in SOURCES.get(graph.nodes[n].type_id, ())}


@dataclass
class Deviation:
    """The worst relative deviation of each comparison, with the output it was found on."""

    positions: tuple[float, str] = (0.0, "")
    lengths: tuple[float, str] = (0.0, "")
    areas: tuple[float, str] = (0.0, "")
    numbers: tuple[float, str] = (0.0, "")
    missing: list[str] = field(default_factory=list)

    def worst(self) -> float:
        return max(self.positions[0], self.lengths[0], self.areas[0], self.numbers[0])

    def __str__(self) -> str:
        parts = [f"{name} {value:.1e} ({where})" for name, (value, where) in
                 (("positions", self.positions), ("lengths", self.lengths), ("areas", self.areas),
                  ("numbers", self.numbers)) if value > 0]
        return ", ".join(parts + [f"missing {m}" for m in self.missing[:3]]) or "identical"


def compare(origin: Solved, moved: Solved, offset: tuple[float, float, float], size: float,
            moving: set[tuple[str, str]], skip: frozenset[tuple[str, str]] = frozenset()) -> Deviation:
    """How far ``moved`` is from ``origin`` shifted by ``offset``, relative to ``size``:
    positions and lengths as fractions of the model's size, areas of themselves,
    plain numbers of max(|x|, 1)."""
    deviation = Deviation()
    shift = np.asarray(offset, dtype=float)

    def worse(current: tuple[float, str], value: float, where: str) -> tuple[float, str]:
        return (value, where) if value > current[0] or not np.isfinite(value) else current

    for key, a in origin.figures.items():
        if key[:2] in skip:
            continue
        where = f"{key[0]}.{key[1]}{key[2]}[{key[3]}]"
        b = moved.figures.get(key)
        if b is None or b.kind != a.kind:
            deviation.missing.append(where)
            continue
        if a.positions is not None:
            expected = a.positions + shift if key[:2] in moving else a.positions
            error = float(np.abs(b.positions - expected).max()) / size
            deviation.positions = worse(deviation.positions, error, where)
        for x, y in zip(a.lengths, b.lengths, strict=True):
            deviation.lengths = worse(deviation.lengths, abs(x - y) / size, where)
        for x, y in zip(a.areas, b.areas, strict=True):
            deviation.areas = worse(deviation.areas, abs(x - y) / max(abs(x), 1e-300), where)
        for x, y in zip(a.numbers, b.numbers, strict=True):
            deviation.numbers = worse(deviation.numbers, abs(x - y) / max(abs(x), 1.0), where)
    deviation.missing += [f"{k[0]}.{k[1]} (new)" for k in moved.figures.keys() - origin.figures.keys()]
    return deviation

