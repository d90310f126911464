"""Bake (torsal.app.bake): the geometry of chosen nodes into one .3dm, one layer per node, headless."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import rhino3dm as rh

from tests.support.io_helpers import rhino_points, rhino_surface_points
from torsal.app.bake import bake, bake_entries, layer_name, node_layers
from torsal.app.exports import FILE_TYPES, FORMATS, ExportError
from torsal.app.headless import run_file

EXAMPLE = Path(__file__).resolve().parents[2] / "torsal" / "resources" / "examples" / (
    "textbook-ruled-surfaces.graph"
)
BAKED = ["cylinder", "helicoid", "cylinder_c_points", "cylinder_c_x"]  # the last makes only numbers


@pytest.fixture(scope="module")
def textbook():
    run = run_file(EXAMPLE)
    return run.graph, {node_id: run.solver.result(node_id) for node_id in run.graph.nodes}


def _objects(path: Path) -> tuple[rh.File3dm, dict[str, list]]:
    model = rh.File3dm.Read(str(path))
    layers = {layer.Index: layer.FullPath for layer in model.Layers}
    by_layer: dict[str, list] = {}
    for obj in model.Objects:
        by_layer.setdefault(layers[obj.Attributes.LayerIndex], []).append(obj)
    return model, by_layer


def test_bake_puts_each_node_with_geometry_on_its_own_layer_and_counts_what_it_left_out(textbook, tmp_path):
    graph, results = textbook
    baked = bake(graph, results, BAKED, tmp_path / "bake.3dm", parent="textbook")
    assert baked.layers == {
        "cylinder": ("textbook::Cylinder", 50),  # the surface and its 49 rulings
        "cylinder_c_points": ("textbook::Cylinder directrix", 49),
        "helicoid": ("textbook::Helicoid", 50),
    }
    assert baked.objects == 149
    assert baked.skipped == 3 * 49  # two nodes' WarpAngles and cylinder_c_x's numbers
    model, by_layer = _objects(baked.path)
    assert {name: len(objects) for name, objects in by_layer.items()} == {
        "textbook::Cylinder": 50, "textbook::Helicoid": 50, "textbook::Cylinder directrix": 49,
    }
    assert model.Settings.ModelUnitSystem == rh.UnitSystem.Meters
    kinds = {type(obj.Geometry).__name__ for obj in by_layer["textbook::Cylinder directrix"]}
    assert kinds == {"Point"}


def test_baked_objects_are_named_and_say_which_node_output_and_item_they_are(textbook, tmp_path):
    graph, results = textbook
    _, by_layer = _objects(bake(graph, results, ["helicoid"], tmp_path / "h.3dm").path)
    objects = by_layer["Torsal::Helicoid"]
    names = [obj.Attributes.Name for obj in objects]
    assert names == ["Surface 1", *(f"Rulings {i}" for i in range(1, 50))]
    ruling = objects[5].Attributes
    keys = ("TorsalNode", "TorsalOutput", "TorsalPath", "TorsalIndex")
    assert [ruling.GetUserString(key) for key in keys] == ["helicoid", "Rulings", "{0}", "4"]


def test_baked_rulings_and_surface_match_torsal_within_1e_9_of_their_size(textbook, tmp_path):
    graph, results = textbook
    _, by_layer = _objects(bake(graph, results, ["helicoid"], tmp_path / "h.3dm").path)
    surface_obj, *ruling_objs = by_layer["Torsal::Helicoid"]
    outputs = results["helicoid"].outputs
    t = np.linspace(0.0, 1.0, 101)
    for obj, line in zip(ruling_objs, outputs["Rulings"].all_items(), strict=True):
        expected = line.point_at(t)
        size = float(np.ptp(expected, axis=0).max())
        assert np.abs(rhino_points(obj.Geometry, t) - expected).max() <= 1e-9 * size
    surface = outputs["Surface"].first()
    rng = np.random.default_rng(3)
    u, v = rng.random(500), rng.random(500)
    expected = surface.point_at(u, v)
    size = float(np.ptp(expected, axis=0).max())
    assert np.abs(rhino_surface_points(surface_obj.Geometry, u, v) - expected).max() <= 1e-9 * size


def test_bake_writes_the_file_in_the_graphs_units(textbook, tmp_path):
    graph, results = textbook
    units = graph.units
    graph.units = "mm"
    try:
        model, _ = _objects(bake(graph, results, ["cylinder"], tmp_path / "mm.3dm").path)
    finally:
        graph.units = units
    assert model.Settings.ModelUnitSystem == rh.UnitSystem.Millimeters


def test_nodes_sharing_a_title_are_told_apart_by_their_ids(textbook):
    graph, _ = textbook
    layers = node_layers(graph, ["torus_analysis", "hypar_analysis", "torus"], parent="T")
    assert layers == {  # in graph order
        "torus": "T::Torus",
        "hypar_analysis": "T::Curvature analysis (hypar_analysis)",
        "torus_analysis": "T::Curvature analysis (torus_analysis)",
    }
    assert node_layers(graph, ["torus_analysis"], parent="T") == {"torus_analysis": "T::Curvature analysis"}


@pytest.mark.parametrize(
    ("text", "name"),
    [("Möbius strip", "Möbius strip"), ("a::b", "a:b"), ("(draft) roof", "draft) roof"),
     ("  tab\there ", "tab here"), ("[]", "Torsal")],
)
def test_layer_names_are_ones_rhino_accepts(text, name):
    assert layer_name(text) == name


def test_only_numbers_is_nothing_to_bake(textbook, tmp_path):
    graph, results = textbook
    entries, layers, skipped = bake_entries(graph, results, ["cylinder_c_x", "steps"])
    assert (entries, layers, skipped) == ([], {}, 50)
    with pytest.raises(ExportError, match="Nothing to bake: none of the 2 previewed nodes has geometry"):
        bake(graph, results, ["cylinder_c_x", "steps"], tmp_path / "none.3dm")
    assert not (tmp_path / "none.3dm").exists()


def test_bake_to_a_folder_in_the_way_is_an_export_error(textbook, tmp_path):
    graph, results = textbook
    (tmp_path / "taken.3dm").mkdir()
    with pytest.raises(ExportError, match="is a folder"):
        bake(graph, results, ["cylinder"], tmp_path / "taken.3dm")
    with pytest.raises(ExportError, match=r"not \.obj"):
        bake(graph, results, ["cylinder"], tmp_path / "x.obj")


def test_the_export_dialogs_file_types_are_the_formats_export_tree_writes():
    listed = FORMATS.replace(" or ", ", ").split(", ")
    assert sorted(FILE_TYPES) == sorted(listed)


def test_bake_leaves_out_the_outputs_a_node_does_not_preview(textbook, tmp_path):
    # SurfaceAnalysis shows its coloured mesh, curvature lines and valid rulings, not the
    # 24 × 24 sample points under them (Out("Points", …, preview=False))
    graph, results = textbook
    node = graph.nodes["hypar_analysis"].node
    assert "Points" not in node.previewed_outputs() and "ColouredMesh" in node.previewed_outputs()
    _, by_layer = _objects(bake(graph, results, ["hypar_analysis"], tmp_path / "a.3dm").path)
    outputs = {obj.Attributes.GetUserString("TorsalOutput") for obj in by_layer["Torsal::Curvature analysis"]}
    assert "Points" not in outputs and {"ColouredMesh", "CurvatureLines"} <= outputs
