"""Rhino .3dm files: Import3dm and Export3dm (through rhino3dm: :mod:`torsal.nodes.io.formats.threedm`)."""

from __future__ import annotations

from typing import Any

from torsal.engine.datatree import DataTree
from torsal.engine.node import LIST, TREE, In, Node, Out
from torsal.engine.types import BOOLEAN, INTEGER, TEXT
from torsal.nodes.common.values import CURVE, LINE, MESH, SURFACE
from torsal.nodes.io.common import file_errors, may_write, read_path, unit_name, write_target
from torsal.nodes.io.formats import threedm

#: Layer names under the parent layer, one per input of Export3dm.
LAYERS = {"Curves": "Curves", "Surfaces": "Surfaces", "Rulings": "Rulings", "Panels": "Panels",
          "Meshes": "Meshes"}

UNITS_HELP = "The graph's model units (mm, cm, m, in, ft; the graph file's \"units\")."


class Import3dm(Node):
    """Curves, surfaces and meshes from a Rhino .3dm file, with their layers and names.

    Lines and polylines come in as such, every other curve as a NURBS curve; surfaces,
    extrusions and the faces of breps (each face on its own) as NURBS surfaces. A face
    trimmed in Rhino keeps its trim loops (a trimmed surface: Rationalise works inside
    them); an extrusion's caps are left out. Lengths are converted from the file's units
    to Units, so a file in millimetres comes into a metre graph at 1/1000. Layers picks
    layers by full path (``Facade::Panels``) or name, ``*`` as a wildcard; a layer brings
    its sublayers. The file is parsed in a separate process with a memory and time
    limit, so a damaged file that crashes the reader puts this node in error ("could not
    read FILE: the reader crashed") and nothing else. Files over 512 MB are refused.
    A relative Path starts from the graph's folder (also with ``torsal run --out``).
    """

    type_id = "io.Import3dm"
    nickname, aliases = "3dmIn", ("Import 3DM", "read rhino", "Geometry Pipeline")
    inputs = (
        In("Path", TEXT, "P", "The .3dm file to read."),
        In("Layers", TEXT, "L", "Only these layers (empty: every layer).", access=LIST, optional=True),
        In("Units", TEXT, "U", UNITS_HELP + " Lengths are converted to them.", default="m"),
    )
    outputs = (
        Out("Curves", CURVE, "C", "Every curve, in file order.", access=LIST),
        Out("CurveLayers", TEXT, "Cl", "Each curve's layer, as a full path (a::b).", access=LIST),
        Out("CurveNames", TEXT, "Cn", "Each curve's object name (empty when it has none).", access=LIST),
        Out("Surfaces", SURFACE, "S", "Every surface as a NURBS surface, in file order.", access=LIST),
        Out("SurfaceLayers", TEXT, "Sl", "Each surface's layer.", access=LIST),
        Out("SurfaceNames", TEXT, "Sn", "Each surface's object name.", access=LIST),
        Out("Meshes", MESH, "M", "Every mesh, as triangles.", access=LIST),
        Out("MeshLayers", TEXT, "Ml", "Each mesh's layer.", access=LIST),
        Out("MeshNames", TEXT, "Mn", "Each mesh's object name.", access=LIST),
        Out("FileUnits", TEXT, "Fu", "The file's units (mm, m …), or none for a unitless file."),
    )

    def solve(self, path: Any, layers: list[Any], units: Any) -> tuple[Any, ...]:
        with file_errors():
            model_units = unit_name(units)
            found = threedm.read_3dm(read_path(self, path), model_units, [str(x) for x in layers if x])
        if found.units == "none":
            self.remark("The file has no units: its numbers are taken as model units")
        elif found.scale != 1.0:
            self.remark(f"Converted from {found.units} to {model_units} (× {found.scale:g})")
        if found.trims:
            self.remark(f"{found.trims} brep faces came in trimmed: each keeps its trim loops")
        if found.trimmed:
            self.remark(
                f"{found.trimmed} brep faces or capped extrusions came in as their untrimmed surfaces"
            )
        if found.skipped:
            kinds = ", ".join(f"{n} {kind}" for kind, n in sorted(found.skipped.items()))
            self.remark(f"Not imported (not curves, surfaces or meshes): {kinds}")
        if not (found.curves or found.surfaces or found.meshes):
            self.warn("No curves, surfaces or meshes found" + (" on those layers" if layers else ""))

        def columns(rows: list[tuple[Any, str, str]]) -> tuple[list[Any], list[str], list[str]]:
            return [r[0] for r in rows], [r[1] for r in rows], [r[2] for r in rows]

        return (*columns(found.curves), *columns(found.surfaces), *columns(found.meshes), found.units)


class Export3dm(Node):
    """Write geometry to a Rhino .3dm file (Rhino 7 format: Rhino 7 and 8 open it).

    Each input goes on its own layer under Layer (Torsal::Curves, ::Surfaces,
    ::Rulings, ::Panels, ::Meshes). Curves become NURBS curves and surfaces NURBS
    surfaces with Torsal's own parameterisation, exactly where the geometry is a
    B-spline already (a ruled surface is degree 1 across its rulings) and otherwise
    interpolated to within 1e-9 of its size (the node says how close); a trimmed surface
    goes out as its untrimmed surface (rhino3dm cannot write trimmed freeform faces). A
    developable strip goes face by face along its rulings: ruled faces with rails fitted to
    1e-6 of its size, fans as planar faces, the strip's faces in one Rhino group, each
    named and tagged with its rulings (TorsalRulings, TorsalFace); see docs/rhino.md. A
    curve of no length is left out. Every object
    is named (Curve 1 …, panels by their ID) and keeps its tree path in the user
    strings TorsalPath and TorsalIndex; panels also carry PanelID. The file's units
    are Units. Nothing is written until Write is true and you have allowed the
    graph to write files; Path is relative to the graph's folder and must stay inside
    it. A file it replaces is kept as ``<name>.bak``. With nothing to write (every input
    empty, as after an upstream node's error) it warns and leaves the file alone.
    """

    type_id = "io.Export3dm"
    nickname, aliases = "3dm", ("Bake", "export rhino", "rhino")
    inputs = (
        In("Path", TEXT, "P", "The .3dm file to write, relative to the graph's folder.", default=""),
        In("Curves", CURVE, "C", "Curves, on the layer Curves.", access=TREE, optional=True),
        In("Surfaces", SURFACE, "S", "Surfaces, on the layer Surfaces.", access=TREE, optional=True),
        In("Rulings", LINE, "R", "Ruling lines, on the layer Rulings.", access=TREE, optional=True),
        In("Panels", CURVE, "Pn", "Flat panel outlines, on the layer Panels.", access=TREE, optional=True),
        In("PanelIDs", TEXT, "ID", "One ID per panel, in order: its name and user string PanelID.",
           access=TREE, optional=True),
        In("Meshes", MESH, "M", "Meshes, on the layer Meshes.", access=TREE, optional=True),
        In("Layer", TEXT, "L", "The parent layer of the layers above.", default="Torsal"),
        In("Units", TEXT, "U", UNITS_HELP + " The file is written in them.", default="m"),
        In("Write", BOOLEAN, "W", "Set to true to write the file; while false nothing is written.",
           default=False),
    )
    outputs = (
        Out("Path", TEXT, "P", "The file written, as an absolute path (empty while Write is false)."),
        Out("Objects", INTEGER, "N", "How many objects there are to write."),
    )

    def solve(
        self,
        path: Any,
        curves: DataTree,
        surfaces: DataTree,
        rulings: DataTree,
        panels: DataTree,
        ids: DataTree,
        meshes: DataTree,
        layer: Any,
        units: Any,
        write: Any,
    ) -> tuple[Any, int]:
        parent = (str(layer).strip() if layer else "") or "Torsal"
        names = ids.all_items() if not ids.is_empty() else None
        if names is not None and len(names) != panels.item_count:
            self.warn(f"There are {len(names)} PanelIDs for {panels.item_count} panels: unnamed panels "
                      "are called Panel n")
        entries = [
            *threedm.tree_entries(curves, f"{parent}::{LAYERS['Curves']}", "Curve"),
            *threedm.tree_entries(surfaces, f"{parent}::{LAYERS['Surfaces']}", "Surface"),
            *threedm.tree_entries(rulings, f"{parent}::{LAYERS['Rulings']}", "Ruling"),
            *threedm.tree_entries(panels, f"{parent}::{LAYERS['Panels']}", "Panel", names, "PanelID"),
            *threedm.tree_entries(meshes, f"{parent}::{LAYERS['Meshes']}", "Mesh"),
        ]
        with file_errors():
            model_units = unit_name(units)
            if not write:
                self.remark("Write is false: nothing written")
                return None, len(entries)
            if not entries:  # e.g. an upstream node refused: the file already there stays as it is
                self.warn("There is nothing to write: every geometry input is empty, so the file (and its "
                          ".bak) is left as it was")
                return None, 0
            target = write_target(self, path)
            if not may_write(self, [target]):
                return None, len(entries)
            written = threedm.write_3dm(target, entries, model_units)
        if written.deviation > 0:
            self.remark(
                f"Some geometry was interpolated as NURBS: within {written.deviation:.2g} {model_units}"
            )
        if written.degenerate:
            self.remark(f"{written.degenerate} curves of no length (points) were left out")
        return str(written.path), written.objects
