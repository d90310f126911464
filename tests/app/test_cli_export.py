"""``torsal run FILE --export ID.PORT=PATH`` writes cut files, .3dm and meshes headless."""

from __future__ import annotations

import json
import xml.etree.ElementTree as ET

import ezdxf
import numpy as np
import pytest
import rhino3dm as rh
import trimesh

from tests.support.io_helpers import polygon_area
from torsal.app.cli import main
from torsal.app.exports import ExportError, export_tree
from torsal.engine.datatree import DataTree

PANEL = [[0, 0, 0], [0.6, 0, 0], [0.5, 0.3, 0], [0.05, 0.25, 0]]  # 8 fit on one sheet


def _node(node_id, node_type, x, inputs=None):
    return {"id": node_id, "type": node_type, "position": [x, 0.0], "inputs": inputs or {}}


@pytest.fixture
def graph(tmp_path):
    data = {
        "format": "torsal.graph",
        "version": 1,
        "units": "m",
        "nodes": [
            _node("panel", "curves.Polyline", 0, {
                "Vertices": {"value": [{"type": "Point", "xyz": p} for p in PANEL]},
                "Closed": {"value": True},
            }),
            _node("row", "transform.Array", 200, {
                "Direction": {"value": {"type": "Vector", "xyz": [0.75, 0, 0]}},
                "Count": {"value": 8},
            }),
            _node("cut", "io.ExportCutSheet", 400, {
                "SheetWidth": {"value": 2500.0}, "SheetHeight": {"value": 1250.0},
            }),
            _node("cyl", "surfaces.Cylinder", 0, {"Radius": {"value": 1.0}, "Height": {"value": 2.0}}),
        ],
        "wires": [
            {"from": ["panel", "Polyline"], "to": ["row", "Geometry"]},
            {"from": ["row", "Geometry"], "to": ["cut", "Panels"]},
        ],
        "groups": [],
        "meta": {},
    }
    path = tmp_path / "panels.graph"
    path.write_text(json.dumps(data))
    return path


def _cut_contours(path):
    doc = ezdxf.readfile(path)
    assert doc.header["$INSUNITS"] == 4
    cuts = doc.modelspace().query('LWPOLYLINE[layer=="CUT"]')
    return [np.array([(x, y) for x, y, *_ in e.get_points()]) for e in cuts]


def test_export_layout_to_dxf_svg_and_3dm_headless(graph, tmp_path):
    dxf, svg, model = (tmp_path / "out" / f"sheet.{suffix}" for suffix in ("dxf", "svg", "3dm"))
    code = main(["run", str(graph), "--export", f"cut.Layout={dxf}", "--export", f"cut.Layout={svg}",
                 "--export", f"cut.Layout={model}"])
    assert code == 0
    contours = _cut_contours(dxf)
    assert len(contours) == 8
    area = polygon_area(np.array(PANEL)[:, :2]) * 1e6
    assert all(polygon_area(c) == pytest.approx(area, rel=1e-6) for c in contours)
    root = ET.parse(svg).getroot()
    assert (root.get("width"), root.get("height")) == ("2500mm", "1250mm")
    file = rh.File3dm.Read(str(model))
    assert file.Settings.ModelUnitSystem == rh.UnitSystem.Millimeters
    layers = {layer.Index: layer.FullPath for layer in file.Layers}
    cuts = [o for o in file.Objects if layers[o.Attributes.LayerIndex] == "CUT"]
    assert sorted(o.Attributes.GetUserString("PanelID") for o in cuts) == [f"P-00{i}" for i in range(1, 9)]


def test_export_plain_curves_to_dxf_lays_them_out_with_the_defaults(graph, tmp_path):
    target = tmp_path / "raw.dxf"
    assert main(["run", str(graph), "--export", f"row.Geometry={target}"]) == 0
    assert len(_cut_contours(target)) == 8


def test_export_surface_to_3dm_and_mesh_formats(graph, tmp_path):
    model, mesh = tmp_path / "cyl.3dm", tmp_path / "cyl.obj"
    code = main(["run", str(graph), "--export", f"cyl.Cylinder={model}", "--export", f"cyl.Cylinder={mesh}"])
    assert code == 0
    file = rh.File3dm.Read(str(model))
    assert file.Settings.ModelUnitSystem == rh.UnitSystem.Meters
    (obj,) = list(file.Objects)
    assert isinstance(obj.Geometry, rh.NurbsSurface)
    assert trimesh.load(str(mesh), force="mesh").area == pytest.approx(2 * np.pi * 2.0, rel=0.01)


@pytest.mark.parametrize(
    ("request_", "needle"),
    [
        ("cyl.Cylinder=x.dxf", "Panel P-001 is not flat"),
        ("panel.Polyline=x.obj", "cannot export Curve to .obj"),
        ("cut.Layout=x.pdf", "cannot export to .pdf"),
    ],
)
def test_export_of_the_wrong_kind_exits_2_with_a_message(graph, capsys, request_, needle):
    assert main(["run", str(graph), "--export", request_]) == 2
    err = capsys.readouterr().err
    assert needle in err and "Traceback" not in err


def test_export_tree_reports_a_bad_panel_as_an_export_error(tmp_path):
    from torsal.nodes.geometry.curves import Polyline

    open_curve = Polyline([[0, 0, 0], [1, 0, 0], [1, 1, 0]])
    with pytest.raises(ExportError, match="Panel P-001 is open"):
        export_tree(DataTree({(0,): [open_curve]}), tmp_path / "x.svg")


def test_json_results_describe_the_layout(graph, capsys):
    assert main(["run", str(graph), "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    (layout,) = data["nodes"]["cut"]["outputs"]["Layout"]["{0}"]
    assert {k: layout[k] for k in ("type", "panels", "sheets", "sheet", "usage", "nesting")} == {
        "type": "CutLayout", "panels": 8, "sheets": 1, "sheet": [2500.0, 1250.0],
        "usage": pytest.approx(8 * 0.145 / 3.125, rel=1e-5), "nesting": "Shelf"}


def test_export_prints_each_file_written_and_json_lists_them(graph, tmp_path, capsys):
    dxf, svg = tmp_path / "out" / "roof.dxf", tmp_path / "out" / "roof.svg"
    args = ["run", str(graph), "--set", "cut.SheetWidth=1500", "--export", f"cut.Layout={dxf}",
            "--export", f"cut.Layout={svg}"]
    assert main(args) == 0
    printed = [line.removeprefix("wrote ") for line in capsys.readouterr().out.splitlines()
               if line.startswith("wrote ")]
    assert main([*args, "--json"]) == 0
    exported = json.loads(capsys.readouterr().out)["exported"]
    assert exported == printed and len(exported) == 4  # 8 panels need two 1500 mm sheets
    assert sorted(p.rsplit("/", 1)[1] for p in exported) == ["roof-1.dxf", "roof-1.svg", "roof-2.dxf",
                                                              "roof-2.svg"]
    assert all((tmp_path / "out" / p).exists() for p in exported)


def test_the_node_says_it_wrote_nothing_without_contradicting_an_export(graph, tmp_path, capsys):
    assert main(["run", str(graph), "--export", f"cut.Layout={tmp_path / 'x.dxf'}"]) == 0
    out = capsys.readouterr().out
    assert "nothing written" not in out
    assert "wrote " in out


def test_run_shows_a_long_nodes_progress_on_a_terminals_stderr(graph, capsys, monkeypatch):
    import sys

    monkeypatch.setattr(sys.stderr, "isatty", lambda: True)
    assert main(["run", str(graph), "--set", "cut.Nesting=TrueShape", "--set", "cut.TimeBudget=1"]) == 0
    err = capsys.readouterr().err
    # one live line (rich's: the node's name, a bar, the percent and the time left), ending at 100 %
    assert "cut" in err and "100%" in err and err.count("%") > 1


def test_run_prints_no_progress_when_stderr_is_not_a_terminal(graph, capsys):
    assert main(["run", str(graph), "--set", "cut.Nesting=TrueShape", "--set", "cut.TimeBudget=1"]) == 0
    assert "%" not in capsys.readouterr().err
