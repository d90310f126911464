"""A chart node's PNG: 640 × 400 as before, carrying the recipe the app draws again at its panel's size."""

from __future__ import annotations

import json

import numpy as np
from PIL import Image

from tests.support.node_helpers import run
from torsal.nodes.common.charts import RECIPE_KEY, read_recipe, render
from torsal.nodes.display.plot import Plot


def test_a_plot_writes_a_640_by_400_png_whose_text_holds_its_numbers_and_title():
    result = run(Plot(), Values=[0.5, 2.0, float("nan"), 1.0], Title="Warp")
    (path,) = result.output("Image").all_items()
    with Image.open(path) as image:
        assert image.size == (640, 400)
        recipe = json.loads(image.text[RECIPE_KEY])
    assert recipe["kind"] == "line" and recipe["title"] == "Warp"
    assert np.array_equal(recipe["y"], [0.5, 2.0, np.nan, 1.0], equal_nan=True)
    assert read_recipe(image.text[RECIPE_KEY]) is not None


def test_a_recipe_drawn_at_another_size_is_laid_out_for_it():
    recipe = {"kind": "line", "y": [1.0, 3.0, 2.0], "title": "t"}
    small, wide = render(recipe, 300, 200), render(recipe, 900, 300)
    assert (small.bbox.width, small.bbox.height) == (300, 200)
    assert (wide.bbox.width, wide.bbox.height) == (900, 300)
    # the axes fill each figure (tight layout for that size), not a scaled copy of one layout
    small_axes, wide_axes = small.axes[0].get_position(), wide.axes[0].get_position()
    assert wide_axes.width > small_axes.width


def test_a_title_with_dollar_signs_is_drawn_as_typed_not_as_maths():
    result = run(Plot(), Values=[1.0, 2.0], Title="$x^{$ per panel")  # broken TeX if read as maths
    assert result.state == "ok"
    figure = render({"kind": "line", "y": [1.0, 2.0], "title": "$x^{$ per panel"})
    figure.canvas.draw()
    assert figure.axes[0].title.get_text() == r"\$x^{\$ per panel"  # matplotlib's escaped dollars
