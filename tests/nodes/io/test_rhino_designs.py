"""Real designs in: NURBS surfaces from Rhino files (trimmed or not), and the shipped example.

Expected values come from rhino3dm's own evaluation (PointAt, NormalAt) of the very objects
written to the file, and from closed forms for the trim loops.
"""

from __future__ import annotations

import uuid
from pathlib import Path

import numpy as np
import rhino3dm as rh

from tests.support.node_helpers import run, texts
from torsal.engine.solver import OK, WARNING
from torsal.nodes.geometry.nurbs_surface import NurbsSurface
from torsal.nodes.geometry.trimmed_surface import TrimmedSurface
from torsal.nodes.io.rhino import Import3dm

ROOT = Path(__file__).resolve().parents[3]
RNG = np.random.default_rng(29)


def rational_surface() -> rh.NurbsSurface:
    """A rational bicubic × biquadratic surface with uneven knots, made with rhino3dm."""
    surface = rh.NurbsSurface.Create(3, True, 4, 3, 6, 4)
    for i in range(6):
        for j in range(4):
            w = 0.6 + RNG.random()
            x, y, z = i * 2.0, j * 1.5, np.sin(i) * np.cos(j) + RNG.random()
            surface.Points[(i, j)] = rh.Point4d(w * x, w * y, w * z, w)
    for k, value in enumerate([0, 0, 0, 0.7, 1.1, 3, 3, 3]):
        surface.KnotsU[k] = value
    for k, value in enumerate([-1, -1, 0.5, 2, 2]):
        surface.KnotsV[k] = value
    return surface


def write(path: Path, *objects) -> Path:
    model = rh.File3dm()
    model.Settings.ModelUnitSystem = rh.UnitSystem.Meters
    for number, geometry in enumerate(objects, 1):
        attributes = rh.ObjectAttributes()
        attributes.Id = uuid.UUID(int=number)
        if isinstance(geometry, rh.Brep):
            model.Objects.AddBrep(geometry, attributes)
        else:
            model.Objects.AddSurface(geometry, attributes)
    assert model.Write(str(path), 7)
    return path


def test_a_rational_nurbs_surface_evaluates_as_rhino3dm_does_points_and_normals(tmp_path):
    original = rational_surface()
    result = run(Import3dm(), Path=str(write(tmp_path / "s.3dm", original)))
    (surface,) = result.outputs["Surfaces"].all_items()
    assert isinstance(surface, NurbsSurface) and surface.is_rational
    du, dv = original.Domain(0), original.Domain(1)
    a, b = RNG.random(300), RNG.random(300)
    ours = surface.point_at(a, b)
    normals = surface.normal_at(a, b)
    for k in range(len(a)):
        u, v = du.T0 + (du.T1 - du.T0) * a[k], dv.T0 + (dv.T1 - dv.T0) * b[k]
        p, n = original.PointAt(u, v), original.NormalAt(u, v)
        assert np.linalg.norm(ours[k] - [p.X, p.Y, p.Z]) <= 1e-12 * 10
        assert np.linalg.norm(normals[k] - [n.X, n.Y, n.Z]) <= 1e-9


def test_a_trimmed_face_comes_in_with_its_trim_loops_in_parameter_space(tmp_path):
    disc = rh.Circle(rh.Point3d(1.0, 0.5, 0.0), 1.5).ToNurbsCurve()
    plane = rh.Plane.WorldXY()
    brep = rh.Brep.CreateTrimmedPlane(plane, disc)  # (rhino3dm makes no trimmed freeform faces)
    result = run(Import3dm(), Path=str(write(tmp_path / "t.3dm", brep)))
    assert result.state == OK, texts(result)
    assert "1 brep faces came in trimmed: each keeps its trim loops" in texts(result)
    (surface,) = result.outputs["Surfaces"].all_items()
    assert isinstance(surface, TrimmedSurface)
    (loop,) = surface.loops_3d()
    centre = np.array([1.0, 0.5, 0.0])
    assert np.abs(np.linalg.norm(loop - centre, axis=1) - 1.5).max() <= 1e-9  # on the circle
    assert len(surface.holes) == 0
    # inside is inside the circle: its (u, v) mapped through the surface
    u, v = RNG.random(2000), RNG.random(2000)
    points = surface.point_at(u, v)
    expected = np.linalg.norm(points - centre, axis=1) < 1.5
    clear = np.abs(np.linalg.norm(points - centre, axis=1) - 1.5) > 0.02  # away from the polygon's chords
    assert np.array_equal(surface.inside(u, v)[clear], expected[clear])
    # the kept part's share of the parameter square is the disc's share of the plane's square
    size = np.ptp(surface.surface.control_points.reshape(-1, 3), axis=0)[:2]
    assert abs(surface.parameter_share - np.pi * 1.5**2 / (size[0] * size[1])) <= 2e-3
    # its area and centroid are the disc's (to the loop's polygon), and the preview drops the rest
    area, centroid = surface.area_and_centroid()
    assert abs(area - np.pi * 1.5**2) <= 5e-3 * area
    assert np.linalg.norm(centroid - centre) <= 1e-6
    points, faces, _ = surface.mesh_arrays(65, 65)
    assert np.linalg.norm(points[faces].mean(axis=1) - centre, axis=1).max() <= 1.5


def test_an_untrimmed_brep_face_comes_in_as_its_surface(tmp_path):
    brep = rh.Brep.CreateFromSurface(rational_surface())
    result = run(Import3dm(), Path=str(write(tmp_path / "b.3dm", brep)))
    (surface,) = result.outputs["Surfaces"].all_items()
    assert isinstance(surface, NurbsSurface)
    assert not [t for t in texts(result) if "trim" in t]


def test_the_canopy_example_reads_its_design_and_solves_with_no_warning(tmp_path):
    from torsal.app.headless import run_file

    solved = run_file(ROOT / "torsal" / "resources" / "examples" / "rationalise-canopy.graph",
                      write_folder=tmp_path)  # as --out: the design is still found beside the graph
    states = {node_id: solved.solver.result(node_id).state for node_id in solved.graph.nodes}
    assert WARNING not in states.values() and set(states.values()) == {OK}, states
    (design,) = solved.solver.result("design").outputs["Surfaces"].all_items()
    box = np.ptp(design.point_at(*np.meshgrid(np.linspace(0, 1, 9), np.linspace(0, 1, 9))).reshape(-1, 3),
                 axis=0)
    assert np.allclose(box[:2], [12.0, 8.0], rtol=0, atol=1e-9)  # millimetres into metres
    deviations = solved.solver.result("strips").outputs["Deviation"].all_items()
    assert deviations and max(deviations) <= 0.02


def test_a_trimmed_surface_is_written_as_its_untrimmed_surface_exactly(tmp_path):
    from tests.support.io_helpers import rhino_surface_points
    from tests.support.node_helpers import allowed, tree
    from torsal.nodes.io.rhino import Export3dm

    disc = rh.Circle(rh.Point3d(1.0, 0.5, 0.0), 1.5).ToNurbsCurve()
    brep = rh.Brep.CreateTrimmedPlane(rh.Plane.WorldXY(), disc)
    (surface,) = run(Import3dm(), Path=str(write(tmp_path / "t.3dm", brep))).outputs["Surfaces"].all_items()
    result = run(Export3dm(), Path="out.3dm", Write=True, writes=allowed(tmp_path),
                 Surfaces=tree({(0,): [surface]}))
    assert result.state == OK, texts(result)
    (obj,) = list(rh.File3dm.Read(str(tmp_path / "out.3dm")).Objects)
    u, v = RNG.random(200), RNG.random(200)
    assert np.abs(rhino_surface_points(obj.Geometry, u, v) - surface.surface.point_at(u, v)).max() <= 1e-12
