"""io.ImportMesh and io.ExportMesh: OBJ, STL, PLY and GLB through trimesh."""

from __future__ import annotations

import numpy as np
import pytest
import trimesh
from scipy.spatial import cKDTree

from tests.support.node_helpers import allowed, out, run, texts, tree
from torsal.engine.solver import ERROR, OK
from torsal.nodes.geometry import parametric_surface
from torsal.nodes.io.meshes import ExportMesh, ImportMesh

FORMATS = ["obj", "stl", "ply", "glb"]
PRECISION = {"obj": 1e-13, "stl": 1e-6, "ply": 1e-6, "glb": 1e-6}  # STL, PLY, GLB: single precision


def ball() -> trimesh.Trimesh:
    return trimesh.creation.icosphere(subdivisions=2, radius=1.5)


@pytest.mark.parametrize("fmt", FORMATS)
def test_mesh_written_then_read_back_has_the_same_triangles(tmp_path, fmt):
    mesh = ball()
    target = tmp_path / f"ball.{fmt}"
    result = run(ExportMesh(), Path=target.name, Meshes=tree({(0,): [mesh]}), Write=True,
                 writes=allowed(tmp_path))
    assert result.state == OK, texts(result)
    assert out(result) == {(0,): [str(target)]}
    back = out(run(ImportMesh(), Path=str(target)))[(0,)][0]
    assert len(back.faces) == len(mesh.faces)
    assert back.area == pytest.approx(mesh.area, rel=PRECISION[fmt] * 10)
    gaps, _ = cKDTree(mesh.vertices).query(back.vertices)  # STL repeats vertices per triangle
    assert gaps.max() <= PRECISION[fmt] * 1.5


def test_glb_is_in_metres_whatever_the_model_units(tmp_path):
    target = tmp_path / "ball.glb"
    run(ExportMesh(), Path=target.name, Meshes=tree({(0,): [ball()]}), Units="mm", Write=True,
        writes=allowed(tmp_path))
    raw = trimesh.load(str(target), force="mesh")
    assert np.ptp(raw.vertices, axis=0).max() == pytest.approx(0.003, rel=1e-6)
    back = out(run(ImportMesh(), Path=str(target), Units="mm"))[(0,)][0]
    assert np.ptp(back.vertices, axis=0).max() == pytest.approx(3.0, rel=1e-6)


def test_file_units_scale_unitless_formats(tmp_path):
    target = tmp_path / "scan.stl"
    ball().export(str(target))  # numbers in millimetres, say
    back = out(run(ImportMesh(), Path=str(target), FileUnits="mm", Units="m"))[(0,)][0]
    assert np.ptp(back.vertices, axis=0).max() == pytest.approx(0.003, rel=1e-6)


def test_surfaces_and_several_meshes_are_written_as_one_mesh(tmp_path):
    target = tmp_path / "both.obj"
    sphere = parametric_surface.sphere(1.0)
    result = run(ExportMesh(), Path=target.name, Meshes=tree({(0,): [ball(), sphere]}), Write=True,
                 writes=allowed(tmp_path))
    assert result.state == OK, texts(result)
    back = out(run(ImportMesh(), Path=str(target)))[(0,)][0]
    assert len(back.faces) == len(ball().faces) + 2 * 32 * 32


def test_nothing_is_written_while_write_is_false(tmp_path):
    target = tmp_path / "no.obj"
    result = run(ExportMesh(), Path=str(target), Meshes=tree({(0,): [ball()]}))
    assert result.state == OK and not target.exists()


@pytest.mark.parametrize(
    ("name", "content", "needle"),
    [
        ("missing.obj", None, "There is no file"),
        ("empty.stl", b"", "is empty (0 bytes)"),
        ("words.obj", b"these are not vertices\n", "holds no triangles"),
        ("zeros.stl", b"\x00" * 50, "holds no triangles"),
        ("fake.glb", b"glTFxxxxxxxxxxxxxxxxxxxx", "is not a readable GLB file"),
        ("points.ply", b"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
         b"property float z\nend_header\n1 2 3\n",
         "holds no triangles"),
        ("model.fbx", b"x", "must end in .obj, .stl, .ply or .glb"),
    ],
)
def test_bad_mesh_file_puts_the_node_in_error_with_the_reason(tmp_path, name, content, needle):
    target = tmp_path / name
    if content is not None:
        target.write_bytes(content)
    result = run(ImportMesh(), Path=str(target))
    assert result.state == ERROR
    assert needle in texts(result)[0]
