"""The records a graph is made of: wires, inputs' states, node records and groups.

They live apart from :class:`~torsal.engine.graph.Graph` so that code which builds or copies
graph parts (the cluster edits) needs no import of the graph itself; ``torsal.engine.graph``
exports them under their usual names.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from torsal.engine.node import Node
from torsal.engine.widgets import Widget


class GraphError(ValueError):
    """An edit that would make the graph invalid (the message says why)."""


@dataclass(frozen=True)
class Wire:
    """A connection from an output port to an input port (``raw``: its object in the file)."""

    source: str
    source_port: str
    target: str
    target_port: str
    raw: dict[str, Any] = field(default_factory=dict, compare=False, hash=False, repr=False)

    def __post_init__(self) -> None:  # a wire is looked up in several indexes: hash it once
        ends = (self.source, self.source_port, self.target, self.target_port)
        object.__setattr__(self, "_hash", hash(ends))

    def __hash__(self) -> int:
        return self._hash

    def __str__(self) -> str:
        return f"{self.source}.{self.source_port} → {self.target}.{self.target_port}"


@dataclass
class InputState:
    """What an input keeps besides its wires: a persistent value and modifiers.

    ``value`` is JSON data (see :func:`torsal.engine.types.encode_value`) or ``None`` when unset.
    """

    value: Any = None
    has_value: bool = False
    modifiers: list[str] = field(default_factory=list)
    raw: dict[str, Any] = field(default_factory=dict)


@dataclass
class NodeRecord:
    """One node in a graph: its behaviour object plus what the document keeps about it.

    ``raw`` is the node's object as read from a file (empty for new nodes): fields the
    app does not know are written back from it unchanged.
    """

    id: str
    node: Node
    type_id: str
    label: str = ""
    position: tuple[float, float] = (0.0, 0.0)
    inputs: dict[str, InputState] = field(default_factory=dict)
    preview: bool = True
    enabled: bool = True
    raw: dict[str, Any] = field(default_factory=dict)

    @property
    def title(self) -> str:
        """The label, or the node type's name as words; shortened for messages and the canvas."""
        text = self.label or self.node.display_name()
        return text if len(text) <= 60 else text[:59] + "…"

    def input_state(self, port: str) -> InputState:
        return self.inputs.setdefault(port, InputState())

    @property
    def shows_geometry(self) -> bool:
        """Whether a viewport, a variant's picture or Bake draws this node's geometry: its
        preview is on, it is enabled, and it is not a panel (a panel shows text). Which of
        its outputs are drawn is the node's :meth:`~torsal.engine.node.Node.previewed_outputs`."""
        return self.preview and self.enabled and self.node.widget is not Widget.PANEL


@dataclass
class Group:
    """A coloured, titled box around some nodes (layout only; it never affects solving)."""

    id: str
    title: str = ""
    colour: str = "#d8e4f0"
    nodes: list[str] = field(default_factory=list)
    raw: dict[str, Any] = field(default_factory=dict)
