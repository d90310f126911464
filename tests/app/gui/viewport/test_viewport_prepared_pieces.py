"""What the solve worker prepares for the viewport: the same points, triangles, normals and
line cells as drawing each value on its own through the public evaluations (a surface's
``point_at``/``normal_at`` on its grid, a line's ends, a curve's samples), made in fewer
passes; and what a drag does not change (the cells) is handed over as the same array."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from torsal.app.gui.viewport import datasets
from torsal.app.gui.viewport.datasets import Piece, arrows, collect, pieces, same_topology
from torsal.app.gui.viewport.preview import drawn_outputs, prepare, prepare_solved, previewed
from torsal.app.headless import run_file
from torsal.nodes.common import preview as protocol
from torsal.nodes.common.preview import (
    CURVE_SAMPLES,
    RULINGS_SHOWN,
    SURFACE_GRID,
    PreviewGeometry,
    preview_of,
    ruling_direction,
)
from torsal.nodes.geometry.curve_base import Curve
from torsal.nodes.geometry.curves.line import Line, Polyline
from torsal.nodes.geometry.mesh_surface import MeshSurface
from torsal.nodes.geometry.surface_base import Surface, grid_triangles, uv_grid

EXAMPLES = Path(__file__).resolve().parents[4] / "torsal" / "resources" / "examples"


def one_by_one(values) -> list[Piece]:
    """The pieces for ``values`` drawn each on its own: surfaces, lines and curves from
    their public evaluations, anything else through :func:`preview_of`; then merged one
    per kind with each chain's cell written out (its count, then its point indices)."""
    meshes, coloured, chains = [], [], {"rulings": [], "curves": []}
    points, vectors = [], []
    for value in values:
        if value is None or isinstance(value, bool | int | float | str):
            continue
        if isinstance(value, Surface) and not isinstance(value, MeshSurface):
            direction = ruling_direction(value)
            nu, nv = {"v": (SURFACE_GRID, 2), "u": (2, SURFACE_GRID)}.get(direction, (SURFACE_GRID,) * 2)
            u, v = uv_grid(nu, nv)
            meshes.append((value.point_at(u, v), grid_triangles(nu, nv), value.normal_at(u, v)))
            if direction is not None:
                lines = getattr(value, "ruling_lines", None)
                lines = value.rulings(RULINGS_SHOWN) if lines is None else lines[:: max(1, len(lines) // 17)]
                chains["rulings"].extend(np.asarray(line, dtype=float) for line in lines)
        elif type(value) is Line:
            chains["curves"].append(np.array([value.start, value.end]))
        elif isinstance(value, Curve) and not isinstance(value, Polyline):
            chains["curves"].append(value.point_at(np.linspace(0.0, 1.0, CURVE_SAMPLES)))
        else:
            geometry = preview_of(value)
            if geometry is None:
                continue
            chains["curves"].extend(np.asarray(c, dtype=float).reshape(-1, 3) for c in geometry.polylines)
            chains["rulings"].extend(np.asarray(r, dtype=float).reshape(2, 3) for r in geometry.rulings)
            points.extend(np.asarray(p, dtype=float).reshape(-1, 3) for p in geometry.points)
            vectors.extend(np.asarray(x, dtype=float).reshape(3) for x in geometry.vectors)
            for mesh in geometry.meshes:
                if mesh.scalars is None:
                    meshes.append((mesh.vertices, mesh.faces, mesh.normals))
                else:
                    coloured.append(Piece("scalars", mesh.vertices, faces=mesh.faces, scalars=mesh.scalars))
    out = []
    if meshes:
        counts = np.cumsum([0] + [len(m[0]) for m in meshes])
        out.append(Piece(
            "surfaces", np.concatenate([m[0] for m in meshes]),
            faces=np.concatenate([m[1] + counts[k] for k, m in enumerate(meshes)]),
            normals=np.concatenate([m[2] for m in meshes]),
        ))
    for kind in ("rulings", "curves"):
        if chains[kind]:
            cells, start = [], 0
            for chain in chains[kind]:
                cells += [len(chain), *range(start, start + len(chain))]
                start += len(chain)
            out.append(Piece(kind, np.concatenate(chains[kind]), lines=np.array(cells)))
    if points:
        out.append(Piece("points", np.vstack(points)))
    if vectors:
        drawn = np.vstack(vectors)
        drawn = drawn[np.linalg.norm(drawn, axis=1) > 0]
        if len(drawn):
            at, faces, lines = arrows(drawn)
            out.append(Piece("vectors", at, faces=faces, lines=lines))
    return out + coloured


def assert_same_pieces(made: list[Piece], expected: list[Piece], where: str) -> None:
    assert [p.kind for p in made] == [p.kind for p in expected], where
    for mine, theirs in zip(made, expected, strict=True):
        for name in ("points", "faces", "lines", "normals", "scalars"):
            a, b = getattr(mine, name), getattr(theirs, name)
            assert (a is None) == (b is None), f"{where} {mine.kind} {name}"
            if a is not None:
                np.testing.assert_array_equal(a, b, err_msg=f"{where} {mine.kind} {name}")


@pytest.mark.parametrize("example", ["kaohsiung-stadium", "textbook-ruled-surfaces", "zve-roof-edge"])
def test_each_previewed_nodes_pieces_are_its_values_drawn_one_by_one(example):
    run = run_file(EXAMPLES / f"{example}.graph")
    results = run.solver.results
    shown = sorted(previewed(run.graph, results))
    assert shown
    for node_id in shown:
        outputs = drawn_outputs(run.graph, node_id)
        trees = [tree for port, tree in results[node_id].outputs.items() if port in outputs]
        values = [v for tree in trees for v in tree.all_items()]
        made = prepare(results[node_id], outputs)
        assert not made.problems
        assert_same_pieces(made.pieces, one_by_one(values), f"{example}:{node_id}")


def test_a_slider_drag_hands_over_the_strips_cells_as_the_same_arrays():
    run = run_file(EXAMPLES / "kaohsiung-stadium.graph")
    frames = []
    for value in (0.70, 0.71):  # (both with 419 rulings)
        run.graph.set_setting("scale", "value", value)
        report = run.solver.solve()
        frames.append(prepare_solved(run.graph, run.solver.results, report.solved)["strip"].pieces)
    before, after = frames
    assert [p.kind for p in after] == ["surfaces", "rulings", "curves"]
    for old, new in zip(before, after, strict=True):
        assert not np.array_equal(old.points, new.points)  # the strips moved
        assert same_topology(old, new)
        assert (new.faces if new.faces is not None else new.lines) is (
            old.faces if old.faces is not None else old.lines
        )


class Mark:
    """A value drawn as one point at ``x`` (and, in a run, by an adapter that fails)."""

    def __init__(self, x: float) -> None:
        self.x = x

    def preview_geometry(self) -> PreviewGeometry:
        return PreviewGeometry(points=[np.array([[self.x, 0.0, 0.0]])])


def test_a_run_whose_pass_fails_is_drawn_value_by_value(monkeypatch):
    def failing(values):
        raise RuntimeError("no pass")

    monkeypatch.setitem(protocol._MANY, Mark, failing)
    found = collect([Mark(1.0), Mark(2.0), 3.0, Mark(4.0)])
    assert not found.problems
    assert [p[0, 0] for p in found.points] == [1.0, 2.0, 4.0]


def test_runs_of_lines_keep_their_place_among_other_curves():
    lines = [Line((k, 0, 0), (k, 1, 0)) for k in range(3)]
    curve = Polyline([(0, 0, 5), (1, 0, 5), (2, 0, 5)])
    values = [lines[0], lines[1], curve, 7.0, lines[2]]
    (piece,) = pieces(collect(values))
    assert_same_pieces([piece], one_by_one(values), "mixed")


def test_merged_grids_keep_one_read_only_triangle_array_per_shape():
    template = grid_triangles(4, 2)
    template.flags.writeable = False
    vertices = (np.zeros((8, 3)),) * 3
    merged = datasets._merged_faces(vertices, (template,) * 3)
    assert merged is datasets._merged_faces(vertices, (template,) * 3)
    np.testing.assert_array_equal(merged, np.concatenate([template + 8 * k for k in range(3)]))
