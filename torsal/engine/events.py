"""Graph events: one small frozen dataclass per kind of edit.

A :class:`~torsal.engine.graph.Graph` calls its listeners (a GUI, an undo stack) with one event
per edit. Listeners tell the kinds apart by class (``isinstance(event, WireAdded)`` or a
``match`` statement); each event carries exactly the fields its kind needs, and
``node_id`` names the node it concerns (the wire's target for wire events, None for
groups). ``kind`` is a short name for logs and messages.
"""

from __future__ import annotations

from dataclasses import dataclass, fields
from typing import TYPE_CHECKING, Any, ClassVar

if TYPE_CHECKING:
    from torsal.engine.graph_records import Group, NodeRecord, Wire


@dataclass(frozen=True)
class GraphEvent:
    """Base of every graph event."""

    kind: ClassVar[str] = "changed"

    @property
    def data(self) -> dict[str, Any]:
        """The fields besides ``node_id`` as a dict: for listeners written when events were
        ``(kind, data)`` pairs. New code reads the fields."""
        return {f.name: getattr(self, f.name) for f in fields(self) if f.name != "node_id"}


@dataclass(frozen=True)
class NodeEvent(GraphEvent):
    """An edit of one node."""

    node_id: str


@dataclass(frozen=True)
class NodeAdded(NodeEvent):
    kind: ClassVar[str] = "node_added"


@dataclass(frozen=True)
class NodeRemoved(NodeEvent):
    kind: ClassVar[str] = "node_removed"
    record: NodeRecord


@dataclass(frozen=True)
class WireEvent(GraphEvent):
    """A wire added or removed; ``node_id`` is the node it runs into."""

    wire: Wire

    @property
    def node_id(self) -> str | None:
        return self.wire.target


@dataclass(frozen=True)
class WireAdded(WireEvent):
    kind: ClassVar[str] = "wire_added"


@dataclass(frozen=True)
class WireRemoved(WireEvent):
    kind: ClassVar[str] = "wire_removed"


@dataclass(frozen=True)
class SettingChanged(NodeEvent):
    kind: ClassVar[str] = "setting_changed"
    name: str
    old: Any
    new: Any


@dataclass(frozen=True)
class InputChanged(NodeEvent):
    """An input's persistent value set or cleared: ``old`` and ``new`` are ``(present, value)``."""

    kind: ClassVar[str] = "input_changed"
    port: str
    old: tuple[bool, Any]
    new: tuple[bool, Any]


@dataclass(frozen=True)
class ModifiersChanged(NodeEvent):
    kind: ClassVar[str] = "modifiers_changed"
    port: str
    old: list[str]
    new: list[str]


@dataclass(frozen=True)
class EnabledChanged(NodeEvent):
    kind: ClassVar[str] = "enabled_changed"
    enabled: bool


@dataclass(frozen=True)
class PreviewChanged(NodeEvent):
    kind: ClassVar[str] = "preview_changed"
    preview: bool


@dataclass(frozen=True)
class NodeMoved(NodeEvent):
    kind: ClassVar[str] = "node_moved"
    old: tuple[float, float]
    new: tuple[float, float]


@dataclass(frozen=True)
class LabelChanged(NodeEvent):
    kind: ClassVar[str] = "label_changed"
    old: str
    new: str


@dataclass(frozen=True)
class GroupEvent(GraphEvent):
    group: Group

    @property
    def node_id(self) -> str | None:
        return None


@dataclass(frozen=True)
class GroupAdded(GroupEvent):
    kind: ClassVar[str] = "group_added"


@dataclass(frozen=True)
class GroupRemoved(GroupEvent):
    kind: ClassVar[str] = "group_removed"


#: Edits that change what a node draws on the canvas (its ports, labels, widget).
NODE_REDRAWN = (SettingChanged, InputChanged, ModifiersChanged, EnabledChanged, PreviewChanged, LabelChanged)
#: Edits that change what the viewport shows.
PREVIEW_CHANGED = (PreviewChanged, EnabledChanged, NodeRemoved)
