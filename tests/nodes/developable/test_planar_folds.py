"""Two curves in one plane: every ruling's tangent plane is that plane, so a ruling's warp
is 0 where the sheet lies on one side of it as the curves run, π where the sheet folds back
over itself there, and undefined where a fan of rulings through one point turns back (the
ruling at the turn runs along the curve). Whether the sheet folds is judged here from the
output Surface alone: the signed areas of thin pieces between 4,000 of its isocurves, seen in
the plane, all have one sign exactly when it does not."""

from __future__ import annotations

import numpy as np
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from tests.support import warp_check
from tests.support.node_helpers import out, run, tree
from torsal.nodes.developable.ruling_developable import RulingDevelopable
from torsal.nodes.geometry.curves import InterpolatedCurve


def planar(heights: list[float], stretch: float = 1.0, shift: float = 0.0,
           lift: float = 0.0) -> InterpolatedCurve:
    """A cubic in the plane y = 0 through (shift + stretch·k, heights[k] + lift)."""
    x = shift + stretch * np.arange(len(heights))
    return InterpolatedCurve(np.column_stack([x, np.zeros(len(x)), np.asarray(heights, float) + lift]))


def solve(a, b, segments: int) -> dict:
    result = run(RulingDevelopable(), CurveA=tree({(0,): [a]}), CurveB=tree({(0,): [b]}), Segments=segments)
    assert result.state != "error", result.messages
    ports = ("Surface", "Rulings", "WarpAngles", "Valid")
    got = {port: next(iter(out(result, port).values())) for port in ports}
    got["Surface"] = got["Surface"][0]
    return got


def folds(surface, n: int = 4000) -> int:
    """How many of the n − 1 thin pieces between isocurves face the other way from the most."""
    u = np.linspace(0.0, 1.0, n)
    a = surface.derivatives(u, np.zeros(n), 0)[0][:, [0, 2]]
    b = surface.derivatives(u, np.ones(n), 0)[0][:, [0, 2]]
    corners = [a[:-1], a[1:], b[1:], b[:-1]]
    following = corners[1:] + corners[:1]
    area = 0.5 * sum(p[:, 0] * q[:, 1] - p[:, 1] * q[:, 0] for p, q in zip(corners, following, strict=True))
    seen = np.abs(area) > 1e-12 * np.abs(area).max()
    return int(np.count_nonzero(np.sign(area[seen]) != np.sign(area[seen].sum())))


def test_a_strip_ending_in_a_fan_whose_curves_end_on_opposite_sides_of_its_last_ruling_is_flat():
    """The last ruling A(1) → B(1) closes a fan through A(1): the sheet next to it is that
    fan, so A's own tangent at its end (on the far side of the ruling from B's) plays no part;
    it used to be measured there, giving π and Valid = false on a sheet that does not fold."""
    a = planar([0.25, -0.125, 0.125])
    b = planar([0.0, -0.125, 0.25, -0.25], stretch=0.875, shift=1.0, lift=1.125)
    got = solve(a, b, 12)
    assert folds(got["Surface"]) == 0
    warp = np.asarray(got["WarpAngles"], dtype=float)
    assert np.abs(warp).max() <= 1e-15  # measured: 0 exactly
    assert all(got["Valid"])


def test_a_fan_that_turns_back_gets_a_ruling_at_the_turn_with_no_warp():
    """The planar strip of the unrolling tests (A the parabola z = x/2 − x²/4 from x = 0 to 2): the
    fan through the point P of B turns back where the ray from P touches A, at the x with
    (P − A(x)) ∥ A'(x): (Px − x)(1/2 − x/2) = Pz − x/2 + x²/4, i.e. x² − 2·Px·x + 2·Px − 4·Pz = 0."""
    a = planar([0.0, 0.25, 0.0])
    b = planar([0.0, 0.0, -0.21875], stretch=0.625, lift=0.5)
    got = solve(a, b, 4)
    starts = np.array([line.start for line in got["Rulings"]])
    ends = np.array([line.end for line in got["Rulings"]])
    warp = np.asarray(got["WarpAngles"], dtype=float)
    valid = np.asarray(got["Valid"])
    # the fan through B's point P = the end shared by most rulings
    ends_seen, counts = np.unique(ends.round(12), axis=0, return_counts=True)
    p = ends_seen[np.argmax(counts)]
    px, pz = p[0], p[2]
    roots = np.roots([1.0, -2.0 * px, 2.0 * px - 4.0 * pz])
    x_turn = float(roots[(roots.real > 0) & (roots.real < 2)].real.max())
    at_turn = np.flatnonzero(np.isnan(warp) & (np.abs(starts[:, 0] - x_turn) < 1e-9))
    assert len(at_turn) == 1  # measured: x equal to the root (0 apart; A is the parabola to 6e-17)
    assert not valid[at_turn[0]]
    assert np.isnan(warp_check.strip_between_curves(a, b, starts, ends)[at_turn[0]])


heights = st.lists(st.floats(-0.3, 0.3), min_size=3, max_size=5)


@settings(max_examples=40, deadline=None, derandomize=True, suppress_health_check=[HealthCheck.too_slow])
@given(heights, heights, st.floats(0.6, 1.6), st.floats(-1.0, 1.0), st.floats(0.5, 3.0), st.integers(4, 40))
def test_a_planar_strip_is_all_valid_exactly_when_its_sheet_does_not_fold(ha, hb, stretch, shift, lift,
                                                                           segments):
    got = solve(planar(ha), planar(hb, stretch, shift, lift), segments)
    assert all(got["Valid"]) == (folds(got["Surface"]) == 0)
