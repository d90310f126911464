"""ExportCutSheet's Preview: the sheets drawn at the model's scale, beside the model
(torsal/nodes/io/sheet_preview.py)."""

from __future__ import annotations

import functools
from pathlib import Path

import numpy as np
import pytest

from tests.support.io_helpers import rectangle
from tests.support.node_helpers import out, run, tree
from torsal.engine.solver import OK
from torsal.nodes.common.preview import preview_of
from torsal.nodes.io.cutting import ExportCutSheet

EXAMPLES = Path(__file__).resolve().parents[3] / "torsal" / "resources" / "examples"
EXAMPLE = EXAMPLES / "kaohsiung-cut-sheets.graph"


@functools.cache
def example():  # type: ignore[no-untyped-def]
    from torsal.app.headless import run_file

    solved = run_file(EXAMPLE)
    strips = solved.solver.result("strip").outputs["Surface"].all_items()
    preview = solved.solver.result("cut").outputs["Preview"].all_items()
    if not strips or not preview:
        pytest.skip("the Kaohsiung example gives no strips here")
    return solved, strips, preview[0]


def test_the_example_previews_its_sheets_at_the_roofs_scale_beside_the_roof_not_inside_it():
    solved, strips, preview = example()
    assert solved.graph.nodes["cut"].preview  # shown when the example opens
    roof = np.vstack([s.bounding_box() for s in strips])
    low, high = roof.min(axis=0), roof.max(axis=0)
    sheets = preview.bounds()
    assert sheets[0, 0] > high[0]  # beside the roof along +X, clear of it
    # level with its front (a box around samples of the strips: within a thousandth of the size)
    assert sheets[0, 1] == pytest.approx(low[1], abs=1e-3 * np.ptp(roof))
    # 2500 x 1250 mm sheets of a 1:50 model (the graph's Model scale) drawn in metres at full size
    borders = preview.sheet_borders()
    assert len(borders) == preview.layout.sheets
    for ring in borders:
        assert np.ptp(ring, axis=0)[:2] == pytest.approx([2.5 * 50, 1.25 * 50], rel=1e-4)
    drawn = preview_of(preview)
    # every sheet border, every cut contour, and the engraved IDs
    assert len(drawn.polylines) >= len(borders) + 2 * len(preview.layout.parts)


def test_each_part_is_drawn_with_its_id_inside_its_contour():
    import shapely

    _, _, preview = example()
    for part, lines in zip(preview.layout.parts, preview.part_polylines(), strict=True):
        contour = shapely.Polygon(lines[0][:, :2])
        letters = lines[1:1 + len(part.label)]
        assert letters and all(contour.contains(shapely.Polygon(g[:, :2])) for g in letters), part.id


def test_without_strips_the_sheets_are_drawn_at_the_panels_scale_from_the_origin():
    result = run(ExportCutSheet(), Panels=tree({(0,): [rectangle(0, 0, 1, 0.5)]}))
    assert result.state == OK
    (preview,) = out(result, "Preview")[(0,)]
    assert preview.scale == pytest.approx(0.001) and preview.origin == (0.0, 0.0, 0.0)
    assert preview.bounds()[:, :2].ravel().tolist() == pytest.approx([0.0, 0.0, 2.5, 1.25])


def test_a_point_picked_on_a_part_names_that_part_and_its_strip_on_the_roof():
    """A point inside each part's drawn contour (its representative point, shapely) names
    that part, and the part's strip is the example's strip of the same position (the cut
    node's Surfaces and Strips come in the same order); a point on the bare sheet names none."""
    import shapely

    _, strips, preview = example()
    assert len(preview.strips) == len(preview.layout.parts) == len(strips)
    for index, lines in enumerate(preview.part_polylines()):
        inside = shapely.Polygon(lines[0][:, :2]).representative_point()
        assert preview.part_at((inside.x, inside.y, lines[0][0, 2])) == index
        assert preview.strip_of(index) is strips[index]
    corner = preview.sheet_borders()[0][0]  # a sheet's corner: inside the margin, no part
    assert preview.part_at(corner + np.array([1e-3, 1e-3, 0.0])) is None
