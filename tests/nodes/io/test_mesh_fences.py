"""Issue 24: ImportMesh reads side files only inside the mesh's folder, only regular files,
and refuses an oversized file before reading it (each trap built here from scratch)."""

from __future__ import annotations

import json
import os
import struct
import threading
from pathlib import Path

import numpy as np
import pytest

from torsal.nodes.io.common import FileFailure
from torsal.nodes.io.formats import meshfiles
from torsal.nodes.limits import MAX_MESH_FILE_BYTES

TRIANGLE_OBJ = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"


def obj_with_material(folder: Path, library: str) -> Path:
    path = folder / "scan.obj"
    path.write_text(f"mtllib {library}\nusemtl paint\n{TRIANGLE_OBJ}")
    return path


@pytest.fixture
def reads(monkeypatch):
    """Every file name the fenced resolver is asked for, and what it answered."""
    asked: list[tuple[str, str]] = []
    original = meshfiles.FencedResolver.get

    def get(self, name):
        try:
            data = original(self, name)
        except Exception as exc:
            asked.append((name, type(exc).__name__))
            raise
        asked.append((name, "read"))
        return data

    monkeypatch.setattr(meshfiles.FencedResolver, "get", get)
    return asked


@pytest.mark.parametrize("where", ["dotdot", "absolute", "link"])
def test_an_obj_material_library_outside_the_folder_is_not_read(tmp_path, where, reads):
    outside = tmp_path / "outside"
    outside.mkdir()
    secret = outside / "secret.mtl"
    secret.write_text("newmtl paint\nKd 1 0 0\n")
    scans = tmp_path / "scans"
    scans.mkdir()
    (scans / "inside.mtl").symlink_to(secret)
    library = {"dotdot": "../outside/secret.mtl", "absolute": str(secret), "link": "inside.mtl"}[where]
    mesh = meshfiles.read_mesh(obj_with_material(scans, library))
    assert len(mesh.faces) == 1  # the triangles still come in, without the material
    assert reads and all(answer != "read" for _, answer in reads)


def test_an_obj_material_library_that_is_a_fifo_does_not_hang(tmp_path, reads):
    """Opening the pipe would wait forever: the read runs in a thread, so a hang fails the
    test (after a minute) instead of stopping the suite."""
    os.mkfifo(tmp_path / "paint.mtl")
    found = []
    reader = threading.Thread(target=lambda: found.append(meshfiles.read_mesh(
        obj_with_material(tmp_path, "paint.mtl"))), daemon=True)
    reader.start()
    reader.join(60)
    assert not reader.is_alive(), "reading the mesh waits on the pipe"
    assert len(found[0].faces) == 1
    assert reads == [("paint.mtl", "ValueError")]


def test_a_material_library_inside_the_folder_is_read(tmp_path, reads):
    (tmp_path / "paint.mtl").write_text("newmtl paint\nKd 1 0 0\n")
    meshfiles.read_mesh(obj_with_material(tmp_path, "paint.mtl"))
    assert ("paint.mtl", "read") in reads


def glb_with_external_buffer(path: Path, uri: str) -> Path:
    """A GLB whose one buffer lives in the file ``uri`` names (a triangle, 3 floats × 3)."""
    gltf = {
        "asset": {"version": "2.0"},
        "buffers": [{"byteLength": 36, "uri": uri}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                       "min": [0, 0, 0], "max": [1, 1, 0]}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
        "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}], "scene": 0,
    }
    chunk = json.dumps(gltf).encode()
    chunk += b" " * (-len(chunk) % 4)
    body = struct.pack("<II", len(chunk), 0x4E4F534A) + chunk
    path.write_bytes(struct.pack("<III", 0x46546C67, 2, 12 + len(body)) + body)
    return path


@pytest.mark.parametrize("where", ["dotdot", "fifo"])
def test_a_glb_buffer_uri_outside_the_folder_or_a_fifo_is_refused(tmp_path, where, reads):
    outside = tmp_path / "outside"
    outside.mkdir()
    np.array([0, 0, 0, 1, 0, 0, 0, 1, 0], dtype="<f4").tofile(outside / "data.bin")
    scans = tmp_path / "scans"
    scans.mkdir()
    if where == "fifo":
        os.mkfifo(scans / "data.bin")
    uri = "../outside/data.bin" if where == "dotdot" else "data.bin"
    with pytest.raises(FileFailure):
        meshfiles.read_mesh(glb_with_external_buffer(scans / "part.glb", uri))
    assert all(answer != "read" for _, answer in reads)


def test_a_1_gb_sparse_mesh_is_refused_before_reading(tmp_path, monkeypatch):
    """Refused on its size: nothing of it is read (how fast: tests/benchmarks/bench_hardening.py)."""
    big = tmp_path / "huge.stl"
    with big.open("wb") as handle:
        handle.truncate(2**30)  # sparse: no disk used
    monkeypatch.setattr(meshfiles, "read_bounded", lambda *args: pytest.fail("the file was read"))
    with pytest.raises(FileFailure, match=f"read up to {MAX_MESH_FILE_BYTES // 2**20} MB"):
        meshfiles.read_mesh(big)


def test_a_fifo_or_a_device_is_refused_by_type_not_as_empty(tmp_path):
    os.mkfifo(tmp_path / "pipe.stl")
    with pytest.raises(FileFailure, match="named pipe"):
        meshfiles.read_mesh(tmp_path / "pipe.stl")
    if Path("/dev/zero").exists():
        os.symlink("/dev/zero", tmp_path / "zero.stl")
        with pytest.raises(FileFailure, match="a device"):
            meshfiles.read_mesh(tmp_path / "zero.stl")
