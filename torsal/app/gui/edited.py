"""The document as the undo commands see it (:class:`EditedDocument`, a Protocol).

The commands of :mod:`torsal.app.gui.commands` edit a graph through its document, and
the document builds commands (to commit a cluster edit): this protocol names only what
the commands use, so :mod:`torsal.app.gui.commands` never imports the document's module
(:class:`torsal.app.gui.document.Document` satisfies it).
"""

from __future__ import annotations

from contextlib import AbstractContextManager
from typing import TYPE_CHECKING, Protocol

if TYPE_CHECKING:
    from PySide6.QtCore import SignalInstance

    from torsal.engine.graph import Graph


class EditedDocument(Protocol):
    """A graph being edited: ``editing()`` pauses the solver around an edit (and asks
    for a solve afterwards when ``affects_solve``); ``groups_changed`` is emitted for the
    group edits the engine does not report."""

    graph: Graph
    groups_changed: SignalInstance

    def editing(self, affects_solve: bool = True) -> AbstractContextManager[Graph]: ...
