"""``torsal run --export ID.PORT=PATH``: write one output's data tree to a file.

The file type follows PATH's extension, and the writing is done by the same code as
the io nodes (:mod:`torsal.nodes.io`), so a file exported headless is the file the node writes:

- ``.json`` — the tree as in ``--json`` results; ``.csv`` — one row per item (path,
  index, then the item's fields), as ``io.ExportCSV`` writes it.
- ``.3dm`` — the geometry (curves, surfaces, meshes, points) on one layer named after
  the file, as ``io.Export3dm`` writes it; an ``io.ExportCutSheet`` Layout is written
  in mm with its sheets side by side (layers CUT, ENGRAVE, Sheets).
- ``.dxf`` / ``.svg`` — an ``io.ExportCutSheet`` Layout as laid out there; or closed
  flat curves or flat surfaces (their boundaries), laid out with the node's defaults
  (2500 × 1250 mm sheets, 10 mm gap, no kerf, IDs P-001 … in tree order). One file
  per sheet (``name-1.dxf`` … when there are several); with ``--preview`` also a PNG of
  each sheet beside its file (``name-1.png`` …).
- ``.obj`` / ``.stl`` / ``.ply`` / ``.glb`` — meshes and surfaces (meshed 33 × 33),
  as ``io.ExportMesh`` writes them.

``units`` is the graph's model units (its ``"units"`` field), used by the geometry
formats.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from torsal.engine.datatree import DataTree
from torsal.engine.types import describe

FORMATS = ".json, .csv, .3dm, .dxf, .svg, .obj, .stl, .ply or .glb"

#: The file types :func:`export_tree` writes, by suffix, as a save dialog lists them.
FILE_TYPES = {
    ".3dm": "Rhino 3D model",
    ".csv": "CSV table",
    ".json": "JSON data tree",
    ".dxf": "DXF cut sheets",
    ".svg": "SVG cut sheets",
    ".obj": "OBJ mesh",
    ".stl": "STL mesh",
    ".ply": "PLY mesh",
    ".glb": "glTF binary mesh",
}


class ExportError(ValueError):
    """An export that cannot be written (unknown format, wrong kind of data, a file error)."""


def export_tree(tree: DataTree, path: Path, units: str = "m", preview: bool = False) -> list[Path]:
    """Write ``tree`` to ``path`` in the format its extension names; returns the files written.
    ``preview``: cut sheets (.dxf/.svg) also get one PNG per sheet beside their files
    (:func:`~torsal.nodes.io.formats.sheetviews.write_previews`)."""
    from torsal.nodes.io.common import FileFailure

    suffix = path.suffix.lower()
    try:
        if suffix in (".json", ".csv"):
            from torsal.nodes.io.formats import tables

            return [(tables.write_json if suffix == ".json" else tables.write_csv)(tree, path)]
        if suffix == ".3dm":
            return [_export_3dm(tree, path, units)]
        if suffix in (".dxf", ".svg"):
            from torsal.nodes.io.formats import cutfiles

            layout = _layout(tree, suffix, units)
            files = cutfiles.write_cut_files(layout, path)
            if preview:
                from torsal.nodes.io.formats.sheetviews import write_previews

                files += write_previews(layout, files)
            return files
        if suffix in (".obj", ".stl", ".ply", ".glb"):
            from torsal.nodes.io.formats import meshfiles

            return [meshfiles.write_mesh(_meshes(tree, suffix), path, units)]
    except FileFailure as exc:
        raise ExportError(str(exc)) from None
    raise ExportError(f"cannot export to {suffix or 'a file without extension'} (use {FORMATS})")


def _items(tree: DataTree) -> list[Any]:
    return [item for item in tree.all_items() if item is not None]


def _kinds(items: list[Any]) -> str:
    return ", ".join(sorted({describe(item).split(" ")[0] for item in items})) or "nothing"


def _export_3dm(tree: DataTree, path: Path, units: str) -> Path:
    from torsal.nodes.io.common import FileFailure
    from torsal.nodes.io.formats import cutfiles, threedm

    items = _items(tree)
    layouts = [item for item in items if isinstance(item, cutfiles.CutLayout)]
    if layouts:
        entries = [entry for layout in layouts for entry in cutfiles.layout_entries(layout)]
        return threedm.write_3dm(path, entries, "mm", cutfiles.LAYOUT_COLOURS).path
    entries = threedm.tree_entries(tree, path.stem or "Torsal", "Object")
    try:
        return threedm.write_3dm(path, entries, units).path
    except FileFailure as exc:
        raise ExportError(f"cannot export {_kinds(items)} to .3dm: {exc}") from None


def _layout(tree: DataTree, suffix: str, units: str) -> Any:
    from torsal.nodes.geometry.curve_base import Curve
    from torsal.nodes.geometry.surface_base import Surface
    from torsal.nodes.io.formats import cutfiles

    items = _items(tree)
    layouts = [item for item in items if isinstance(item, cutfiles.CutLayout)]
    if len(layouts) == 1 and len(items) == 1:
        return layouts[0]
    if items and all(isinstance(item, Curve | Surface) for item in items):
        return cutfiles.lay_out(items, units=units)
    raise ExportError(
        f"cannot export {_kinds(items)} to {suffix}: a cut sheet needs closed flat curves, "
        "flat surfaces or one ExportCutSheet Layout"
    )


def _meshes(tree: DataTree, suffix: str) -> list[Any]:
    import trimesh

    from torsal.nodes.geometry.mesh_surface import MeshSurface
    from torsal.nodes.geometry.surface_base import Surface

    meshes = []
    for item in _items(tree):
        if isinstance(item, trimesh.Trimesh):
            meshes.append(item)
        elif isinstance(item, MeshSurface | Surface):
            meshes.append(item.to_mesh())
        else:
            raise ExportError(f"cannot export {_kinds([item])} to {suffix}: it needs meshes or surfaces")
    return meshes
