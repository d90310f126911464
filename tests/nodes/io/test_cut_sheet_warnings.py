"""A value ExportCutSheet refuses is a warning naming the input, its outputs empty and
nothing written (the rule of nodes/common/checks.py); files that cannot be written and
panels the pre-export check refuses stay errors, as the node's description says
(tests/nodes/io/test_cut_sheets.py)."""

from __future__ import annotations

import pytest

from tests.nodes.io.test_seams import band
from tests.support.io_helpers import rectangle
from tests.support.node_helpers import allowed, out, run, texts, tree
from torsal.engine.solver import WARNING
from torsal.nodes.io.cutting import ExportCutSheet

PANELS = [rectangle(0, 0, 1, 0.5), rectangle(2, 0, 1, 0.5)]


def _refused(tmp_path, **inputs):
    result = run(ExportCutSheet(), writes=allowed(tmp_path), Path="cut.dxf", Write=True, **inputs)
    assert result.state == WARNING, texts(result)
    assert all(item is None for items in out(result, "Layout").values() for item in items)
    assert not list(tmp_path.iterdir())
    return texts(result)


@pytest.mark.parametrize(
    ("inputs", "needle"),
    [
        ({"TickSpacing": -5.0}, "TickSpacing must be 0 or a positive length in mm, not -5"),
        ({"Seed": 1.5}, "Seed must be a whole number from 0, not 1.5"),
        ({"Nesting": "Best"}, "Nesting is 'Best': use TrueShape or Shelf"),
        ({"SheetWidth": -1.0}, "SheetWidth must be a positive length in mm, not -1"),
        ({"Gap": 700.0}, "A gap of 700 mm on each side leaves no room on a 2500 × 1250 mm sheet"),
        ({"Kerf": -1.0}, "Kerf must be zero or a positive width in mm, not -1"),
        ({"TextHeight": -2.0}, "TextHeight must be zero or a positive height in mm, not -2"),
        ({"Nesting": "TrueShape", "TimeBudget": 0.0}, "TimeBudget must be between 1 and 3600 s, not 0"),
        ({"Units": "parsec"}, "Units 'parsec' is not a length unit"),
    ],
)
def test_a_refused_setting_is_a_warning_naming_it(tmp_path, inputs, needle):
    assert any(needle in text for text in _refused(tmp_path, Panels=tree({(0,): PANELS}), **inputs))


def test_a_null_panel_id_is_a_warning_naming_its_position(tmp_path):
    ids = tree({(0,): ["A", None]})
    (text,) = _refused(tmp_path, Panels=tree({(0,): PANELS}), PanelIDs=ids)
    assert text.startswith("PanelIDs has an empty (null) item at position 2")


def test_strips_that_do_not_match_the_surfaces_in_number_are_a_warning(tmp_path):
    strips = [band(0.0, 0.3), band(0.3, 0.5)]
    (text,) = _refused(tmp_path, Surfaces=tree({(0,): strips}), Strips=tree({(0,): strips[:1]}))
    assert text.startswith("Strips has 1 items for 2 Surfaces")
