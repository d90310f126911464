"""The search popup as a Grasshopper user types into it: numbers make sliders, aliases find
nodes by the designer's word, names that start with the text rank first, and the popup
stays inside the window."""

from __future__ import annotations

from PySide6.QtCore import QPoint, QPointF, Qt
from PySide6.QtTest import QTest

from tests.support.fixtures_gui import place_by_search
from torsal.app.gui.fuzzy import build_entries, search


def typed(qtbot, window, query: str) -> list[str]:
    """Open the search by a double-click on empty canvas, type ``query``: the listed rows."""
    QTest.mouseDClick(window.view.viewport(), Qt.MouseButton.LeftButton, Qt.KeyboardModifier.NoModifier,
                      QPoint(200, 200))
    qtbot.waitUntil(window.popup.isVisible, timeout=3000)
    QTest.keyClicks(window.popup.query, query)
    rows = [window.popup.list.item(i).text() for i in range(window.popup.list.count())]
    QTest.keyClick(window.popup.query, Qt.Key.Key_Escape)
    return rows


def test_a_typed_number_and_enter_places_a_slider_set_to_it(qtbot, window):
    node_id = place_by_search(qtbot, window, "6", QPointF(100, 100))
    record = window.doc.graph.nodes[node_id]
    assert record.type_id == "params.NumberSlider"
    assert record.node.settings["value"] == 6.0
    assert (record.node.settings["min"], record.node.settings["max"]) == (0.0, 10.0)


def test_a_typed_range_places_a_slider_with_that_range(qtbot, window):
    node_id = place_by_search(qtbot, window, "-1<0.25<4", QPointF(100, 100))
    settings = window.doc.graph.nodes[node_id].node.settings
    assert (settings["min"], settings["value"], settings["max"], settings["decimals"]) == (-1.0, 0.25, 4.0, 2)


def test_isomap_lists_iso_mapping_first(qtbot, window):
    assert typed(qtbot, window, "isomap")[0].startswith("Iso Mapping")


def test_unroll_flatten_and_development_find_iso_mapping(registry):
    entries = build_entries(list(registry))
    for word in ("unroll", "development"):
        assert search(entries, word)[0].name == "IsoMapping", word
    flatten = [e.name for e in search(entries, "flatten")]
    assert flatten[:2] == ["Flatten", "IsoMapping"]  # the list node keeps its own name first


def test_nest_finds_export_cut_sheet_and_panel_the_panel_node_then_patching(registry):
    entries = build_entries(list(registry))
    assert search(entries, "nest")[0].name == "ExportCutSheet"
    assert [e.name for e in search(entries, "panel")][:2] == ["Panel", "SurfacePatching"]


def test_names_starting_with_the_text_rank_before_names_containing_it(registry):
    names = [e.name for e in search(build_entries(list(registry)), "curve")]
    starting = [i for i, n in enumerate(names) if n.lower().startswith("curve")]
    containing = [i for i, n in enumerate(names) if "curve" in n.lower()[1:] and i not in starting]
    assert starting and containing and max(starting) < min(containing)


def test_the_popup_opened_near_the_bottom_right_corner_stays_inside_the_window(qtbot, window):
    corner = window.mapToGlobal(QPoint(window.width() - 5, window.height() - 5))
    window.popup.open_at(corner)
    qtbot.waitUntil(window.popup.isVisible, timeout=3000)
    inside = window.geometry()
    popup = window.popup.frameGeometry()
    window.popup.hide()
    assert inside.contains(popup), (inside, popup)


#: What a Grasshopper user types, and the node it must list first.
GRASSHOPPER_WORDS = {
    "Pt": "Point",
    "Construct Point": "Point",
    "Divide Curve": "Divide Curve",
    "XY Plane": "XY Plane",
    "Plane": "XY Plane",
    "Construct Plane": "Construct Plane",
    "Plane 3Pt": "Plane Three Points",
    "Deconstruct": "Deconstruct Point",
    "Deconstruct Vector": "Deconstruct Vector",
    "Loft": "Loft",
    "Unroll": "Iso Mapping",
    "Construct Domain": "Domain",
    "Remap Numbers": "Remap",
    "Bounding Box": "Bounding Box",
    "Evaluate Surface": "Evaluate Surface",
    "Perp Frames": "Perp Frames",
    "Extrude": "Cylindrical Surface",
    "Number Slider": "Number Slider",
    "Join Curves": "Join Curves",
    "Explode": "Explode",
    "Shatter": "Shatter",
    "Split Curve": "Shatter",
    "Divide Surface": "Divide Surface",
    "Contour": "Contour",
    "Brep | Plane": "Section",
    "Sweep1": "Sweep 1",
    "Simplify Tree": "Simplify Tree",
    "Tree Branch": "Tree Branch",
    "Path Mapper": "Path Mapper",
}


def test_typing_grasshoppers_names_lists_the_node_first(qtbot, window):
    for query, title in GRASSHOPPER_WORDS.items():
        rows = typed(qtbot, window, query)
        assert rows and rows[0].split("  (")[0] == title, (query, rows[:3])


def test_every_node_declares_a_nickname_and_nicknames_are_unique_within_a_palette(registry):
    seen: dict[tuple[str, str], str] = {}
    for cls in registry:
        if cls.type_id.partition(".")[0] not in TORSAL_PALETTES:
            continue
        assert cls.nickname, cls.type_id
        key = (cls.type_id.partition(".")[0], cls.nickname.lower())
        assert key not in seen, (cls.type_id, seen.get(key))
        seen[key] = cls.type_id


TORSAL_PALETTES = {
    "params", "maths", "lists", "curves", "surfaces", "transform", "analysis", "developable",
    "patching", "display", "io",
}
