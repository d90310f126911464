"""The panel: a note on the canvas that also shows and passes on whatever is wired into it."""

from __future__ import annotations

from torsal.engine.datatree import DataTree
from torsal.engine.node import TREE, In, Node, NodeError, Out, Setting
from torsal.engine.types import GENERIC
from torsal.engine.widgets import Widget


class Panel(Node):
    """Show data, or type text to use as data.

    Wire anything into the panel to see it, branch by branch; it passes the same
    tree on unchanged. With nothing wired, each line of the panel's text becomes
    one Text item, so a panel can feed a list of names or numbers written by hand::

        3.5
        4.0
        4.5

    gives the three Texts '3.5', '4.0', '4.5' (a Number input reads them as numbers).
    """

    type_id = "params.Panel"
    nickname, aliases = "Panel", ("text", "note", "show", "display value")
    widget = Widget.PANEL
    inputs = (
        In("Input", GENERIC, "I", "Data to show and pass on; leave unwired to use the text.",
           access=TREE, optional=True),
    )
    outputs = (
        Out("Output", GENERIC, "O", "The wired data, or the text's lines when nothing is wired.",
            access=TREE),
    )
    settings_spec = (Setting("text", str, "", "The panel's text, one item per line."),)

    def solve(self, data: DataTree) -> DataTree:
        if not data.is_empty():
            return data
        text = self.settings.get("text")
        if text is None:
            text = ""
        if not isinstance(text, str):
            raise NodeError(f"The panel's text must be text, not {text!r}")
        lines = text.splitlines()
        return DataTree({(0,): lines}) if lines else DataTree()
