"""Curves that share a knot vector, evaluated together: each gets what it gets alone, bit for bit."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.interpolate import BSpline

from torsal.nodes.geometry.curves import Circle, InterpolatedCurve, Line, NurbsCurve
from torsal.nodes.geometry.curves.shared_knots import derivative_each, derivatives_together, polynomial_curves


def curves_sharing_knots(seed: int, rational: bool, count: int) -> list[NurbsCurve]:
    """``count`` random curves of one random degree and knot vector (a doubled inner knot
    on some seeds, a domain other than [0, 1] on odd seeds), far from the origin on some."""
    rng = np.random.default_rng(seed)
    degree = int(rng.integers(1, 5))
    points = int(rng.integers(degree + 1, degree + 7))
    inner = np.sort(rng.random(points - degree - 1))
    if seed % 3 == 0 and len(inner) > 1:
        inner[1] = inner[0]
    a, b = (0.0, 1.0) if seed % 2 == 0 else (-2.5, 4.0)
    knots = np.concatenate([[a] * (degree + 1), a + (b - a) * inner, [b] * (degree + 1)])
    return [
        NurbsCurve(
            rng.normal(size=(points, 3)) * 10.0 ** rng.integers(-2, 4) + 10.0 ** rng.integers(0, 7),
            degree, knots, rng.uniform(0.3, 3.0, points) if rational else None,
        )
        for _ in range(count)
    ]


def parameters(seed: int, counts: list[int]) -> tuple[np.ndarray, np.ndarray]:
    """Random parameters for curves getting ``counts`` of them, with the domain's ends and
    a few outside it (extrapolated), and the bounds of each curve's share."""
    rng = np.random.default_rng(seed + 1000)
    x = rng.uniform(-0.05, 1.05, sum(counts))
    x[::5], x[1::7] = 0.0, 1.0
    return x, np.concatenate([[0], np.cumsum(counts)])


def alone(curves, x, bounds, order, local):
    return [np.array((c.local_derivatives if local else c.derivatives)(x[lo:hi], order))
            for c, lo, hi in zip(curves, bounds[:-1], bounds[1:], strict=True)]


@pytest.mark.parametrize("seed", range(12))
@pytest.mark.parametrize("rational", [False, True])
def test_curves_sharing_knots_get_what_they_get_alone_bit_for_bit(seed, rational):
    curves = curves_sharing_knots(seed, rational, 5)
    x, bounds = parameters(seed, [7, 0, 12, 1, 9])
    for order in range(4):
        for local in (False, True):
            together = derivatives_together(curves, x, bounds, order, local)
            owns = alone(curves, x, bounds, order, local)
            for mine, own, lo, hi in zip(curves, owns, bounds[:-1], bounds[1:], strict=True):
                assert np.array_equal(together[:, lo:hi], own), (mine, order, local)


def test_a_polynomial_curve_together_is_scipys_bspline_of_its_control_points():
    curves = curves_sharing_knots(4, False, 3)
    x, bounds = parameters(4, [10, 10, 10])
    together = derivatives_together(curves, x, bounds, 2, local=True)
    for i, curve in enumerate(curves):
        spline = BSpline(curve.knots, curve.control_points - curve.anchor, curve.degree)
        rows = slice(bounds[i], bounds[i + 1])
        for k in range(3):
            assert np.array_equal(together[k, rows], spline(x[rows], nu=k))


def test_curves_of_other_knots_and_kinds_are_evaluated_each_on_its_own():
    shared = curves_sharing_knots(2, True, 2)
    others = [Circle(), Line([0, 0, 0], [1, 2, 3]), InterpolatedCurve([[0, 0], [1, 2], [3, 1], [4, 4]])]
    curves = [shared[0], others[0], others[1], shared[1], others[2]]
    x, bounds = parameters(7, [6, 5, 4, 6, 8])
    together = derivatives_together(curves, x, bounds, 2)
    for own, lo, hi in zip(alone(curves, x, bounds, 2, False), bounds[:-1], bounds[1:], strict=True):
        assert np.array_equal(together[:, lo:hi], own)


def test_curves_sharing_knots_need_one_basis_evaluation_per_derivative_order(monkeypatch):
    curves = curves_sharing_knots(6, True, 8)
    x, bounds = parameters(6, [5] * 8)
    calls = []
    evaluate = BSpline.__call__

    def counted(self, *args, **kwargs):
        calls.append(1)
        return evaluate(self, *args, **kwargs)

    monkeypatch.setattr(BSpline, "__call__", counted)
    derivatives_together(curves, x, bounds, 2)
    assert len(calls) == min(2, curves[0].degree) + 1


@pytest.mark.parametrize("rational", [False, True])
def test_one_derivative_of_curves_sharing_knots_is_each_curves_derivative_at(rational):
    curves = [*curves_sharing_knots(8, rational, 4), Circle(), Line([0, 0, 0], [1, 2, 3])]
    x, bounds = parameters(8, [6, 3, 9, 4, 5, 5])
    ts = np.split(x, bounds[1:-1])
    for order in range(4):
        for curve, t, found in zip(curves, ts, derivative_each(curves, ts, order), strict=True):
            assert np.array_equal(found, curve.derivative_at(t, order)), (curve, order)



@pytest.mark.parametrize("seed", range(6))
def test_curves_sharing_knots_and_parameters_are_each_curves_derivative_at_bit_for_bit(seed):
    # one spline of every curve's coefficients side by side; many parameters each (more
    # than curves evaluated together take), the same array or equal copies of it
    curves = [*curves_sharing_knots(seed, False, 5), Circle(), Line([0, 0, 0], [1, 2, 3]),
              *curves_sharing_knots(seed + 10, True, 2)]
    x, _ = parameters(seed, [300])
    ts = [x if k % 2 else x.copy() for k in range(len(curves))]
    for order in range(6):
        for curve, t, found in zip(curves, ts, derivative_each(curves, ts, order), strict=True):
            assert found.tobytes() == np.asarray(curve.derivative_at(t, order)).tobytes(), (curve, order)
            assert found.shape == (len(t), 3) and found.flags.c_contiguous


@pytest.mark.parametrize("seed", range(6))
@pytest.mark.parametrize("local", [False, True])
def test_all_orders_of_curves_sharing_knots_and_parameters_are_each_curves_own(seed, local):
    curves = [*curves_sharing_knots(seed, False, 4), Circle(), *curves_sharing_knots(seed + 10, True, 2)]
    t, _ = parameters(seed, [200])
    t[3] = -0.0  # (a parameter of another sign bit is another parameter)
    x = np.concatenate([t] * len(curves))
    x[len(t) + 3] = 0.0
    bounds = np.arange(len(curves) + 1) * len(t)
    found = derivatives_together(curves, x, bounds, 4, local)
    for k, curve in enumerate(curves):
        own = (curve.local_derivatives if local else curve.derivatives)(x[bounds[k] : bounds[k + 1]], 4)
        for order in range(5):
            assert found[order, bounds[k] : bounds[k + 1]].tobytes() == own[order].tobytes(), (k, order)

def test_a_partition_kept_for_other_curves_with_the_same_ids_is_not_taken():
    from torsal.nodes.geometry.curves import shared_knots

    line = Line([0, 0, 0], [1, 2, 3])
    curves = [*curves_sharing_knots(4, False, 3), line, *curves_sharing_knots(5, True, 2)]
    with shared_knots.partitions_kept():
        grouped, others = shared_knots._partition(curves)
        assert sorted(group.members.tolist() for group in grouped) == [[0, 1, 2], [4, 5]] and others == [3]
        assert shared_knots._partition(list(curves))[0] is grouped  # (the same curves: the one kept)
        # a kept partition under these ids, but of other curves (theirs since collected, their ids reused)
        ids = tuple(map(id, curves))
        others_kept = curves_sharing_knots(6, False, 6)
        kept = ([shared_knots._Group(np.arange(6), others_kept)], [])
        shared_knots._KEPT.get()[ids] = (tuple(others_kept), kept)
        again, others = shared_knots._partition(curves)
        assert sorted(group.members.tolist() for group in again) == [[0, 1, 2], [4, 5]] and others == [3]
        assert all(group.curves == [curves[i] for i in group.members] for group in again)


def test_partitions_are_kept_only_inside_a_block_and_dropped_with_it():
    from torsal.nodes.geometry.curves import shared_knots

    curves = curves_sharing_knots(4, False, 3)
    assert shared_knots._partition(curves)[0] is not shared_knots._partition(curves)[0]  # (none kept)
    with shared_knots.partitions_kept():
        kept = shared_knots._partition(curves)[0]
        with shared_knots.partitions_kept():  # (nested: the outer block's)
            assert shared_knots._partition(curves)[0] is kept
    assert shared_knots._KEPT.get() is None


@pytest.mark.parametrize("degree", [1, 2, 3, 5])
def test_polynomial_curves_made_together_are_the_curves_set_up_alone_bit_for_bit(degree):
    # far from the origin, flat on z = 0 or z = -0.0 (the sign of a zero box survives), and
    # some closed (their first and last control points one point)
    rng = np.random.default_rng(degree)
    points = rng.normal(size=(12, degree + 1, 3)) * 10.0 + 1e6 * rng.normal(size=(12, 1, 3))
    points[:3, :, 2], points[3:5, :, 2] = 0.0, -0.0
    if degree > 1:
        points[5:7, -1] = points[5:7, 0]
    knots = np.repeat([0.0, 1.0], degree + 1)
    for together, row in zip(polynomial_curves(NurbsCurve, points, knots, degree), points, strict=True):
        alone = NurbsCurve(row, degree, knots)
        for name in ("control_points", "knots", "weights", "_anchor", "_coefficients", "end_points"):
            mine, theirs = getattr(together, name), getattr(alone, name)
            assert mine.tobytes() == theirs.tobytes() and mine.shape == theirs.shape, name
            assert mine.flags.writeable == theirs.flags.writeable, name
        for name in ("degree", "domain", "closed", "is_rational", "periodic"):
            assert getattr(together, name) == getattr(alone, name), name
        t = np.linspace(-0.1, 1.1, 9)
        for mine, theirs in zip(together.derivatives(t, 3), alone.derivatives(t, 3), strict=True):
            assert mine.tobytes() == theirs.tobytes()
    assert sum(curve.closed for curve in polynomial_curves(NurbsCurve, points, knots, degree)) == (
        2 if degree > 1 else 0)
