"""Triangle meshes in and out through trimesh: OBJ, STL, PLY and GLB.

OBJ, STL and PLY carry no units: their numbers are taken to be in ``file_units``
(by default the model's own). glTF/GLB is in metres by its specification, always.
OBJ is written with 15 significant digits; STL, PLY and GLB store single-precision
floats (about 7 digits), as those formats do. Several meshes are written as one.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

import numpy as np
import trimesh

from torsal.nodes.io.common import FileFailure, readable, replacing, unit_name, unit_scale, writable

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
    try:
        loaded = trimesh.load(str(path), file_type=suffix[1:], force="mesh", process=False)
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
