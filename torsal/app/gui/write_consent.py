"""Asking once per document before its nodes write files (see :mod:`torsal.engine.writes`).

A graph someone sent you may hold an exporter with Write = true. Opening it must not
write anything until you say so: the first time its nodes want to write, the app lists
the files and asks. Allow writes them (and lets the document write from then on);
Don't write leaves them unwritten, with the nodes saying why. File ▸ "Allow File
Writes" changes the answer later.
"""

from __future__ import annotations

import os

from PySide6.QtWidgets import QMessageBox

from torsal.app.gui.hosts import ConsentWindow
from torsal.engine.writes import WriteRequest

#: At most this many files are listed in the question; the rest are counted.
LISTED = 12


def ask_to_write(window: ConsentWindow, requests: list[WriteRequest]) -> bool:
    """Ask whether the document may write the files ``requests`` name; True if allowed."""
    doc = window.doc
    folder = doc.writes.folder
    paths = [p for r in requests for p in r.paths]
    shown = [_relative(p, folder) for p in paths[:LISTED]]
    more = len(paths) - len(shown)
    titles = sorted({doc.graph.nodes[r.node_id].title for r in requests if r.node_id in doc.graph.nodes})
    box = QMessageBox(window)
    box.setIcon(QMessageBox.Icon.Question)
    box.setWindowTitle("Allow this graph to write files?")
    box.setText(
        f"{doc.title} wants to write {len(paths)} file{'s' if len(paths) != 1 else ''} "
        f"in its folder{f' ({folder})' if folder else ''}:"
    )
    listing = "\n".join(f"    {name}" for name in shown) + (f"\n    … and {more} more" if more > 0 else "")
    box.setInformativeText(
        f"{listing}\n\nAsked by: {', '.join(titles)}.\n\n"
        "Allow it only for a graph you trust. Files it replaces are kept as .bak."
    )
    allow = box.addButton("Allow", QMessageBox.ButtonRole.AcceptRole)
    refuse = box.addButton("Don't Write", QMessageBox.ButtonRole.RejectRole)
    box.setDefaultButton(refuse)
    box.setEscapeButton(refuse)
    box.exec()
    allowed = box.clickedButton() is allow
    doc.answer_writes(allowed)
    if allowed:
        window.report(f"Allowed {doc.title} to write files in {folder}")
    else:
        window.report(f"{doc.title} may not write files: nothing written (File ▸ Allow File Writes)",
                      "warning")
    sync_action(window)
    return allowed


def toggle_writes(window: ConsentWindow) -> None:
    """File ▸ Allow File Writes: change the document's answer."""
    doc = window.doc
    allow = not doc.writes.allowed
    if allow and doc.writes.folder is None:
        window.report("Save the graph first: its files are written next to it", "warning")
        sync_action(window)
        return
    doc.answer_writes(allow)
    window.report(f"{doc.title} {'may' if allow else 'may not'} write files in its folder")
    sync_action(window)


def sync_action(window: ConsentWindow) -> None:
    action = window.actions_by_name.get("allow_writes") if hasattr(window, "actions_by_name") else None
    if action is not None:
        action.setChecked(window.doc.writes.allowed)


def _relative(path: os.PathLike[str], folder: os.PathLike[str] | None) -> str:
    if folder is None:
        return os.fspath(path)
    try:
        return os.path.relpath(path, os.path.realpath(folder))
    except ValueError:
        return os.fspath(path)
