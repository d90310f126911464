"""PaperStrip's Placement: where its Development lies (1 Origin, the default, so files made
before the input existed keep their Development; 0 beside the strip; 2 on a Plane).

Expected values are closed forms: a flat strip (Curvature 0, parallel rulings) Length 5 by
Width 2 in 4 segments is the rectangle [0, 5] × [0, 2] in the XY plane with rulings at
x = 1.25·i; beside a model the development moves past the model's greatest x by a fifth
of the model's longest side, level with its least y, at its lowest z.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from tests.support.node_helpers import out, run, texts
from torsal.engine.values import Plane, Point, Vector
from torsal.nodes.developable.paper_strip import PaperStrip

FLAT = {"Length": 5.0, "Width": 2.0, "IsoAngle": [math.pi / 2], "Curvature": [0.0], "Segments": 4}
BENT = {"Length": 6.0, "Width": 0.6, "IsoAngle": [1.5], "Curvature": [0.1, 0.25, -0.1, 0.3], "Segments": 12}


def development(**inputs) -> np.ndarray:
    """The Development's rulings, ``(n, 2, 3)``."""
    ((surface,),) = out(run(PaperStrip(), **inputs), "Development").values()
    return surface.ruling_lines


def flat_rectangle(shift=(0.0, 0.0, 0.0)) -> np.ndarray:
    x = 1.25 * np.arange(5)
    starts = np.column_stack([x, np.zeros(5), np.zeros(5)])
    ends = np.column_stack([x, np.full(5, 2.0), np.zeros(5)])
    return np.stack([starts, ends], axis=1) + np.asarray(shift)


def test_without_placement_the_development_lies_at_the_origin_as_before():
    assert np.array_equal(development(**FLAT), flat_rectangle())


def test_placement_1_is_the_origin():
    assert np.array_equal(development(**FLAT, Placement=1), flat_rectangle())


def test_placement_0_lays_a_flat_strip_a_fifth_of_its_length_past_it():
    # the flat strip is its own model: x in [0, 5], so the development starts at 5 + 5/5
    np.testing.assert_allclose(development(**FLAT, Placement=0), flat_rectangle((6.0, 0.0, 0.0)), atol=1e-15)


def test_placement_0_lays_a_bent_strip_beside_it_at_its_lowest_point():
    result = run(PaperStrip(), **BENT, Placement=0)
    (rulings,) = out(result, "Rulings").values()
    model = np.array([[line.start, line.end] for line in rulings]).reshape(-1, 3)
    low, high = model.min(axis=0), model.max(axis=0)
    ((surface,),) = out(result, "Development").values()
    flat = surface.ruling_lines.reshape(-1, 3)
    size = (high - low).max()
    assert flat[:, 0].min() == pytest.approx(high[0] + 0.2 * size, abs=1e-12 * size)
    assert flat[:, 1].min() == pytest.approx(low[1], abs=1e-12 * size)
    np.testing.assert_allclose(flat[:, 2], low[2], atol=1e-12 * size)


def test_placement_is_a_rigid_motion_of_the_development():
    here, beside = development(**BENT).reshape(-1, 3), development(**BENT, Placement=0).reshape(-1, 3)

    def distances(points: np.ndarray) -> np.ndarray:
        return np.linalg.norm(points[:, None] - points[None], axis=-1)

    size = np.ptp(here, axis=0).max()
    np.testing.assert_allclose(distances(beside), distances(here), atol=4e-15 * size)


def test_placement_2_lays_the_development_on_the_plane():
    plane = Plane(Point(1, 2, 3), Vector(0, 1, 0), Vector(0, 0, 1))  # the YZ plane through (1, 2, 3)
    rect = flat_rectangle()
    expected = np.stack([np.full(rect.shape[:2], 1.0), 2.0 + rect[..., 0], 3.0 + rect[..., 1]], axis=-1)
    np.testing.assert_allclose(development(**FLAT, Placement=2, Plane=plane), expected, atol=1e-15)


def test_a_placement_that_is_no_choice_is_refused_naming_the_choices():
    result = run(PaperStrip(), **FLAT, Placement=3)
    assert result.state == "warning"
    assert texts(result) == ["Placement is 3, not one of its choices: 0 Beside model, 1 Origin, 2 On plane"]
