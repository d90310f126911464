"""IsoMapping of RulingDevelopable's output never overlaps itself, on random curve pairs
(hypothesis): the development is a simple polygon (shapely ``is_valid``, no crossing)."""

from __future__ import annotations

import numpy as np
import shapely
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from nodes.analysis.iso_mapping import IsoMapping
from nodes.developable.ruling_developable import RulingDevelopable
from nodes.geometry.curves import InterpolatedCurve
from tests.nodes.helpers import out, run, tree

offset = st.floats(-0.3, 0.3, allow_nan=False, allow_infinity=False)
wiggles = st.lists(st.tuples(offset, offset), min_size=3, max_size=6)


def curve(wiggle: list[tuple[float, float]], stretch: float, shift: float, lift: float) -> InterpolatedCurve:
    """A curve through points a unit apart along x (times ``stretch``), each moved by up to
    0.3 across: it never turns back on itself (a curve folding back over itself makes a
    strip that overlaps itself in 3D, whose development may overlap too)."""
    yz = np.array(wiggle, dtype=float)
    x = stretch * np.arange(len(yz)) + shift
    return InterpolatedCurve(np.column_stack([x, yz[:, 0], yz[:, 1] + lift]))


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(wiggles, wiggles, st.floats(0.6, 1.6), st.floats(-1.0, 1.0), st.floats(0.5, 3.0), st.integers(4, 40))
def test_iso_mapping_of_a_developable_between_random_curves_is_a_simple_polygon(
    wiggle_a, wiggle_b, stretch, shift, lift, segments
):
    a = curve(wiggle_a, 1.0, 0.0, 0.0)
    b = curve(wiggle_b, stretch, shift, lift)
    strip = run(RulingDevelopable(), CurveA=tree({(0,): [a]}), CurveB=tree({(0,): [b]}), Segments=segments)
    assert strip.state != "error", strip.messages
    (surface,) = out(strip, "Surface")[(0,)]
    unrolled = run(IsoMapping(), Surface=tree({(0,): [surface]}), Segments=segments)
    assert unrolled.state != "error", unrolled.messages
    (development,) = out(unrolled, "Map")[(0,)]
    assert shapely.Polygon(development.outline).is_valid
    assert not development.overlaps
