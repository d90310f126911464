"""developable.stack: several strips' rows in one array, each strip's curve evaluated on its
own rows with the values it gives them alone."""

from __future__ import annotations

import numpy as np

from torsal.nodes.geometry.curves import NurbsCurve
from torsal.nodes.geometry.developable.stack import Stack, evaluate_each, evaluate_rows


def _curves() -> list[NurbsCurve]:
    rng = np.random.default_rng(7)
    return [NurbsCurve(rng.normal(size=(6 + k, 3)) * 10 ** k, degree=3) for k in range(3)]


def test_a_stack_splits_repeats_and_reduces_by_strip():
    stack = Stack([2, 0, 3])
    values = np.array([[1.0], [5.0], [2.0], [-1.0], [4.0]])
    assert [part[:, 0].tolist() for part in stack.split(values)] == [[1.0, 5.0], [], [2.0, -1.0, 4.0]]
    assert stack.repeat(np.array([7, 8, 9])).tolist() == [7, 7, 9, 9, 9]
    assert stack.owner().tolist() == [0, 0, 2, 2, 2]
    assert stack.groups(np.array([1, 3, 4])).tolist() == [0, 1, 1, 3]


def test_each_curve_on_its_rows_gives_what_it_gives_alone():
    curves = _curves()
    rng = np.random.default_rng(8)
    x = [rng.uniform(0, 1, size=n) for n in (5, 1, 9)]
    together = evaluate_each(curves, np.concatenate(x), np.array([0, 5, 6, 15]), 2)
    alone = [curve.derivatives(t, 2) for curve, t in zip(curves, x, strict=True)]
    for k in range(3):
        np.testing.assert_array_equal(together[k], np.concatenate([a[k] for a in alone]))


def test_rows_in_any_order_get_their_own_curves_values():
    curves = _curves()
    rng = np.random.default_rng(9)
    owner = rng.integers(0, 3, size=40)
    x = rng.uniform(0, 1, size=40)
    found = evaluate_rows(curves, x, owner, 1)
    for i in range(40):
        points, tangents = curves[owner[i]].derivatives(x[i : i + 1], 1)
        np.testing.assert_array_equal(found[0][i], points[0])
        np.testing.assert_array_equal(found[1][i], tangents[0])
