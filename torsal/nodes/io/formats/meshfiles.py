"""Triangle meshes in and out through trimesh: OBJ, STL, PLY and GLB.

OBJ, STL and PLY carry no units: their numbers are taken to be in ``file_units``
(by default the model's own). glTF/GLB is in metres by its specification, always.
OBJ is written with 15 significant digits; STL, PLY and GLB store single-precision
floats (about 7 digits), as those formats do. Several meshes are written as one.

Reading is fenced: the mesh and every file it names (an OBJ's ``mtllib``, a glTF's
buffer ``uri``) must be regular files of at most :data:`MAX_MESH_FILE_BYTES`, checked
before reading (a pipe is refused by type, never opened to wait), and the files it names
must lie in the mesh's own folder (no absolute path, no ``..`` or link leading out).
"""

from __future__ import annotations

import io
import os
from collections.abc import Sequence
from pathlib import Path

import numpy as np
import trimesh
from trimesh.resolvers import FilePathResolver

from torsal.engine.bounded_read import UnreadableFileError, kind_of, read_bounded
from torsal.nodes.io.common import FileFailure, readable, replacing, unit_name, unit_scale, writable
from torsal.nodes.limits import MAX_MESH_FILE_BYTES

SUFFIXES = (".obj", ".stl", ".ply", ".glb")
NAMES = {".obj": "OBJ", ".stl": "STL", ".ply": "PLY", ".glb": "GLB"}


def _format(path: Path) -> str:
    suffix = path.suffix.lower()
    if suffix not in SUFFIXES:
        raise FileFailure(
            f"{path.name}: a mesh file must end in .obj, .stl, .ply or .glb, not {suffix or 'nothing'}"
        )
    return suffix


def _file_units(suffix: str, file_units: str | None, units: str) -> str:
    if suffix == ".glb":
        return "m"
    return unit_name(file_units, "FileUnits") if file_units else unit_name(units)


def read_mesh(path: Path, units: str = "m", file_units: str | None = None) -> trimesh.Trimesh:
    """One triangle mesh from the file (a GLB scene's meshes joined, placed by its
    transforms), scaled into ``units``. Raises FileFailure with the reason."""
    suffix = _format(path)
    readable(path, NAMES[suffix])
    source = _file_units(suffix, file_units, units)
    data = fenced_read(path, NAMES[suffix])
    try:
        loaded = trimesh.load(io.BytesIO(data), file_type=suffix[1:], force="mesh", process=False,
                              resolver=FencedResolver(str(path)))
    except Exception as exc:  # trimesh raises many kinds on malformed files
        raise FileFailure(f"{path.name} is not a readable {NAMES[suffix]} file ({exc})") from None
    if not isinstance(loaded, trimesh.Trimesh) or len(loaded.faces) == 0:
        raise FileFailure(
            f"{path.name} holds no triangles: it is not a {NAMES[suffix]} mesh, or an empty one"
        )
    mesh = loaded.copy()
    if not np.all(np.isfinite(mesh.vertices)):
        raise FileFailure(f"{path.name} has a vertex with a coordinate that is not a finite number")
    factor = unit_scale(source, units)
    if factor != 1.0:
        mesh.apply_scale(factor)
    return mesh


def fenced_read(path: Path, what: str) -> bytes:
    """The bytes of ``path``, a regular file of at most :data:`MAX_MESH_FILE_BYTES` (its
    size checked before reading), or a FileFailure saying why not."""
    found = kind_of(path)
    if found is not None:
        raise FileFailure(f"{path.name} is {found}, not a {what} file: only regular files are read")
    try:
        size = os.stat(path).st_size
    except OSError as exc:
        raise FileFailure(f"Cannot read {path}: {exc.strerror or exc}") from None
    if size > MAX_MESH_FILE_BYTES:
        raise FileFailure(f"{path.name} is {size / 2**20:,.0f} MB; a {what} file is read up to "
                          f"{MAX_MESH_FILE_BYTES // 2**20} MB (split the mesh, or decimate it)")
    try:
        return read_bounded(path, MAX_MESH_FILE_BYTES, f"a {what} file")
    except UnreadableFileError as exc:
        raise FileFailure(f"{path.name}: {exc}") from None


class FencedResolver(FilePathResolver):
    """What trimesh may read besides the mesh: files in the mesh's own folder only (links
    resolved, and refused if they lead out), regular files, size-capped before reading."""

    def get(self, name: str) -> bytes:
        path = self.absolute(name.strip())  # ValueError if it leads out of the folder
        if not path.exists():
            raise FileNotFoundError(name)
        try:
            return fenced_read(path, "side")
        except FileFailure as exc:
            raise ValueError(str(exc)) from None

    def keys(self):  # type: ignore[no-untyped-def]
        return iter(())  # never walk the folder (it may be huge, or hold pipes)


def write_mesh(
    meshes: Sequence[trimesh.Trimesh], path: Path, units: str = "m", file_units: str | None = None
) -> Path:
    """Write the meshes (joined into one) to ``path`` in the format its extension names."""
    suffix = _format(path)
    if not meshes:
        raise FileFailure("There is no mesh to write")
    mesh = trimesh.util.concatenate(list(meshes)) if len(meshes) > 1 else meshes[0].copy()
    factor = unit_scale(units, _file_units(suffix, file_units, units))
    if factor != 1.0:
        mesh.apply_scale(factor)
    writable(path)
    options = {"digits": 15} if suffix == ".obj" else {}
    return replacing(path, lambda temporary: mesh.export(str(temporary), file_type=suffix[1:], **options))
