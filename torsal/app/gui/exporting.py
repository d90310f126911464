"""Export… (one output's data tree to a file) and Bake (the previewed geometry to a .3dm).

Both are thin: the files are written by :func:`torsal.app.exports.export_tree` (what ``torsal
run --export`` uses) and :func:`torsal.app.bake.bake`, which write through the io nodes' code.
Whatever goes wrong is said in a warning dialog; the status bar names the files written.
"""

from __future__ import annotations

import re
from pathlib import Path
from typing import Any

from PySide6.QtCore import Qt
from PySide6.QtWidgets import QApplication, QFileDialog, QMessageBox

from torsal.app.bake import DEFAULT_PARENT, Baked, bake, bake_entries, is_geometry, nothing_to_bake
from torsal.app.exports import FILE_TYPES, ExportError, export_tree
from torsal.app.gui.hosts import ExportingWindow
from torsal.engine.datatree import DataTree

BAKE_FILTER = "Rhino 3D models (*.3dm)"


def file_filters() -> list[str]:
    """One save-dialog filter per format :func:`export_tree` writes, then All files."""
    return [f"{label} (*{suffix})" for suffix, label in FILE_TYPES.items()] + ["All files (*)"]


def file_name(text: str) -> str:
    """``text`` made safe as a file name on every system (no ``/ \\ : * ? " < > |``)."""
    name = re.sub(r'[\x00-\x1f\x7f/\\:*?"<>|]+', "_", text).strip(" .")
    return name or "export"


def default_suffix(tree: DataTree) -> str:
    """``.3dm`` for geometry, ``.dxf`` for a cut-sheet layout, ``.csv`` for other data."""
    from torsal.nodes.io.formats.cutfiles import CutLayout

    items = [item for item in tree.all_items() if item is not None]
    if any(isinstance(item, CutLayout) for item in items):
        return ".dxf"
    if any(is_geometry(item) for item in items):
        return ".3dm"
    return ".csv"


def _folder(window: ExportingWindow) -> Path | None:
    return window.doc.path.parent if window.doc.path is not None else None


def _not_ready(window: ExportingWindow) -> str:
    """Why the results cannot be used now ("" when they can)."""
    if not window.doc.solves.idle():
        return "Torsal is still solving: try again when the solve has finished."
    return ""


def _warn(window: ExportingWindow, title: str, text: str) -> None:
    window.log.add(text, "warning")
    QMessageBox.warning(window, title, text)


def export_output(window: ExportingWindow, node_id: str, port: str) -> list[Path]:
    """Ask for a file and write the output ``node_id``.``port`` to it; the files written."""
    doc = window.doc
    record = doc.graph.nodes.get(node_id)
    if record is None:
        return []
    what = f"{record.title} › {port}"
    result = doc.results.get(node_id)
    reason = _not_ready(window)
    if not reason and (result is None or port not in result.outputs):
        reason = f"{what} has not been solved yet: solve the graph first (Solve ▸ Solve Now)."
    tree = result.outputs.get(port) if result is not None else None
    if not reason and (tree is None or all(item is None for item in tree.all_items())):
        reason = f"{what} is empty: there is nothing to export."
        if result is not None and result.messages:
            reason += f"\n\n{record.title} says: {result.messages[0].text}"
    if reason or tree is None:
        _warn(window, "Cannot export", reason)
        return []
    suffix = default_suffix(tree)
    name = file_name(f"{record.label or node_id}-{port}") + suffix
    folder = _folder(window)
    start = str(folder / name) if folder is not None else name
    filters = file_filters()
    chosen_filter = next(f for f in filters if f.endswith(f"(*{suffix})"))
    chosen, selected = QFileDialog.getSaveFileName(
        window, f"Export {what}", start, ";;".join(filters), chosen_filter
    )
    if not chosen:
        return []
    path = Path(chosen)
    if not path.suffix:  # typed without one: the chosen filter's
        found = re.search(r"\(\*(\.\w+)\)", selected or "")
        path = path.with_suffix(found.group(1) if found else suffix)
    try:
        written = _busy(lambda: export_tree(tree, path, units=doc.graph.units))
    except (ExportError, OSError) as exc:
        _warn(window, "Cannot export", f"{what} was not exported to {path.name}:\n\n{exc}")
        return []
    except Exception as exc:  # a kernel object that cannot be converted: say so, never crash
        _warn(window, "Cannot export", f"{what} was not exported: {type(exc).__name__}: {exc}")
        return []
    window.report(f"Exported {what} to {', '.join(str(p) for p in written)}")
    return written


def bake_previewed(window: ExportingWindow, path: Path | None = None, node_ids: list[str] | None = None
                   ) -> Baked | None:
    """Write the geometry of every previewed node — or of ``node_ids`` only (a node's own
    Bake…, previewed or not, as Grasshopper's) — into one .3dm (asked for unless ``path``)."""
    from torsal.app.gui.viewport.preview import previewed  # pyvista: not before the first frame

    doc = window.doc
    reason = _not_ready(window)
    if node_ids is None:
        shown = previewed(doc.graph, doc.results) if not reason else set()
    else:
        shown = {n for n in node_ids if n in doc.results} if not reason else set()
    if not reason and not shown:
        reason = ("Nothing to bake: no node is previewed (or the graph has not been solved yet)."
                  if node_ids is None else "Nothing to bake: the node has no results yet.")
    if not reason and not bake_entries(doc.graph, doc.results, shown)[0]:
        reason = nothing_to_bake(len(shown))
    if reason:
        _warn(window, "Cannot bake", reason)
        return None
    stem = doc.path.stem if doc.path is not None else ""
    if path is None:
        only = f"-{file_name(sorted(shown)[0])}" if node_ids is not None and len(shown) == 1 else ""
        name = f"{file_name(stem or 'torsal')}{only}-bake.3dm"
        folder = _folder(window)
        chosen, _ = QFileDialog.getSaveFileName(
            window, "Bake previewed geometry to Rhino", str(folder / name) if folder else name, BAKE_FILTER
        )
        if not chosen:
            return None
        path = Path(chosen)
        if not path.suffix:
            path = path.with_suffix(".3dm")
    try:
        baked = _busy(lambda: bake(doc.graph, doc.results, shown, path, stem or DEFAULT_PARENT))
    except (ExportError, OSError) as exc:
        _warn(window, "Cannot bake", str(exc))
        return None
    except Exception as exc:  # a kernel object that cannot be converted: say so, never crash
        _warn(window, "Cannot bake", f"The bake failed: {type(exc).__name__}: {exc}")
        return None
    left_out = f"; {baked.skipped} values that are not geometry left out" if baked.skipped else ""
    window.report(
        f"Baked {baked.objects} objects from {len(baked.layers)} node{'s' if len(baked.layers) != 1 else ''} "
        "(one layer each) "
        f"to {baked.path}{left_out}"
    )
    return baked


def _busy(work: Any) -> Any:
    """Run ``work()`` under a wait cursor (a bake of many surfaces takes seconds)."""
    QApplication.setOverrideCursor(Qt.CursorShape.WaitCursor)
    try:
        return work()
    finally:
        QApplication.restoreOverrideCursor()
