"""Which parameter lines cross the design's asymptotic directions, and harmfully.

Height fields in closed form (tests/support/freeform_designs.py): on z = f(x, y) the
normal curvature along a parameter line is f_xx (along x) or f_yy (along y) over a
positive factor, and its change of sign is harmless only where the cross term f_xy
vanishes with it.
"""

from __future__ import annotations

import numpy as np
import pytest

from tests.support.freeform_designs import DESIGNS, Design, _monkey
from torsal.nodes.geometry.developable.asymptotic import asymptotic_crossings
from torsal.nodes.geometry.developable.fans import patch_areas
from torsal.nodes.geometry.developable.rationalise import rationalise


def _ripple(x, y):
    """z = sin x: a cylinder whose lines along x cross an inflection with f_xy = 0 there."""
    zero = 0 * x + 0 * y
    return np.sin(x) + zero, np.cos(x) + zero, zero, -np.sin(x) + zero, zero, zero


def _tilted_ripple(x, y):
    """z = sin(x + y/2): the same cylinder turned, so the lines along x and along y both
    cross its inflection lines where f_xy = −sin(x + y/2)/2 vanishes too."""
    p = x + 0.5 * y
    return np.sin(p), np.cos(p), 0.5 * np.cos(p), -np.sin(p), -0.5 * np.sin(p), -0.25 * np.sin(p)


MONKEY = Design("monkey", _monkey, (-7.0, 7.0), (-7.0, 7.0))


def test_lines_along_x_on_a_monkey_saddle_cross_its_straight_asymptotic_line_x_0():
    # f_xx = 6x/400 changes sign at x = 0 on every line y = c, where f_xy = −6c/400 ≠ 0
    assert asymptotic_crossings(MONKEY.surface(), "u") > 0.3


def test_lines_along_y_on_a_monkey_saddle_never_cross_one():
    # f_yy = −6x/400 keeps its sign along every line x = c (and is 0 along x = 0 itself)
    assert asymptotic_crossings(MONKEY.surface(), "v") == 0.0


@pytest.mark.parametrize("jet", [_ripple, _tilted_ripple])
@pytest.mark.parametrize("family", ["u", "v"])
def test_crossing_an_inflection_where_the_tangent_plane_stands_still_is_harmless(jet, family):
    # on a cylinder II(t, ·) vanishes wherever II(t, t) does: only the interpolation's error
    design = Design("ripple", jet, (-6.0, 6.0), (-4.0, 4.0))
    assert asymptotic_crossings(design.surface(), family) < 0.02


def test_the_waves_lines_along_y_cross_and_its_lines_along_x_do_not():
    # z = 0.7 sin(0.5(x + y/2)) + 0.5 sin(0.6 y): along x, f_xx and f_xy are both multiples of
    # sin(0.5(x + y/2)); along y, f_yy has the second wave's term and f_xy does not
    wave = DESIGNS["wave"].surface()
    assert asymptotic_crossings(wave, "u") < 0.02
    assert asymptotic_crossings(wave, "v") > 0.1


def test_a_saddle_and_a_dome_have_none():
    for name in ("saddle", "dome"):
        for family in "uv":
            assert asymptotic_crossings(DESIGNS[name].surface(), family) == 0.0


def _twisted(x, y):
    """z = y·sin(x)/4: along every line y = c, f_xx = −c·sin(x)/4 changes sign where
    sin x = 0 while f_xy = cos(x)/4 = ±1/4 there."""
    return y * np.sin(x) / 4, y * np.cos(x) / 4, np.sin(x) / 4, -y * np.sin(x) / 4, np.cos(x) / 4, 0 * x


def test_crossing_an_inflection_where_the_surface_twists_is_harmful():
    design = Design("twisted", _twisted, (-6.0, 6.0), (-4.0, 4.0))
    assert asymptotic_crossings(design.surface(), "u") > 0.3


def test_rationalise_runs_a_monkey_saddles_boundaries_along_its_asymptotic_line_within_the_tolerance():
    # the square law ties the two families (the saddle is symmetric under x ↔ y up to sign);
    # the lines along x all cross x = 0, so the boundaries run along y, and the one strip
    # on x = 0 creases (the saddle's straight line: no strip along it is torsal)
    tolerance = 0.1
    result = rationalise(MONKEY.surface(), tolerance, 64, min_width=0.2)
    assert result.family == "v"
    u, v = (a.ravel() for a in np.meshgrid(np.linspace(0, 1, 121), np.linspace(0, 1, 13)))
    worst = max(float(MONKEY.distance(strip.surface.point_at(u, v)).max()) for strip in result.strips)
    assert worst <= tolerance
    areas = [patch_areas(s.result.starts, s.result.ends) for s in result.strips]
    shared = [(np.linalg.norm(np.diff(s.result.starts, axis=0), axis=1) <= 1e-9)
              | (np.linalg.norm(np.diff(s.result.ends, axis=0), axis=1) <= 1e-9) for s in result.strips]
    triangles = sum(float(a[k].sum()) for a, k in zip(areas, shared, strict=True))
    assert triangles / sum(float(a.sum()) for a in areas) <= 0.10
