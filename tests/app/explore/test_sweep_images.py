"""``torsal sweep --images``: each variant's picture and Design Explorer's img: column."""

from __future__ import annotations

import csv

import numpy as np
import pytest
from matplotlib.image import imread

from tests.support.explore_graphs import formula_graph
from torsal.app.explore.executors import InlineExecutor
from torsal.app.explore.images import SIZE
from torsal.app.explore.samplers import grid
from torsal.app.explore.study import open_study
from torsal.app.explore.sweep import IMAGE_COLUMN, RESULTS, run_sweep
from torsal.engine.graph import Graph
from torsal.engine.graphfile import write_graph
from torsal.nodes.catalogue import default_registry

REGISTRY = default_registry(plugins=False)


@pytest.fixture
def torus(tmp_path):
    """A slider r (0.2 … 0.8) feeding the minor radius of a torus of major radius 1."""
    graph = Graph()
    graph.add_node(REGISTRY.create("params.NumberSlider", {"min": 0.2, "max": 0.8, "value": 0.5,
                                                            "decimals": 3}), "r")
    graph.add_node(REGISTRY.create("surfaces.Torus"), "torus")
    graph.connect("r", "Value", "torus", "MinorRadius")
    write_graph(graph, tmp_path / "torus.graph")
    return tmp_path / "torus.graph"


def read_table(path):
    with path.open(newline="", encoding="utf-8") as handle:
        return list(csv.reader(handle))


def sweep(path, out, vary, collect, **options):
    study = open_study(path, vary, collect, steps=True)
    return run_sweep(study, grid(study.variables), InlineExecutor(), out, **options)


def test_each_variant_gets_its_picture_and_the_table_names_it(torus, tmp_path):
    sweep(torus, tmp_path / "out", ["r=0.2:0.8:3"], ["torus.Torus:count"], images=True)
    rows = read_table(tmp_path / "out" / RESULTS)
    assert rows[0] == ["in:r", "out:torus.Torus:count", IMAGE_COLUMN, "status"]
    pictures = []
    for index, row in enumerate(rows[1:]):
        assert row[2] == f"{index:05d}.png"  # beside the table, where Design Explorer looks
        picture = imread(tmp_path / "out" / row[2])
        assert picture.shape[:2] == (SIZE[1], SIZE[0])
        pictures.append(picture[..., :3])
    # the torus is drawn: some pixels are not white, and a fatter tube covers more of them
    inked = [int(np.count_nonzero(p.min(axis=2) < 0.95)) for p in pictures]
    assert inked[0] > 0.01 * SIZE[0] * SIZE[1]
    assert inked[0] < inked[1] < inked[2]


def test_a_variant_without_geometry_has_an_empty_picture_cell(tmp_path):
    plane = formula_graph(tmp_path / "plane.graph", {"x": (0, 1, 0.5)}, {"f": "2*x"})
    sweep(plane, tmp_path / "out", ["x=0:1:2"], ["f.Result"], images=True)
    rows = read_table(tmp_path / "out" / RESULTS)
    assert [row[2] for row in rows[1:]] == ["", ""]
    assert not list((tmp_path / "out").glob("*.png"))


def test_without_images_the_table_has_no_picture_column(torus, tmp_path):
    sweep(torus, tmp_path / "out", ["r=0.2:0.8:2"], ["torus.Torus:count"])
    assert IMAGE_COLUMN not in read_table(tmp_path / "out" / RESULTS)[0]


def test_a_rerun_with_images_takes_the_pictures_from_the_cache(torus, tmp_path):
    first = sweep(torus, tmp_path / "out", ["r=0.2:0.8:2"], ["torus.Torus:count"], images=True)
    again = sweep(torus, tmp_path / "out", ["r=0.2:0.8:2"], ["torus.Torus:count"], images=True)
    assert (first.solved, again.solved, again.cached) == (2, 0, 2)
    assert [o.image for o in again.outcomes] == ["00000.png", "00001.png"]
