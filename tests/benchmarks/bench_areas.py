"""Surface areas by Gauss rules per span, against scipy's Simpson rule (``make bench``).

Run alone with::

    .venv/bin/python -m pytest tests/benchmarks/bench_areas.py \\
        -o python_files='bench_*.py' -o norecursedirs='.*' -s

The bars of the area issue were absolute (a NURBS loft's area in well under a second, a
ruled loft's in under half a second: the generic adaptive cubature took 4–50 s). Here
each area is timed against a baseline measured in the same run: scipy's Simpson rule on
a uniform grid of the surface's own area element, the grid fine enough to pass the same
accuracy test (errors printed beside it; for the twisted loft, whose area has no closed
form, the fine grid ``make test`` takes as the reference). Unlike the Gauss rules, which check themselves (two
orders must agree), Simpson's grid has to be chosen knowing the answer. What the areas
are is checked by ``make test`` (``tests/geometry``, ``tests/developable``).
"""

from __future__ import annotations

import math

from nodes.geometry.curves import Circle
from nodes.geometry.nurbs_surface import Loft
from nodes.geometry.surface_base import Surface
from nodes.geometry.vectors import Plane
from tests.benchmarks.timing import ratio_to_baseline
from tests.developable.test_ruled_area import circle_loft, simpson_area, twisted_loft


def compare(
    what: str, surface: Surface, exact: float, known_as: str, grid: tuple[int, int], bar: float
) -> None:
    """Time the Gauss rules against Simpson's on ``grid``; print both errors against ``exact``."""
    ours, simpson = surface.area(), simpson_area(surface, *grid)
    ratio = ratio_to_baseline(
        what,
        lambda: surface.area_and_centroid(),
        f"Simpson's rule, {grid[0]} × {grid[1]} grid",
        lambda: simpson_area(surface, *grid),
        15,
    )
    print(
        f"  relative error against {known_as}: Gauss {abs(ours - exact) / exact:.1e}, "
        f"Simpson {abs(simpson - exact) / exact:.1e}"
    )
    assert abs(ours - exact) <= 1e-6 * exact
    assert ratio <= bar


def test_nurbs_loft_of_two_circles_within_30x_simpsons_rule_of_the_same_accuracy():
    radius, height = 1.5, 2.0
    circles = [Circle(Plane.from_normal([0, 0, z], [0, 0, 1]), radius) for z in (0.0, height)]
    exact = 2 * math.pi * radius * height
    compare("NURBS loft of two circles, area and centroid", Loft(circles), exact, "2πrh", (801, 3), 30.0)


def test_ruled_cylinder_loft_within_20x_simpsons_rule_of_the_same_accuracy():
    surface = circle_loft(2.0, 3.0, 97)
    exact = 2 * math.pi * 2.0 * 3.0
    compare("ruled loft of 97 cylinder rulings, area and centroid", surface, exact, "2πrh", (385, 3), 20.0)


def test_twisted_ruled_loft_within_half_the_time_of_the_fine_simpson_reference():
    surface = twisted_loft()
    fine = simpson_area(surface, 3961, 33)  # make test's reference
    what = "ruled loft of 100 twisted rulings, area and centroid"
    compare(what, surface, fine, "that reference", (3961, 33), 0.5)
