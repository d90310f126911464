"""RulingDevelopable on a cylinder whose CurveB was drawn against CurveA (issue 26, item 4).

Both curves lie on the cylinder x² + y² = 1 (closed forms here, exact tangents). The
cylinder's generators are torsal rulings between them: the ruling from A at angle φ ends
on B at the same angle φ, so it is vertical (its end has the start's x and y). With B
run backwards its partners run backwards along it; the node solves the strip with CurveB
reversed (as a loft aligns its curves), says so, and gives the generators — not a cone
from A's start over B and a remark that no torsal ruling reaches it.
"""

from __future__ import annotations

import numpy as np

from tests.support.node_helpers import out, run, texts, tree
from tests.support.warp_check import warp
from torsal.nodes.developable.ruling_developable import RulingDevelopable
from torsal.nodes.geometry.curves import ParametricCurve


def on_cylinder(angle, d_angle, height, d_height) -> ParametricCurve:
    """x ↦ (cos θ(x), sin θ(x), z(x)) with its exact derivative."""

    def point(x):
        x = np.asarray(x, dtype=float)
        return np.column_stack([np.cos(angle(x)), np.sin(angle(x)), height(x)])

    def tangent(x):
        x = np.asarray(x, dtype=float)
        th, w = angle(x), d_angle(x)
        return np.column_stack([-np.sin(th) * w, np.cos(th) * w, d_height(x)])

    return ParametricCurve(point, (0.0, 1.0), derivatives=(tangent,))


def ones(x):
    return np.ones_like(x)


#: A from angle 0 to 2 (a low wave), B from angle 2 back to 0 (rising): every generator
#: from A reaches B, backwards along it.
A_FULL = on_cylinder(lambda x: 2 * x, lambda x: 2 * ones(x), lambda x: 0.1 * np.sin(3 * x),
                     lambda x: 0.3 * np.cos(3 * x))
B_BACK = on_cylinder(lambda x: 2 * (1 - x), lambda x: -2 * ones(x), lambda x: 1 + 0.2 * x,
                     lambda x: 0.2 * ones(x))
#: A from angle 0.62 to 1.62; B from 1.2 back to −0.46 on a wave: generators reach B from
#: the part of A below angle 1.2 only.
A_PART = on_cylinder(lambda x: 0.62 + x, ones, lambda x: 0 * x, lambda x: 0 * x)
WAVE = 3.9 * 2 * np.pi
B_PART = on_cylinder(lambda x: 1.2 - 1.66 * x, lambda x: -1.66 * ones(x),
                     lambda x: 1 + 0.27 * np.sin(WAVE * x), lambda x: 0.27 * WAVE * np.cos(WAVE * x))


def solve(a, b):
    node = run(RulingDevelopable(), CurveA=tree({(0,): [a]}), CurveB=tree({(0,): [b]}), Segments=20)
    rulings = out(node, "Rulings")[(0,)]
    starts = np.array([r.start for r in rulings])
    ends = np.array([r.end for r in rulings])
    return node, starts, ends, out(node, "Kind")[(0,)]


def angle_of(points: np.ndarray) -> np.ndarray:
    return np.arctan2(points[:, 1], points[:, 0])


def test_a_curve_b_drawn_backwards_gives_the_cylinders_generators():
    node, starts, ends, kinds = solve(A_FULL, B_BACK)
    assert kinds == ["torsal"] * 21
    np.testing.assert_allclose(ends[:, :2], starts[:, :2], atol=1e-12)  # vertical: generators
    # the warp from the curves' own tangents (B's reversed: the strip runs against it)
    ta = A_FULL.derivatives(angle_of(starts) / 2, 1)[1]
    tb = -B_BACK.derivatives(1 - angle_of(ends) / 2, 1)[1]
    assert np.nanmax(warp(starts, ends, ta, tb)) <= 1e-12
    assert texts(node)[0].startswith("CurveB runs against CurveA")
    assert not any("no torsal ruling" in t for t in texts(node))


def test_where_generators_reach_b_they_are_the_rulings_and_no_cone_from_a_start_covers_them():
    node, starts, ends, kinds = solve(A_PART, B_PART)
    torsal = np.array([k == "torsal" for k in kinds])
    # every point of A the rulings start from whose generator meets B (angle up to 1.2)
    # has that generator among its rulings
    points, which = np.unique(starts.round(12), axis=0, return_inverse=True)
    reach = angle_of(points) <= 1.2 - 1e-9
    has_torsal = np.bincount(which.ravel(), weights=torsal, minlength=len(points)) > 0
    assert has_torsal[reach].all() and reach.sum() >= 12
    np.testing.assert_allclose(ends[torsal, :2], starts[torsal, :2], atol=1e-12)
    # rulings from A(0) end on B only beyond A's own angles (below 0.62): no cone from A's
    # start over the stretch of B the generators reach
    from_start = np.linalg.norm(starts - A_PART.derivatives(np.array([0.0]), 0)[0], axis=1) <= 1e-12
    assert (angle_of(ends[from_start]) <= 0.62 + 1e-9).all()
    assert not any("reaches part of curve B" in t for t in texts(node))
