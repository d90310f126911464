"""display.Preview and Tag: display hints the viewport reads."""

from __future__ import annotations

import json

import pytest

from tests.support.node_helpers import out, run, texts, tree
from torsal.engine.types import decode_value, encode_value, summarize_value
from torsal.engine.values import Point
from torsal.nodes.display.hints import StyledGeometry, Tag, parse_colour
from torsal.nodes.display.preview import Preview
from torsal.nodes.display.preview import Tag as TagNode
from torsal.nodes.geometry import curves as kernel

LINE = kernel.Line([0, 0, 0], [1, 0, 0])


def test_preview_passes_geometry_on_and_styles_every_item():
    result = run(Preview(), Geometry=tree({(0,): [LINE, Point(1, 2, 3)]}), Colour="#ff8800", Width=3.0)
    assert out(result, "Geometry") == {(0,): [LINE, Point(1, 2, 3)]}
    assert out(result, "Styled") == {(0,): [
        StyledGeometry(LINE, "#ff8800", 3.0), StyledGeometry(Point(1, 2, 3), "#ff8800", 3.0),
    ]}


def test_preview_pairs_colours_with_items_and_reuses_the_last():
    geometry = tree({(0,): [Point(0, 0, 0), Point(1, 0, 0), Point(2, 0, 0)]})
    result = run(Preview(), Geometry=geometry, Colour=["red", "Steel Blue"])
    assert [s.colour for s in out(result, "Styled")[(0,)]] == ["#ff0000", "#4682b4", "#4682b4"]
    assert texts(result) == ["Geometry has 3 items, Colour has 2: Colour's last value is reused"]


@pytest.mark.parametrize("text, colour", [
    ("#FF8800", "#ff8800"), ("ff8800", "#ff8800"), ("#f80", "#ff8800"), ("orange", "#ffa500"),
    (" Grey ", "#808080"),
])
def test_colours_are_read_as_hex_or_names(text, colour):
    assert parse_colour(text) == colour


def test_styled_geometry_gives_its_colour_as_rgb():
    assert StyledGeometry(LINE, "#ff8000", 1.0).rgb == (1.0, 128 / 255, 0.0)


def test_preview_with_an_unknown_colour_warns():
    result = run(Preview(), Geometry=tree({(0,): [LINE]}), Colour="blurple")
    assert result.state == "warning"
    assert texts(result) == [
        "Colour 'blurple' is not a colour: write #rrggbb (like #ff8800) or a name such as red"
    ]


def test_preview_width_must_be_positive():
    result = run(Preview(), Geometry=tree({(0,): [LINE]}), Width=0.0)
    assert texts(result) == ["Width must be a positive number of pixels, not 0"]


def test_styled_geometry_is_summarised_for_json_results():
    summary = summarize_value(StyledGeometry(LINE, "#00ff00", 2.0))
    assert summary["type"] == "Styled" and summary["colour"] == "#00ff00"
    assert summary["geometry"]["length"] == 1.0
    json.dumps(summary)


def test_tag_puts_text_at_a_location():
    result = run(TagNode(), Text="panel 7", Location=Point(1, 2, 3))
    assert out(result) == {(0,): [Tag("panel 7", Point(1, 2, 3))]}


def test_tags_from_lists_pair_texts_and_points():
    result = run(TagNode(), Text=["a", "b"], Location=[Point(0, 0, 0), Point(1, 0, 0)])
    assert out(result) == {(0,): [Tag("a", Point(0, 0, 0)), Tag("b", Point(1, 0, 0))]}


def test_a_tag_can_be_written_to_a_file_and_read_back():
    tag = Tag("hello", Point(1, 2, 3))
    assert decode_value(json.loads(json.dumps(encode_value(tag)))) == tag
