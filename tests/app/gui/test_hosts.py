"""The real window, document, scene, view and node item have every member the protocols
that stand for them name (torsal/app/gui/hosts.py, edited.py, canvas/hosts.py): a protocol
that asks for something its host lacks, or a host that loses a member a helper uses,
fails here rather than when a user opens that menu."""

from __future__ import annotations

import inspect
from typing import Any, Protocol

from torsal.app.gui import hosts
from torsal.app.gui.canvas import hosts as canvas_hosts
from torsal.app.gui.edited import EditedDocument


def members(protocol: type) -> set[str]:
    """The attributes and methods ``protocol`` (and the protocols it extends) declares."""
    names: set[str] = set()
    for cls in protocol.__mro__:
        if Protocol not in cls.__bases__:  # object, Protocol, Generic
            continue
        names |= set(inspect.get_annotations(cls))
        names |= {name for name, value in vars(cls).items() if callable(value) and not name.startswith("_")}
    return names


def missing(host: Any, protocol: type) -> list[str]:
    return sorted(name for name in members(protocol) if not hasattr(host, name))


def test_the_members_are_read_from_the_protocol_and_its_bases():
    assert {"doc", "report", "log"} <= members(hosts.ExportingWindow)
    assert {"doc", "report", "actions_by_name", "menuBar", "save_as"} <= members(hosts.MenuWindow)
    assert missing(object(), hosts.ExportingWindow) == ["doc", "log", "report"]


def test_the_main_window_is_every_helper_s_host(window):
    for protocol in (hosts.ExportingWindow, hosts.ConsentWindow, hosts.OptimiseOwner, hosts.MenuWindow):
        assert missing(window, protocol) == [], protocol.__name__


def test_the_document_scene_view_and_node_items_are_their_parts_hosts(window):
    node_id = window.editor.add_node("params.NumberSlider", (0.0, 0.0))
    item = window.scene.nodes[node_id]
    assert missing(window.doc, EditedDocument) == []
    assert missing(window.scene, canvas_hosts.NodeCanvas) == []
    assert missing(window.scene, canvas_hosts.ClusterCanvas) == []
    assert missing(window.view, canvas_hosts.MenuView) == []
    assert missing(item, canvas_hosts.WidgetHost) == []
    assert item.canvas() is window.scene
