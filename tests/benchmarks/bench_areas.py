"""Surface areas by Gauss rules per span, against the cheapest Simpson grid as accurate (``make bench``).

Run alone with::

    .venv/bin/python -m pytest tests/benchmarks/bench_areas.py \\
        -o python_files='bench_*.py' -o norecursedirs='.*' -s

The bars of the area issue were absolute (a NURBS loft's area in well under a second, a
ruled loft's in under half a second: the generic adaptive cubature took 4–50 s). Here
each area is timed against a baseline measured in the same run: scipy's Simpson rule on a
uniform grid of the surface's own area element, on the cheapest grid that passes the same
accuracy test (``ACCURACY`` of the true area), searched for in the run knowing the answer
(:func:`cheapest_simpson_grid`). The Gauss rules need no such search: they check
themselves (two orders must agree), so they reach rounding where Simpson's grid is only
as fine as it must be; both errors are printed. Against that best case the Gauss rules
are slower (8–18× measured), the price of not having to know the answer to pick a grid.
What the areas are is checked by ``make test`` (``tests/nodes/geometry``).
"""

from __future__ import annotations

import math
import time

from tests.benchmarks.timing import ratio_to_baseline
from tests.nodes.geometry.test_ruled_area import circle_loft, simpson_area, twisted_loft
from torsal.nodes.geometry.curves import Circle
from torsal.nodes.geometry.nurbs_surface import Loft
from torsal.nodes.geometry.surface_base import Surface
from torsal.nodes.geometry.vectors import Plane

#: The accuracy test both rules must pass: relative error against the true area.
ACCURACY = 1e-6
#: Grid sizes tried (odd, for Simpson's rule), about 1.25 times apart.
SIZES = sorted({2 * round(1.25**k) + 1 for k in range(1, 38)})


def cheapest_simpson_grid(surface: Surface, exact: float) -> tuple[int, int]:
    """The Simpson grid ``(nu, nv)`` with fewest points whose error is within ``ACCURACY``
    of ``exact``, and stays within it on the next two finer ``nu`` (a converged grid, not
    one that is right by luck)."""
    best: tuple[int, int] | None = None
    for nv in SIZES[:12]:
        if best is not None and SIZES[0] * nv >= best[0] * best[1]:
            break
        errors: list[float] = []
        for nu in SIZES:
            if best is not None and nu * nv >= best[0] * best[1]:
                break
            errors.append(abs(simpson_area(surface, nu, nv) - exact) / exact)
            if len(errors) >= 3 and max(errors[-3:]) <= ACCURACY:
                best = (SIZES[len(errors) - 3], nv)
                break
    assert best is not None, "no Simpson grid reaches the accuracy"
    return best


def compare(what: str, surface: Surface, exact: float, known_as: str, bar: float) -> None:
    """Time the Gauss rules against Simpson's cheapest grid; print both errors against ``exact``."""
    grid = cheapest_simpson_grid(surface, exact)
    ours, simpson = surface.area(), simpson_area(surface, *grid)
    # sub-millisecond calls are repeated to about 10 ms a timing: on a loaded machine a
    # single one varies by 3× and more
    started = time.perf_counter()
    simpson_area(surface, *grid)
    loops = max(1, round(0.01 / (time.perf_counter() - started)))
    ratio = ratio_to_baseline(
        f"{what} (× {loops})" if loops > 1 else what,
        lambda: [surface.area_and_centroid() for _ in range(loops)],
        f"Simpson's rule (area only) on the cheapest grid within {ACCURACY:.0e}, {grid[0]} × {grid[1]}",
        lambda: [simpson_area(surface, *grid) for _ in range(loops)],
        11,
    )
    print(
        f"  relative error against {known_as}: Gauss {abs(ours - exact) / exact:.1e}, "
        f"Simpson {abs(simpson - exact) / exact:.1e}"
    )
    assert abs(ours - exact) <= ACCURACY * exact
    assert ratio <= bar


def test_nurbs_loft_of_two_circles_within_30x_the_cheapest_simpson_grid_as_accurate():
    """Measured 15× (on a 531 × 3 grid)."""
    radius, height = 1.5, 2.0
    circles = [Circle(Plane.from_normal([0, 0, z], [0, 0, 1]), radius) for z in (0.0, height)]
    exact = 2 * math.pi * radius * height
    compare("NURBS loft of two circles, area and centroid", Loft(circles), exact, "2πrh", 30.0)


def test_ruled_cylinder_loft_within_35x_the_cheapest_simpson_grid_as_accurate():
    """Measured 17–18× (its area element is so even that a 3 × 3 grid is within 1e-7)."""
    surface = circle_loft(2.0, 3.0, 97)
    exact = 2 * math.pi * 2.0 * 3.0
    compare("ruled loft of 97 cylinder rulings, area and centroid", surface, exact, "2πrh", 35.0)


def test_twisted_ruled_loft_within_17x_the_cheapest_simpson_grid_as_accurate():
    """Measured 8.5× (on a 25 × 5 grid)."""
    surface = twisted_loft()
    reference = simpson_area(surface, 3961, 33)  # make test's reference: 2e-10 from a 7921 × 65 grid
    what = "ruled loft of 100 twisted rulings, area and centroid"
    compare(what, surface, reference, "a 3961 × 33 Simpson grid", 17.0)
