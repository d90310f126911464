"""TriangleMesh recognises trimesh's meshes without importing trimesh, and the flagship's
palettes and solve never import it (what the desktop app's start-up rests on)."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import numpy as np
import trimesh

from torsal.engine.types import type_of
from torsal.nodes.common.preview import costly, preview_of
from torsal.nodes.common.values import MESH
from torsal.nodes.geometry.trimesh_type import TriangleMesh

ROOT = Path(__file__).resolve().parents[3]


def test_a_trimesh_and_its_subclasses_are_triangle_meshes_and_nothing_else_is():
    box = trimesh.creation.box()  # a trimesh.primitives.Box: a subclass of Trimesh
    assert isinstance(box, TriangleMesh)
    assert isinstance(trimesh.Trimesh(box.vertices, box.faces), TriangleMesh)
    assert issubclass(trimesh.Trimesh, TriangleMesh)
    assert not isinstance(trimesh.PointCloud(box.vertices), TriangleMesh)
    assert not isinstance(np.zeros((3, 3)), TriangleMesh)
    assert not isinstance(None, TriangleMesh)


def test_a_mesh_on_a_wire_is_a_mesh_and_draws_its_triangles():
    box = trimesh.creation.box(extents=(2.0, 3.0, 4.0))
    assert type_of(box) is MESH
    assert MESH.accepts(box)
    drawn = preview_of(box)
    assert drawn is not None and len(drawn.meshes) == 1
    assert drawn.meshes[0].faces.shape == (12, 3)
    # the area of what is drawn: the box's, 2 (2·3 + 2·4 + 3·4) = 52
    v = drawn.meshes[0].vertices[drawn.meshes[0].faces]
    areas = 0.5 * np.linalg.norm(np.cross(v[:, 1] - v[:, 0], v[:, 2] - v[:, 0]), axis=1)
    assert np.isclose(areas.sum(), 52.0)
    assert not costly(box)


def test_solving_the_flagship_imports_no_trimesh():
    example = ROOT / "torsal" / "resources" / "examples" / "kaohsiung-stadium.graph"
    script = (
        "import sys\n"
        "from torsal.app.headless import run_file\n"
        f"run = run_file({str(example)!r})\n"
        "assert run.ok\n"
        "from torsal.nodes.common.preview import preview_of\n"
        "for node_id in run.graph.nodes:\n"
        "    for tree in run.solver.result(node_id).outputs.values():\n"
        "        for item in tree.all_items():\n"
        "            preview_of(item)\n"
        "print(sorted(m for m in sys.modules if m.split('.')[0] == 'trimesh'))\n"
    )
    out = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, cwd=ROOT,
                         timeout=120)
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == "[]"
