"""Mesh files: ImportMesh and ExportMesh for OBJ, STL, PLY and GLB (through trimesh)."""

from __future__ import annotations

from typing import Any

from torsal.engine.datatree import DataTree
from torsal.engine.node import TREE, In, Node, Out
from torsal.engine.types import BOOLEAN, TEXT
from torsal.nodes.common.values import MESH
from torsal.nodes.io.common import file_errors, may_write, read_path, unit_name, write_target
from torsal.nodes.io.formats import meshfiles


class ImportMesh(Node):
    """A triangle mesh from an OBJ, STL, PLY or GLB file, e.g. a scan to analyse.

    The mesh comes in as one (a GLB scene's meshes joined where its transforms put
    them), vertices as in the file: not merged, not repaired. OBJ, STL and PLY have no
    units, so their numbers are read as FileUnits (empty: the model's Units); GLB is
    in metres by definition. Wire the mesh into MeshSurface to analyse it. A relative
    Path starts from the graph's folder.
    """

    type_id = "io.ImportMesh"
    nickname, aliases = "MeshIn", ("import obj", "import stl", "scan")
    inputs = (
        In("Path", TEXT, "P", "The .obj, .stl, .ply or .glb file to read."),
        In("FileUnits", TEXT, "Fu", "Units of the file's numbers (empty: the model's; GLB: always m).",
           default=""),
        In("Units", TEXT, "U", "The graph's model units (mm, cm, m, in, ft).", default="m"),
    )
    outputs = (Out("Mesh", MESH, "M", "The triangles, in model units."),)

    def solve(self, path: Any, file_units: Any, units: Any) -> Any:
        with file_errors():
            return meshfiles.read_mesh(read_path(self, path), unit_name(units), str(file_units or "") or None)


class ExportMesh(Node):
    """Write meshes to an OBJ, STL, PLY or GLB file (by Path's extension), e.g. for a renderer.

    Every mesh wired in is written as one mesh; surfaces wired in are meshed on a
    33 × 33 grid. Numbers are written in FileUnits (empty: the model's Units), except
    GLB, which is always in metres. OBJ keeps 15 digits, STL, PLY and GLB single
    precision. Nothing is written until Write is true and you have allowed the graph to
    write files; Path is relative to the graph's folder and must stay inside it. A file
    it replaces is kept as ``<name>.bak``.
    """

    type_id = "io.ExportMesh"
    nickname, aliases = "MeshOut", ("export obj", "export stl", "glb", "ply")
    inputs = (
        In("Path", TEXT, "P", "The .obj, .stl, .ply or .glb file to write, relative to the graph's folder.",
           default=""),
        In("Meshes", MESH, "M", "The meshes to write, in model units.", access=TREE),
        In("FileUnits", TEXT, "Fu", "Units to write in (empty: the model's; GLB: always m).", default=""),
        In("Units", TEXT, "U", "The graph's model units (mm, cm, m, in, ft).", default="m"),
        In("Write", BOOLEAN, "W", "Set to true to write the file; while false nothing is written.",
           default=False),
    )
    outputs = (Out("Path", TEXT, "P", "The file written, as an absolute path (empty while Write is false)."),)

    def solve(self, path: Any, meshes: DataTree, file_units: Any, units: Any, write: Any) -> Any:
        items = [m for m in meshes.all_items() if m is not None]
        with file_errors():
            model_units = unit_name(units)
            if not write:
                self.remark("Write is false: nothing written")
                return None
            if not items:  # e.g. an upstream node refused: the file already there stays as it is
                self.warn("There is nothing to write: Meshes is empty, so the file (and its .bak) is left "
                          "as it was")
                return None
            target = write_target(self, path)
            if not may_write(self, [target]):
                return None
            target = meshfiles.write_mesh(items, target, model_units, str(file_units or "") or None)
        return str(target)
