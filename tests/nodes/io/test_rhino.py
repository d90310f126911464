"""io.Import3dm and io.Export3dm: Rhino files that match Torsal's geometry, and bad files."""

from __future__ import annotations

import math

import numpy as np
import pytest
import rhino3dm as rh
import trimesh

from tests.support.io_helpers import rectangle, rhino_points, rhino_surface_points
from tests.support.node_helpers import allowed, out, run, texts, tree
from torsal.engine.solver import ERROR, OK
from torsal.nodes.geometry import parametric_surface
from torsal.nodes.geometry.curves import Arc, Circle, InterpolatedCurve, Line, NurbsCurve, Polyline
from torsal.nodes.geometry.nurbs_surface import Loft, NurbsSurface
from torsal.nodes.geometry.ruled import RuledSurface
from torsal.nodes.geometry.transforms import rotation
from torsal.nodes.geometry.vectors import Plane
from torsal.nodes.io.formats import threedm
from torsal.nodes.io.rhino import Export3dm, Import3dm

RNG = np.random.default_rng(2024)
UP = np.array([0.0, 0.0, 2.0])
T = np.linspace(0.0, 1.0, 1000)
TILTED = Plane.from_axes(np.array([1.0, 2.0, 3.0]), np.array([1.0, 1.0, 0.0]), np.array([0.0, 1.0, 1.0]))


def _curves() -> dict[str, object]:
    return {
        "rational cubic": NurbsCurve(RNG.random((7, 3)) * 10, 3, [0, 0, 0, 0, 0.2, 0.5, 0.7, 1, 1, 1, 1],
                                     0.5 + RNG.random(7)),
        "periodic quadratic": NurbsCurve(RNG.random((6, 3)), 2, periodic=True),
        "unclamped knots": NurbsCurve(RNG.random((5, 3)), 2, [0, 1, 2, 3, 4, 5, 6, 7]),
        "polyline": Polyline([[0, 0, 0], [1, 0, 0], [1, 2, 0], [0, 3, 1]], closed=True),
        "line": Line([0, 0, 0], [3, 4, 5]),
        "circle": Circle(TILTED, 2.5),
        "arc": Arc(TILTED, 1.5, 0.3, 4.0),
        "interpolated": InterpolatedCurve(RNG.random((9, 3))),
        "reversed": NurbsCurve(RNG.random((7, 3)), 3).reversed(),
        "rotated": InterpolatedCurve(RNG.random((6, 3))).transformed(rotation([1, 2, 3], 0.7)),
        "rail of a ruled surface": RuledSurface.from_rulings(RNG.random((7, 3)), RNG.random((7, 3))).curve_a,
        "isocurve (interpolated)": Loft([Circle(radius=1.0), Circle(Plane.from_axes(
            np.array([0, 0, 2.0]), np.array([1.0, 0, 0]), np.array([0, 1.0, 0])), 2.0)]).isocurve("v", 0.3),
    }


def _surfaces() -> dict[str, object]:
    theta = np.linspace(0, 2 * np.pi, 25)
    ring = np.column_stack([np.cos(theta), np.sin(theta), np.zeros_like(theta)])
    return {
        "rational NURBS": NurbsSurface(RNG.random((5, 4, 3)) * 4, 3, 2, weights=0.5 + RNG.random((5, 4))),
        "ruled from rulings": RuledSurface.from_rulings(RNG.random((9, 3)), RNG.random((9, 3)) + UP),
        "closed ruled (cone-like)": RuledSurface.from_rulings(ring * 2, ring + 1.5 * UP),
        "three rulings": RuledSurface.from_rulings(RNG.random((3, 3)), RNG.random((3, 3)) + 1),
        "loft": Loft([Circle(radius=1.0), Circle(TILTED, 2.0), Circle(Plane.from_axes(
            np.array([0, 0, 5.0]), np.array([1.0, 0, 0]), np.array([0, 1.0, 0])), 1.0)]),
        "moved NURBS": NurbsSurface(RNG.random((4, 4, 3))).transformed(rotation([0, 0, 1], 1.0, [1, 1, 0])),
        "ruled between two curves": RuledSurface(InterpolatedCurve(RNG.random((5, 3))),
                                                 NurbsCurve(RNG.random((6, 3)) + 2, 2)),
        "sphere (interpolated)": parametric_surface.sphere(3.0, (1, 2, 3)),
    }


CURVES = _curves()
SURFACES = _surfaces()


def export(tmp_path, **inputs):
    target = tmp_path / "model.3dm"
    trees = {k: tree({(0,): v}) if isinstance(v, list) else v for k, v in inputs.items()}
    result = run(Export3dm(), Path=target.name, Write=True, writes=allowed(tmp_path), **trees)
    return result, target


@pytest.mark.parametrize("name", list(CURVES))
def test_curve_written_then_read_by_rhino3dm_matches_torsal_at_1000_parameters(tmp_path, name):
    curve = CURVES[name]
    result, target = export(tmp_path, Curves=[curve])
    assert result.state == OK, texts(result)
    model = rh.File3dm.Read(str(target))
    (obj,) = list(model.Objects)
    expected = curve.point_at(T)
    size = float(np.ptp(expected, axis=0).max())
    assert np.abs(rhino_points(obj.Geometry, T) - expected).max() <= 1e-9 * size


@pytest.mark.parametrize("name", [name for name in SURFACES if "interpolated" not in name])
def test_surface_written_then_read_by_rhino3dm_matches_torsal_at_1000_parameters(tmp_path, name):
    surface = SURFACES[name]
    result, target = export(tmp_path, Surfaces=[surface])
    assert result.state == OK, texts(result)
    (obj,) = list(rh.File3dm.Read(str(target)).Objects)
    u, v = RNG.random(1000), RNG.random(1000)
    u[:4], v[:4] = [0, 1, 0, 1], [0, 0, 1, 1]  # the corners too
    expected = surface.point_at(u, v)
    size = float(np.ptp(expected, axis=0).max())
    assert np.abs(rhino_surface_points(obj.Geometry, u, v) - expected).max() <= 1e-9 * size


def test_ruled_surface_is_written_degree_1_across_its_rulings(tmp_path):
    surface = SURFACES["ruled from rulings"]
    _, target = export(tmp_path, Surfaces=[surface])
    (obj,) = list(rh.File3dm.Read(str(target)).Objects)
    nurbs = obj.Geometry
    assert (nurbs.OrderU, nurbs.OrderV) == (4, 2)
    assert nurbs.Points.CountV == 2


def test_file_is_rhino_7_with_units_layers_names_and_panel_ids(tmp_path):
    panels = [rectangle(0, 0, 1, 0.5), rectangle(2, 0, 1, 0.5)]
    result, target = export(
        tmp_path,
        Curves=[CURVES["circle"]], Rulings=[Line([0, 0, 0], [0, 0, 1])],
        Panels=panels, PanelIDs=["A-1", "A-2"], Meshes=[trimesh.creation.box()],
        Units="mm",
    )
    assert result.state == OK, texts(result)
    assert out(result, "Path") == {(0,): [str(target)]}
    assert out(result, "Objects") == {(0,): [5]}
    assert rh.File3dm.ReadArchiveVersion(str(target)) == 70
    model = rh.File3dm.Read(str(target))
    assert model.Settings.ModelUnitSystem == rh.UnitSystem.Millimeters
    layers = {layer.Index: layer.FullPath for layer in model.Layers}
    found = {(layers[o.Attributes.LayerIndex], o.Attributes.Name, o.Attributes.GetUserString("PanelID"))
             for o in model.Objects}
    assert found == {
        ("Torsal::Curves", "Curve 1", ""), ("Torsal::Rulings", "Ruling 1", ""),
        ("Torsal::Panels", "A-1", "A-1"), ("Torsal::Panels", "A-2", "A-2"), ("Torsal::Meshes", "Mesh 1", ""),
    }
    panel = next(o for o in model.Objects if o.Attributes.Name == "A-2")
    assert panel.Geometry.IsClosed and panel.Geometry.IsPolyline()
    assert panel.Attributes.GetUserString("TorsalPath") == "{0}"
    assert panel.Attributes.GetUserString("TorsalIndex") == "1"


def test_nothing_is_written_while_write_is_false(tmp_path):
    target = tmp_path / "never.3dm"
    result = run(Export3dm(), Path=str(target), Curves=tree({(0,): [CURVES["line"]]}))
    assert result.state == OK
    assert not target.exists()
    assert "Write is false: nothing written" in texts(result)


def test_export_then_import_gives_the_same_geometry_back(tmp_path):
    curve, surface = CURVES["rational cubic"], SURFACES["ruled from rulings"]
    _, target = export(tmp_path, Curves=[curve], Surfaces=[surface], Panels=[rectangle(0, 0, 2, 1)])
    result = run(Import3dm(), Path=str(target))
    assert result.state == OK, texts(result)
    curves = out(result, "Curves")[(0,)]
    assert out(result, "CurveLayers")[(0,)] == ["Torsal::Curves", "Torsal::Panels"]
    assert out(result, "CurveNames")[(0,)] == ["Curve 1", "Panel 1"]
    assert np.abs(curves[0].point_at(T) - curve.point_at(T)).max() <= 1e-12
    (back,) = out(result, "Surfaces")[(0,)]
    u, v = RNG.random(200), RNG.random(200)
    assert np.abs(back.point_at(u, v) - surface.point_at(u, v)).max() <= 1e-12
    assert out(result, "FileUnits") == {(0,): ["m"]}


# ------------------------------------------------------------------ files made by rhino3dm


def _layer(model: rh.File3dm, name: str, parent: int | None = None) -> int:
    layer = rh.Layer()
    layer.Name = name
    if parent is not None:
        layer.ParentLayerId = model.Layers.FindIndex(parent).Id
    return model.Layers.Add(layer)


def _attributes(layer: int, name: str) -> rh.ObjectAttributes:
    attributes = rh.ObjectAttributes()
    attributes.LayerIndex = layer
    attributes.Name = name
    return attributes


@pytest.fixture
def rhino_file(tmp_path):
    """A millimetre file made with rhino3dm's own API: curves on Facade and Roof::Edges."""
    model = rh.File3dm()
    model.Settings.ModelUnitSystem = rh.UnitSystem.Millimeters
    facade = _layer(model, "Facade")
    roof = _layer(model, "Roof")
    edges = _layer(model, "Edges", roof)
    model.Objects.AddCircle(rh.Circle(rh.Point3d(1000, 0, 0), 500), _attributes(facade, "ring"))
    model.Objects.AddLine(rh.Point3d(0, 0, 0), rh.Point3d(2000, 0, 0), _attributes(facade, "sill"))
    corners = [rh.Point3d(0, 0, 3000), rh.Point3d(4000, 0, 3000), rh.Point3d(4000, 2000, 3000),
               rh.Point3d(0, 0, 3000)]
    model.Objects.AddPolyline(corners, _attributes(edges, "eave"))
    spline = rh.NurbsCurve.Create(False, 3, [rh.Point3d(i * 1000, (i % 2) * 500, 0) for i in range(6)])
    model.Objects.AddCurve(spline, _attributes(roof, "ridge"))
    target = tmp_path / "drawn-in-rhino.3dm"
    assert model.Write(str(target), 7)
    return target


def test_rhino_file_imports_with_its_layers_names_and_units(rhino_file):
    result = run(Import3dm(), Path=str(rhino_file), Units="m")
    assert result.state == OK, texts(result)
    assert out(result, "CurveLayers")[(0,)] == ["Facade", "Facade", "Roof::Edges", "Roof"]
    assert out(result, "CurveNames")[(0,)] == ["ring", "sill", "eave", "ridge"]
    assert out(result, "FileUnits") == {(0,): ["mm"]}
    ring, sill, eave, ridge = out(result, "Curves")[(0,)]
    assert ring.closed and math.isclose(ring.length, 2 * math.pi * 0.5, rel_tol=1e-12)
    assert np.allclose(ring.point_at(T)[:, 0].max(), 1.5, rtol=0, atol=1e-12)
    assert isinstance(sill, Line) and sill.length == pytest.approx(2.0, rel=1e-15)
    assert isinstance(eave, Polyline) and eave.closed
    assert np.allclose(eave.points[1], [4.0, 0.0, 3.0], rtol=0, atol=1e-15)
    assert ridge.end.tolist() == pytest.approx([5.0, 0.5, 0.0], abs=1e-15)
    assert "Converted from mm to m (× 0.001)" in texts(result)


def test_mm_file_into_a_mm_graph_keeps_its_numbers(rhino_file):
    result = run(Import3dm(), Path=str(rhino_file), Units="mm")
    sill = out(result, "Curves")[(0,)][1]
    assert sill.length == 2000.0


@pytest.mark.parametrize(
    ("layers", "names"),
    [
        (["Facade"], ["ring", "sill"]),
        (["Roof"], ["eave", "ridge"]),  # a layer brings its sublayers
        (["Roof::Edges"], ["eave"]),
        (["edges"], ["eave"]),  # by name, any case
        (["F*"], ["ring", "sill"]),
        (["Facade", "Roof::Edges"], ["ring", "sill", "eave"]),
    ],
)
def test_layer_filter_picks_layers_by_path_name_or_wildcard(rhino_file, layers, names):
    result = run(Import3dm(), Path=str(rhino_file), Layers=tree({(0,): layers}))
    assert out(result, "CurveNames")[(0,)] == names


def test_layer_filter_matching_nothing_warns(rhino_file):
    result = run(Import3dm(), Path=str(rhino_file), Layers=tree({(0,): ["Nope"]}))
    assert "No curves, surfaces or meshes found on those layers" in texts(result)


def test_extrusions_breps_and_meshes_come_in_as_surfaces_and_meshes(tmp_path):
    model = rh.File3dm()
    model.Settings.ModelUnitSystem = rh.UnitSystem.Meters
    profile = rh.Circle(rh.Point3d(0, 0, 0), 1.0).ToNurbsCurve()
    model.Objects.AddExtrusion(rh.Extrusion.Create(profile, 2.0, False))
    model.Objects.AddBrep(rh.Brep.CreateFromSphere(rh.Sphere(rh.Point3d(5, 0, 0), 1.0)))
    model.Objects.AddSurface(rh.NurbsSurface.CreateFromCylinder(
        rh.Cylinder(rh.Circle(rh.Point3d(0, 5, 0), 1.0), 3.0)))
    mesh = rh.Mesh()
    for x, y in [(0, 0), (1, 0), (1, 1), (0, 1)]:
        mesh.Vertices.Add(x, y, 0)
    mesh.Faces.AddFace(0, 1, 2, 3)
    model.Objects.AddMesh(mesh)
    model.Objects.AddPoint(rh.Point3d(0, 0, 0))
    target = tmp_path / "solids.3dm"
    model.Write(str(target), 7)
    result = run(Import3dm(), Path=str(target))
    assert result.state == OK, texts(result)
    extrusion, sphere, cylinder = out(result, "Surfaces")[(0,)]
    assert extrusion.area() == pytest.approx(2 * math.pi * 2.0, rel=1e-9)
    assert sphere.area() == pytest.approx(4 * math.pi, rel=1e-9)
    assert cylinder.area() == pytest.approx(2 * math.pi * 3.0, rel=1e-9)
    (square,) = out(result, "Meshes")[(0,)]
    assert len(square.faces) == 2 and square.area == pytest.approx(1.0)
    assert "Not imported (not curves, surfaces or meshes): 1 Point" in texts(result)


# ------------------------------------------------------------------ bad files


def _bad_file(tmp_path, kind: str):
    target = tmp_path / f"{kind}.3dm"
    if kind == "empty":
        target.write_bytes(b"")
    elif kind == "text":
        target.write_text("this is not a Rhino file\n")
    elif kind.startswith("truncated"):
        model = rh.File3dm()
        model.Objects.AddCircle(rh.Circle(rh.Point3d(0, 0, 0), 1.0))
        whole = tmp_path / "whole.3dm"
        model.Write(str(whole), 7)
        data = whole.read_bytes()
        cut = {"truncated-header": 40, "truncated-middle": len(data) // 2, "truncated-end": len(data) - 20}
        target.write_bytes(data[: cut[kind]])
    elif kind == "folder":
        target.mkdir()
    return target


@pytest.mark.parametrize(
    ("kind", "needle"),
    [
        ("missing", "There is no file"),
        ("empty", "is empty (0 bytes)"),
        ("text", "is not a Rhino .3dm file"),
        ("truncated-header", "is damaged or truncated"),
        ("truncated-middle", "is damaged or truncated"),
        ("truncated-end", "is damaged or truncated"),
        ("folder", "is a folder"),
    ],
)
def test_bad_file_puts_the_node_in_error_with_the_reason(tmp_path, kind, needle):
    target = tmp_path / "missing.3dm" if kind == "missing" else _bad_file(tmp_path, kind)
    result = run(Import3dm(), Path=str(target))
    assert result.state == ERROR
    (message,) = texts(result)
    assert needle in message
    assert "Traceback" not in message and "Error:" not in message


def test_unknown_units_put_the_node_in_error(rhino_file):
    result = run(Import3dm(), Path=str(rhino_file), Units="furlongs")
    assert result.state == ERROR
    assert texts(result) == ["Units 'furlongs' is not a length unit Torsal knows: use mm, cm, m, in or ft"]


def test_file_with_custom_units_is_refused_with_advice(tmp_path):
    model = rh.File3dm()
    model.Settings.ModelUnitSystem = rh.UnitSystem.CustomUnits
    model.Objects.AddLine(rh.Point3d(0, 0, 0), rh.Point3d(1, 0, 0))
    target = tmp_path / "custom.3dm"
    model.Write(str(target), 7)
    result = run(Import3dm(), Path=str(target))
    assert result.state == ERROR
    assert "units are CustomUnits" in texts(result)[0]


def test_unitless_file_is_read_as_model_units(tmp_path):
    model = rh.File3dm()
    model.Settings.ModelUnitSystem = rh.UnitSystem.None_ if hasattr(rh.UnitSystem, "None_") else getattr(
        rh.UnitSystem, "None")
    model.Objects.AddLine(rh.Point3d(0, 0, 0), rh.Point3d(7, 0, 0))
    target = tmp_path / "plain.3dm"
    model.Write(str(target), 7)
    result = run(Import3dm(), Path=str(target), Units="mm")
    assert out(result, "Curves")[(0,)][0].length == 7.0
    assert out(result, "FileUnits") == {(0,): ["none"]}


def test_export_to_an_unwritable_place_is_an_error_not_a_crash(tmp_path):
    blocker = tmp_path / "file"
    blocker.write_text("x")
    result = run(Export3dm(), Path="file/sub/model.3dm", Write=True, writes=allowed(tmp_path),
                 Curves=tree({(0,): [CURVES["line"]]}))
    assert result.state == ERROR
    assert "Cannot create the folder" in texts(result)[0]


def test_relative_path_is_taken_from_the_graphs_folder(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path.parent)
    result = run(Export3dm(), Path="out/rel.3dm", Write=True, writes=allowed(tmp_path),
                 Curves=tree({(0,): [CURVES["line"]]}))
    assert out(result, "Path") == {(0,): [str(tmp_path / "out" / "rel.3dm")]}
    assert (tmp_path / "out" / "rel.3dm").exists()


def test_nurbs_forms_of_exact_kinds_report_no_deviation():
    assert threedm.curve_form(CURVES["circle"]).deviation == 0.0
    assert threedm.surface_form(SURFACES["ruled from rulings"]).deviation == 0.0
    assert threedm.surface_form(SURFACES["ruled between two curves"]).deviation == 0.0


def test_a_sphere_is_interpolated_within_1e_8_of_its_size_and_the_node_says_so(tmp_path):
    sphere = SURFACES["sphere (interpolated)"]
    form = threedm.surface_form(sphere)
    assert 0 < form.deviation <= 1e-8 * 6.0
    result, target = export(tmp_path, Surfaces=[sphere])
    assert any(t.startswith("Some geometry was interpolated as NURBS: within") for t in texts(result))
    (obj,) = list(rh.File3dm.Read(str(target)).Objects)
    u, v = RNG.random(1000), RNG.random(1000)
    gap = np.abs(rhino_surface_points(obj.Geometry, u, v) - sphere.point_at(u, v)).max()
    assert gap <= form.deviation * 1.5


def test_a_ruled_parametric_surface_is_written_degree_1_across(tmp_path):
    form = threedm.surface_form(parametric_surface.cylinder(1.0, 2.0))
    assert (form.nurbs.degree_u, form.nurbs.degree_v) == (3, 1)
    assert form.deviation <= 1e-8 * 2.0
