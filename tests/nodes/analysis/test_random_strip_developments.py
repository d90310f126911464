"""IsoMapping of RulingDevelopable's output never overlaps itself, on random curve pairs
(hypothesis): the development is a simple polygon (shapely ``is_valid``, no crossing).

What holds and why: a development is an isometry of the strip, so it can overlap only
where the strip itself does not lie in one sheet — its rulings cross, or it winds round
more than a turn. RulingDevelopable's rulings never run back along either curve, so for
curves that do not fold back on themselves (these) the strip is one sheet and its
development is simple. Two counterexamples were found, both strips whose rulings cross:
- a torsal fan through A's vertex ran over the whole of the straight B and the flat
  triangles after it ran back over B from the station's own partner; they now start
  where the fan ends (kept as an example below, and its own test);
- two curves in one plane (the whole strip is one planar piece): the planar pieces'
  fans were drawn before the stations between them got their partners, so a fan over
  the whole of B was followed by a station whose partner ran back; the stations get
  their partners first now (its own test below).
The random examples are drawn from a fixed seed (``derandomize``), so the suite does not
fail by chance; ``--hypothesis-seed`` with ``derandomize`` off explores more."""

from __future__ import annotations

import numpy as np
import shapely
from hypothesis import HealthCheck, example, given, settings
from hypothesis import strategies as st

from tests.support.node_helpers import out, run, tree
from torsal.nodes.analysis.iso_mapping import IsoMapping
from torsal.nodes.developable.ruling_developable import RulingDevelopable
from torsal.nodes.geometry.curves import InterpolatedCurve

offset = st.floats(-0.3, 0.3, allow_nan=False, allow_infinity=False)
wiggles = st.lists(st.tuples(offset, offset), min_size=3, max_size=6)


def curve(wiggle: list[tuple[float, float]], stretch: float, shift: float, lift: float) -> InterpolatedCurve:
    """A curve through points a unit apart along x (times ``stretch``), each moved by up to
    0.3 across: it never turns back on itself (a curve folding back over itself makes a
    strip that overlaps itself in 3D, whose development may overlap too)."""
    yz = np.array(wiggle, dtype=float)
    x = stretch * np.arange(len(yz)) + shift
    return InterpolatedCurve(np.column_stack([x, yz[:, 0], yz[:, 1] + lift]))


@settings(max_examples=60, deadline=None, derandomize=True, suppress_health_check=[HealthCheck.too_slow])
@given(wiggles, wiggles, st.floats(0.6, 1.6), st.floats(-1.0, 1.0), st.floats(0.5, 3.0), st.integers(4, 40))
@example(wiggle_a=[(0.25, 0.0), (0.0, 0.0), (0.25, 0.0)], wiggle_b=[(0.0, 0.0)] * 3, stretch=1.5, shift=0.0,
         lift=0.5, segments=8)  # a fan over all of B, then flat triangles (68 % of the strip)
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


def test_the_flat_triangles_after_a_fan_over_all_of_b_start_where_the_fan_ends():
    """A planar V (A, in z = 0) and a straight B above it: the only torsal rulings are the
    fan through A's vertex, which reaches the whole of B; the rest of the strip is two flat
    triangles through B's ends, so the strip unrolls to its area exactly, in one sheet."""
    a = curve([(0.25, 0.0), (0.0, 0.0), (0.25, 0.0)], 1.0, 0.0, 0.0)
    b = curve([(0.0, 0.0)] * 3, 1.5, 0.0, 0.5)
    strip = run(RulingDevelopable(), CurveA=tree({(0,): [a]}), CurveB=tree({(0,): [b]}), Segments=8)
    (rulings,) = out(strip, "Rulings").values()
    ends = np.array([line.end for line in rulings])
    assert np.all(np.diff(ends[:, 0]) >= -1e-12)  # B's points never run back
    unrolled = run(IsoMapping(), Surface=tree({(0,): [out(strip, "Surface")[(0,)][0]]}), Segments=8)
    (development,) = out(unrolled, "Map")[(0,)]
    assert not development.overlaps
    assert abs(development.area_error) < 1e-6  # measured 8.5e-8 (the rails' chords)


def test_two_curves_in_one_plane_make_a_strip_that_unrolls_in_one_sheet():
    a = curve([(0.0, 0.0), (0.0, 0.25), (0.0, 0.0)], 1.0, 0.0, 0.0)
    b = curve([(0.0, 0.0), (0.0, 0.0), (0.0, -0.21875)], 0.625, 0.0, 0.5)
    strip = run(RulingDevelopable(), CurveA=tree({(0,): [a]}), CurveB=tree({(0,): [b]}), Segments=4)
    (rulings,) = out(strip, "Rulings").values()
    ends = np.array([line.end for line in rulings])
    assert np.all(np.diff(ends[:, 0]) >= -1e-12)  # B's points never run back
