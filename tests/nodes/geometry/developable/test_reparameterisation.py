"""The strip between two curves depends on the curves, not on how they are parameterised.

Random pairs cut from one cone (seeded wave parameters; every generator is a torsal
ruling, its partner known in closed form) are solved as given and with a curve
re-parameterised: t → t² (the parameter stands still at the start: B′(0) = 0),
t → (t + t³)/2 and t → 1 − t on both curves (the strip read from its other end). The
rulings' end points must agree to 1e-9 of the pair's size, in order (reversed for
t → 1 − t). The curves' derivatives are exact (chain rule on analytic ones), so any
difference is the solver's.

Seeded random rational NURBS rails (:mod:`tests.support.rational_rails`), mostly not
developable, are closed largely by fans, closing triangles, near partners and end cones:
all of those rulings too must stay where they are, whichever curve is re-parameterised
(a NURBS run as t² no longer reports where its knots are, so its length is measured by
the adaptive rule) or reversed (as RulingDevelopable does: a CurveB drawn against CurveA
is reversed for the solve, :func:`~torsal.nodes.geometry.developable.alternatives.align_b`).
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import HealthCheck, example, given, settings
from hypothesis import strategies as st

from tests.support import curve_pairs
from tests.support.rational_rails import rails
from torsal.nodes.geometry.curves import ParametricCurve
from torsal.nodes.geometry.developable import ruling_developable, ruling_developables
from torsal.nodes.geometry.developable.alternatives import align_b

SEGMENTS = 30


def reparameterised(curve, phi, dphi, ddphi) -> ParametricCurve:
    """x ↦ curve(φ(x)) with exact first and second derivatives."""

    def parts(x):
        x = np.asarray(x, dtype=float)
        p, d1, d2 = curve.derivatives(phi(x), 2)
        return p, d1 * dphi(x)[:, None], d2 * (dphi(x) ** 2)[:, None] + d1 * ddphi(x)[:, None]

    return ParametricCurve(lambda x: parts(x)[0], (0.0, 1.0),
                           derivatives=(lambda x: parts(x)[1], lambda x: parts(x)[2]))


def squared(curve) -> ParametricCurve:
    return reparameterised(curve, lambda x: x * x, lambda x: 2 * x, lambda x: np.full_like(x, 2.0))


def reversed_(curve) -> ParametricCurve:
    return reparameterised(curve, lambda x: 1 - x, lambda x: -np.ones_like(x), lambda x: np.zeros_like(x))


def cubic(curve) -> ParametricCurve:
    """t → (t + t³)/2: slow at the start, fast at the end."""
    return reparameterised(curve, lambda x: 0.5 * (x + x**3), lambda x: 0.5 + 1.5 * x * x, lambda x: 3.0 * x)


def cone_pair(base_a: float, amp_a: float, freq_a: float, base_b: float, amp_b: float, freq_b: float):
    span = curve_pairs._lin(0.0, 2.5)
    a = curve_pairs._curve(curve_pairs.cone_surface, span, curve_pairs._wave(base_a, amp_a, freq_a), False)
    wave_b = curve_pairs._wave(base_a + base_b, amp_b, freq_b, 1.0)
    b = curve_pairs._curve(curve_pairs.cone_surface, span, wave_b, False)
    return a, b


def ends(a, b) -> tuple[np.ndarray, float]:
    r = ruling_developable(a, b, SEGMENTS)
    size = float(np.linalg.norm(np.ptp(np.vstack([r.starts, r.ends]), axis=0)))
    return np.stack([r.starts, r.ends], axis=1), size


pairs = st.tuples(
    st.floats(1.5, 2.5), st.floats(0.0, 0.3), st.floats(1.0, 6.0),
    st.floats(1.5, 3.0), st.floats(0.0, 0.4), st.floats(1.0, 5.0),
)
SETTINGS = settings(
    max_examples=8, deadline=None, derandomize=True, suppress_health_check=[HealthCheck.too_slow]
)


@SETTINGS
@given(pairs)
def test_reading_both_curves_from_their_other_ends_gives_the_same_rulings_reversed(params):
    a, b = cone_pair(*params)
    given_, size = ends(a, b)
    other, _ = ends(reversed_(a), reversed_(b))
    assert other.shape == given_.shape
    assert np.abs(other[::-1] - given_).max() <= 1e-9 * size


@SETTINGS
@given(pairs)
def test_squaring_the_parameter_of_b_leaves_the_rulings_where_they_were(params):
    a, b = cone_pair(*params)
    given_, size = ends(a, b)
    other, _ = ends(a, squared(b))
    assert other.shape == given_.shape
    assert np.abs(other - given_).max() <= 1e-9 * size


@SETTINGS
@given(pairs)
def test_squaring_the_parameter_of_a_leaves_the_rulings_where_they_were(params):
    a, b = cone_pair(*params)
    given_, size = ends(a, b)
    other, _ = ends(squared(a), b)
    assert other.shape == given_.shape
    assert np.abs(other - given_).max() <= 1e-9 * size


@SETTINGS
@given(pairs, st.sampled_from(["A", "B"]))
def test_a_cubic_pace_on_either_curve_leaves_the_rulings_where_they_were(params, which):
    a, b = cone_pair(*params)
    given_, size = ends(a, b)
    other, _ = ends(cubic(a), b) if which == "A" else ends(a, cubic(b))
    assert other.shape == given_.shape
    assert np.abs(other - given_).max() <= 1e-9 * size


# -- plane sections through inflections (tests/support/curve_pairs.py) --------------------------
#
# A's stations at s = 1/3 and 2/3 meet the directrix's inflections, where the true
# partner is a double root of the coplanarity (f and f_t vanish together): before it was
# solved as one (the simple root of f_t), rounding alone moved it by 1.4e-9 of B and the
# re-parameterised strips by up to 2.3e-9 of the size; measured now 5.6e-12 at most
# (t -> (t + t^3)/2 on A: the stations read back from A's length).

CHANGES = {
    "t -> 1 - t on both": lambda a, b: (reversed_(a), reversed_(b)),
    "t -> 1 - t on A": lambda a, b: (reversed_(a), b),
    "t -> 1 - t on B": lambda a, b: (a, reversed_(b)),
    "t -> t^2 on A": lambda a, b: (squared(a), b),
    "t -> t^2 on B": lambda a, b: (a, squared(b)),
    "t -> (t + t^3)/2 on A": lambda a, b: (cubic(a), b),
    "t -> (t + t^3)/2 on B": lambda a, b: (a, cubic(b)),
}
#: The sections' test takes every change but turning one curve alone.
SECTION_CHANGES = {
    name: make for name, make in CHANGES.items() if name not in ("t -> 1 - t on A", "t -> 1 - t on B")
}


@pytest.mark.parametrize("name", ["cylinder_sections", "cone_sections"])
def test_sections_through_inflections_keep_their_rulings_when_re_parameterised(name):
    pair = curve_pairs.PAIRS[name]()
    given_, _ = ends(pair.a, pair.b)
    for change, make in SECTION_CHANGES.items():
        other, _ = ends(*make(pair.a, pair.b))
        if change == "t -> 1 - t on both":
            other = other[::-1]
        assert other.shape == given_.shape, change
        assert np.abs(other - given_).max() <= 1e-10 * pair.size, change


# -- random rational NURBS pairs (tests/support/rational_rails.py) -------------------------------
#
# Mostly not developable: fans and near partners (rulings whose warp is within the
# tolerance but not zero, the least-warped among points evenly spaced along B) close most
# of them, placed along B's length, never by its parameter. Measured on every one of seeds
# 0-159 with every change of CHANGES (1,120 pairs of strips, 33 s, run once): 1.3e-10 of the size
# at most (seed 69, (t + t^3)/2 on A; before, the fans moved with B's pace: 1.7e-2 under t²,
# 3e-2 read from the other end). Seed 156's strip is all fans whichever way B runs (100 %
# either way): the tie is settled by the curves' ends, as Rhino's Loft aligns two curves
# (1.4e-16 with B reversed, 1.6e-15 with A reversed; 0.27 before). Here 30 of those pairs
# are drawn, besides the ones that once failed.



def node_rulings(a, b) -> tuple[np.ndarray, float]:
    """All the strip's rulings as RulingDevelopable makes them (CurveB reversed where it
    was drawn against CurveA), as rows (start, end), and the pair's size."""
    job = (a, b, SEGMENTS, 1e-3)
    results = ruling_developables([job])
    align_b([job], results)
    r = results[0]
    size = float(np.linalg.norm(np.ptp(np.vstack([r.starts, r.ends]), axis=0)))
    return np.hstack([r.starts, r.ends]), size


@settings(SETTINGS, max_examples=30)
@given(st.integers(0, 159), st.sampled_from(sorted(CHANGES)))
@example(0, "t -> t^2 on B")  # (another partner at one station before the choice read lengths)
@example(0, "t -> 1 - t on both")  # (the closing triangles leaned the other way: 3e-2)
@example(18, "t -> 1 - t on B")  # (B reversed stood still at its end, its tangent taken backwards)
@example(26, "t -> t^2 on B")  # (a hole told by the steps of t, not of B's length)
@example(38, "t -> t^2 on A")  # (a jump predicted along A's parameter, not its length)
@example(21, "t -> t^2 on A")  # (the end cone's pencil sampled in A's parameter missed its root)
@example(156, "t -> t^2 on A")  # (A standing still at its start: its chain slope read as 0)
@example(156, "t -> 1 - t on B")  # (all fans either way: B was kept as drawn, 0.27 away)
@example(156, "t -> 1 - t on A")
def test_random_rational_pairs_keep_every_ruling_when_re_parameterised(seed, change):
    rail_a, rail_b = rails(seed, near_planar=seed % 2 == 1)
    a, b = rail_a.as_torsal(), rail_b.as_torsal()
    given_, size = node_rulings(a, b)
    other, _ = node_rulings(*CHANGES[change](a, b))
    if change in ("t -> 1 - t on A", "t -> 1 - t on both"):
        other = other[::-1]  # (A read from its other end, and B reversed with it)
    assert other.shape == given_.shape
    assert np.abs(other - given_).max() <= 1e-9 * size
