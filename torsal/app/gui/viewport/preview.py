"""Actors in the viewport, kept per node and rebuilt only for nodes whose results changed."""

from __future__ import annotations

import re
from collections.abc import Collection
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import pyvista as pv

from torsal.app.gui import theme
from torsal.app.gui.viewport.coloured import replace_coloured
from torsal.app.gui.viewport.datasets import (
    PLAIN_TYPES,
    Memo,
    Piece,
    collect,
    dataset,
    move_points,
    pieces,
    reshape,
    same_topology,
)
from torsal.engine.graph import Graph
from torsal.engine.solver import NodeResult

PREFIX = "preview:"

STYLE = {
    # opaque: translucency costs a depth-sorting pass on every frame; the pieces carry
    # exact normals, so Phong shading needs no normals filter in the pipeline (and moving
    # a surface's points during a drag keeps it smooth)
    "surfaces": {"color": theme.PREVIEW_SURFACE, "interpolation": "phong", "specular": 0.2},
    "rulings": {"color": theme.PREVIEW_RULING, "line_width": 1.0},
    "curves": {"color": theme.PREVIEW_CURVE, "line_width": 2.0},
    "points": {"color": theme.PREVIEW_POINT, "point_size": 9.0, "render_points_as_spheres": True},
    "vectors": {"color": theme.PREVIEW_VECTOR},
    "scalars": {"smooth_shading": True},
}


@dataclass
class NodeActors:
    """What one node shows: the result it was built from, and its actors."""

    result: NodeResult | None
    bars: list[str] = field(default_factory=list)
    #: by actor name, in drawing order: the actor, the piece it was made from (its kind,
    #: its cells) and the dataset it draws (whose points a drag moves)
    actors: dict[str, Any] = field(default_factory=dict)
    pieces: dict[str, Piece] = field(default_factory=dict)
    datasets: dict[str, Any] = field(default_factory=dict)

    @property
    def names(self) -> list[str]:
        return list(self.actors)


@dataclass
class Prepared:
    """A node's preview datasets, made (on the solver's thread) from one result."""

    result: NodeResult
    pieces: list[Piece]
    problems: list[str]


def piece_names(node_id: str, pieces: list[Piece]) -> list[str]:
    """The actors' names of a node's pieces: the node, the kind, and the piece's place
    among the pieces of its kind (so a kind's actor keeps its name when another kind comes
    or goes)."""
    seen: dict[str, int] = {}
    names = []
    for piece in pieces:
        index = seen[piece.kind] = seen.get(piece.kind, -1) + 1
        names.append(f"{PREFIX}{node_id}:{piece.kind}:{index}")
    return names


def point_size(piece: Piece) -> float:
    """Dots of points: smaller when there are many."""
    return 9.0 if len(piece.points) <= 60 else 5.0


def ascii_title(text: str) -> str:
    """VTK's built-in font has no symbols beyond ASCII (and loses "|"): spell them out for
    colour-bar titles."""
    for symbol, spelled in (
        ("·", "*"),
        ("×", "x"),
        ("−", "-"),
        ("²", "^2"),
        ("³", "^3"),
        ("κ", "k"),
        ("°", " deg"),
        ("’", "'"),
        ("…", "..."),
    ):
        text = text.replace(symbol, spelled)
    # VTK's text renderer drops "|" (and turns the comma between two into a quote):
    # "min(|k1|, |k2|)" rendered "min( k1 ' k2 )". Absolute values are spelled abs(...).
    text = re.sub(r"\|([^|]*)\|", r"abs(\1)", text).replace("|", "/")
    return text.encode("ascii", "replace").decode("ascii")


def previewed(graph: Graph, results: dict[str, NodeResult]) -> set[str]:
    """Ids of the nodes whose geometry the viewport shows."""
    return {
        node_id
        for node_id, record in graph.nodes.items()
        if record.shows_geometry and node_id in results
    }


def prepare(result: NodeResult, outputs: Collection[str], memo: Memo | None = None) -> Prepared:
    """The datasets for one node's result, from the ``outputs`` it draws — no plotter
    needed: safe off the GUI thread."""
    drawn = (tree.all_items() for port, tree in result.outputs.items() if port in outputs)
    # outputs of numbers, flags or texts only (a strip's warps, Valid, kinds) are passed
    # over whole: one type check of all their items in C, not one Python step each
    items = [values for values in drawn if not PLAIN_TYPES.issuperset(map(type, values))]
    found = collect((v for values in items for v in values), memo)
    return Prepared(result, pieces(found), found.problems)


def drawn_outputs(graph: Graph, node_id: str) -> frozenset[str]:
    """The outputs of a node the viewport draws (see :attr:`torsal.engine.node.Out.preview`)."""
    return graph.nodes[node_id].node.previewed_outputs()


def prepare_solved(graph: Graph, results: dict[str, NodeResult], solved: list[str]) -> dict[str, Prepared]:
    """Datasets for the just-solved nodes that are previewed: run by the solve worker
    right after solving, so while the GUI draws one frame the next one is being made."""
    shown = previewed(graph, results)
    memo: Memo = {}
    return {
        node_id: prepare(results[node_id], drawn_outputs(graph, node_id), memo)
        for node_id in solved
        if node_id in shown
    }


class Preview:
    """Keeps the plotter's preview actors in step with the graph's results."""

    def __init__(self, plotter: Any) -> None:
        self.plotter = plotter
        self.nodes: dict[str, NodeActors] = {}
        self.selected: set[str] = set()
        self.problems: dict[str, list[str]] = {}
        self.bar_users: dict[str, set[str]] = {}  # colour-bar title -> nodes that use it
        self.bar_keys: dict[str, tuple[Any, str]] = {}  # colour-bar title -> (range, colour map)
        self._bounds: tuple[np.ndarray | None] | None = None  # bounds() until the actors change
        self.hidden: set[str] = set()  # nodes whose surfaces a colour map replaces

    def update(
        self, graph: Graph, results: dict[str, NodeResult], prepared: dict[str, Prepared] | None = None
    ) -> bool:
        """Rebuild the actors of nodes whose result or preview changed; True if any did.

        ``prepared`` holds datasets made on the solver's thread; a node without them (or
        whose result has moved on since) has its datasets made here.
        """
        changed = False
        self._bounds = None
        wanted = previewed(graph, results)
        for node_id in [n for n in self.nodes if n not in wanted]:
            self._remove(node_id)
            changed = True
        for node_id in wanted:
            result = results[node_id]
            shown = self.nodes.get(node_id)
            if shown is not None and shown.result is result:
                continue
            ready = (prepared or {}).get(node_id)
            if ready is None or ready.result is not result:
                ready = prepare(result, drawn_outputs(graph, node_id))
            if ready.problems:
                self.problems[node_id] = ready.problems
            else:
                self.problems.pop(node_id, None)
            if shown is None or not self._update_in_place(node_id, shown, ready):
                self._remove(node_id)
                self._add(node_id, ready)
            changed = True
        if changed:  # a colour map replaces the surface it colours (viewport/coloured.py)
            self.hidden = replace_coloured(graph, self.nodes)
        return changed

    def _update_in_place(self, node_id: str, entry: NodeActors, ready: Prepared) -> bool:
        """Reuse the node's actors (a slider drag): a piece of a kind the node drew before
        keeps that kind's actor, its points moved in place when its cells are unchanged,
        else its dataset's arrays replaced; a kind the node now draws as well gets an actor
        of its own, and a kind it no longer draws loses its. Much cheaper than new actors.
        False for coloured meshes (their colour bars are made with their actors)."""
        if "scalars" in (piece.kind for piece in [*ready.pieces, *entry.pieces.values()]):
            return False
        names = piece_names(node_id, ready.pieces)
        for name in [name for name in entry.actors if name not in names]:
            self.plotter.remove_actor(name, reset_camera=False, render=False)
            del entry.actors[name], entry.pieces[name], entry.datasets[name]
        added = False
        for name, piece in zip(names, ready.pieces, strict=True):
            before = entry.pieces.get(name)
            if before is None:
                self._add_piece(name, piece, node_id, entry)
                added = True
                continue
            if same_topology(before, piece):
                move_points(entry.datasets[name], piece)
            else:
                reshape(entry.datasets[name], piece)
                if piece.kind == "points":
                    entry.actors[name].prop.point_size = point_size(piece)
            entry.pieces[name] = piece
        if added and node_id in self.selected:
            self._style(node_id, True)
        entry.result = ready.result
        return True

    def _add(self, node_id: str, ready: Prepared) -> None:
        self._bounds = None
        entry = NodeActors(ready.result)
        for name, piece in zip(piece_names(node_id, ready.pieces), ready.pieces, strict=True):
            self._add_piece(name, piece, node_id, entry)
        self.nodes[node_id] = entry
        if node_id in self.selected:
            self._style(node_id, True)

    def _add_piece(self, name: str, piece: Piece, node_id: str, entry: NodeActors) -> None:
        style = dict(STYLE[piece.kind])
        data = dataset(piece)
        if piece.kind == "scalars":
            actor = self.plotter.add_mesh(
                data,
                name=name,
                scalars=piece.scalar_name or "value",
                rgb=piece.rgb,
                clim=piece.clim,
                cmap=piece.cmap or "viridis",
                show_scalar_bar=False,
                reset_camera=False,
                render=False,
                **style,
            )
            if not piece.rgb:
                entry.bars.append(self._add_bar(piece, node_id, actor))
        else:
            if piece.kind == "points":
                style["point_size"] = point_size(piece)
            actor = self.plotter.add_mesh(data, name=name, reset_camera=False, render=False, **style)
        entry.actors[name] = actor
        entry.pieces[name] = piece
        entry.datasets[name] = data

    def _add_bar(self, piece: Piece, node_id: str, actor: Any) -> str:
        """The colour bar of a coloured mesh, at the bottom right; returns its title.

        Nodes showing the same quantity on the same range and colours share one bar
        (two curvature analyses read against one legend); otherwise the bar's title
        names its node, and bars stack upwards.
        """
        quantity = ascii_title(piece.scalar_name or "value")
        key = (piece.clim, piece.cmap or "viridis")
        title = quantity
        if self.bar_keys.get(title, key) != key:
            title = f"{quantity}  [{node_id}]"
        self.bar_users.setdefault(title, set()).add(node_id)
        if title in self.plotter.scalar_bars:
            return title
        self.bar_keys[title] = key
        row = len(self.plotter.scalar_bars)
        bar = self.plotter.add_scalar_bar(
            title=title,
            mapper=actor.mapper,
            vertical=False,
            n_labels=2,  # the two ends: a middle tick label would lie under the centred title
            fmt="%.3g",
            title_font_size=11,
            label_font_size=10,
            width=0.45,
            height=0.1,
            position_x=0.52,
            position_y=0.03 + 0.14 * row,
        )
        bar.SetTextPositionToPrecedeScalarBar()  # the end labels and the title under the bar
        return title

    def _remove(self, node_id: str) -> None:
        self._bounds = None
        entry = self.nodes.pop(node_id, None)
        if entry is None:
            return
        for name in entry.names:
            self.plotter.remove_actor(name, reset_camera=False, render=False)
        for title in entry.bars:
            users = self.bar_users.get(title, set())
            users.discard(node_id)
            if not users:
                self.bar_users.pop(title, None)
                self.bar_keys.pop(title, None)
                if title in self.plotter.scalar_bars:
                    self.plotter.remove_scalar_bar(title, render=False)

    def clear(self) -> None:
        for node_id in list(self.nodes):
            self._remove(node_id)

    # -- selection -------------------------------------------------------------------
    def set_selected(self, node_ids: set[str]) -> None:
        for node_id in self.selected - node_ids:
            self._style(node_id, False)
        for node_id in node_ids - self.selected:
            self._style(node_id, True)
        self.selected = set(node_ids)

    def _style(self, node_id: str, selected: bool) -> None:
        entry = self.nodes.get(node_id)
        if entry is None:
            return
        for name, actor in entry.actors.items():
            kind = entry.pieces[name].kind
            prop = actor.prop
            if kind == "scalars":
                prop.show_edges = selected
                prop.edge_color = theme.PREVIEW_SELECTED
            else:
                prop.color = theme.PREVIEW_SELECTED if selected else STYLE[kind]["color"]

    # -- queries ---------------------------------------------------------------------
    def actor_names(self) -> list[str]:
        return [n for entry in self.nodes.values() for n in entry.names]

    def bounds(self) -> np.ndarray | None:
        """``[[xmin, ymin, zmin], [xmax, ymax, zmax]]`` of every preview actor, or None
        (measured once per change of the actors: a refresh asks several times)."""
        if self._bounds is None:
            self._bounds = (self._measure_bounds(),)
        return self._bounds[0]

    def _measure_bounds(self) -> np.ndarray | None:
        boxes = []
        for actor in (a for entry in self.nodes.values() for a in entry.actors.values()):
            if actor.GetVisibility():
                b = actor.GetBounds()
                if np.all(np.isfinite(b)) and b[0] <= b[1]:
                    boxes.append(b)
        if not boxes:
            return None
        boxes = np.asarray(boxes)
        return np.array([boxes[:, [0, 2, 4]].min(axis=0), boxes[:, [1, 3, 5]].max(axis=0)])


def ground_grid(bounds: np.ndarray | None) -> pv.PolyData:
    """A square grid on z = 0 around ``bounds``, with a round spacing."""
    if bounds is None:
        centre, extent = np.zeros(2), 10.0
    else:
        centre = (bounds[0][:2] + bounds[1][:2]) / 2
        extent = float(max(np.ptp(bounds[:, 0]), np.ptp(bounds[:, 1]), 1e-9)) * 1.4
    spacing = 10 ** np.floor(np.log10(extent / 4)) if extent > 0 else 1.0
    half = np.ceil(extent / 2 / spacing) * spacing
    cx, cy = np.round(centre / spacing) * spacing
    ticks = np.arange(-half, half + spacing / 2, spacing)
    lines = []
    for t in ticks:
        lines.append([[cx + t, cy - half, 0], [cx + t, cy + half, 0]])
        lines.append([[cx - half, cy + t, 0], [cx + half, cy + t, 0]])
    points = np.asarray(lines, dtype=float).reshape(-1, 3)
    cells = np.column_stack(
        [np.full(len(lines), 2), np.arange(0, len(points), 2), np.arange(1, len(points), 2)]
    )
    return pv.PolyData(points, lines=cells.ravel())
