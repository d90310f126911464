"""Curve kernel timings (``make bench``): evaluation, derivatives, closest point, length,
division, interpolation and tessellation, each against a baseline measured in the same run.

Run alone with::

    .venv/bin/python -m pytest tests/benchmarks/bench_curves.py -s

Every baseline is plain scipy and numpy doing the same job to the same accuracy, with
nothing of the kernel but the curve's arrays (knots, control points, weights): scipy's
``BSpline`` on the weighted control points and the quotient rule for a NURBS curve, a
k-d tree and Newton's method for closest points, Gauss–Legendre rules for lengths,
``make_interp_spline`` for interpolation. Where a baseline's work depends on how accurate
it must be (lengths, tessellation), the cheapest rule or sampling that is as accurate is
searched for in the run, knowing the answer. The kernel wraps scipy, so the ratios say
what its bookkeeping costs (anchoring, checks, the quotient rule in general form): the
bars are about twice the ratios measured (0.85–1.9×; interpolation 1.6–3.1×). Two
findings stood out and are fixed: a circle's closest points took the generic search, 68×
its closed form (Circle and Arc now have the closed form), and the closest points of a
rational cubic missed the nearest stretch of the curve for about 3 % of random queries
(the test below compares them with the baseline; tests/nodes/geometry/curves/test_curve_closest_point.py
with brute force).
"""

from __future__ import annotations

import time
from collections.abc import Callable
from itertools import pairwise
from math import comb

import numpy as np
from scipy.integrate import quad
from scipy.interpolate import BSpline, make_interp_spline
from scipy.spatial import cKDTree

from tests.benchmarks.timing import ratio_to_baseline
from torsal.nodes.geometry.curves import Circle, InterpolatedCurve, NurbsCurve, Polyline

RNG = np.random.default_rng(0)
MILLION = np.linspace(0.0, 1.0, 1_000_000)
RATIONAL = NurbsCurve(RNG.uniform(-10, 10, (40, 3)), 3, weights=RNG.uniform(0.5, 2.0, 40))
POLYNOMIAL = NurbsCurve(RNG.uniform(-10, 10, (40, 3)), 3)
REPEATS = 7


# --------------------------------------------------------------------------- the baselines


def homogeneous(curve: NurbsCurve) -> BSpline:
    """scipy's B-spline of the weighted control points and the weights: (w·P, w)."""
    w = np.asarray(curve.weights)
    return BSpline(curve.knots, np.column_stack([curve.control_points * w[:, None], w]), curve.degree)


def knot_parameters(curve: NurbsCurve, t: np.ndarray) -> tuple[np.ndarray, float]:
    a, b = curve.domain
    return a + (b - a) * t, b - a


def scipy_derivatives(spline: BSpline, curve: NurbsCurve, t: np.ndarray, order: int) -> list[np.ndarray]:
    """C, C', …, C^(order) with respect to t, by the quotient rule on ``homogeneous(curve)``."""
    u, scale = knot_parameters(curve, t)
    h = [spline(u, nu=k) for k in range(order + 1)]
    w = [x[:, 3:] for x in h]
    result: list[np.ndarray] = []
    for k in range(order + 1):
        numerator = h[k][:, :3].copy()
        for i in range(1, k + 1):
            numerator -= comb(k, i) * w[i] * result[k - i]
        result.append(numerator / w[0])
    return [c * scale**k for k, c in enumerate(result)]


def scipy_closest(spline: BSpline, curve: NurbsCurve, queries: np.ndarray, samples: int) -> np.ndarray:
    """Distances from a k-d tree of ``samples`` points, then Newton on (C − P)·C' = 0."""
    grid = np.linspace(0.0, 1.0, samples)
    (points,) = scipy_derivatives(spline, curve, grid, 0)
    _, nearest = cKDTree(points).query(queries)
    start = grid[nearest]
    low, high = np.maximum(start - grid[1], 0.0), np.minimum(start + grid[1], 1.0)  # the sample's bracket
    t = start
    for _ in range(6):
        c, d1, d2 = scipy_derivatives(spline, curve, t, 2)
        gap = c - queries
        slope = np.einsum("ij,ij->i", d1, d1) + np.einsum("ij,ij->i", gap, d2)
        step = np.where(slope > 0, np.einsum("ij,ij->i", gap, d1) / np.where(slope > 0, slope, 1.0), 0.0)
        t = np.clip(t - step, low, high)
    (c,) = scipy_derivatives(spline, curve, t, 0)
    return np.minimum(np.linalg.norm(c - queries, axis=1), np.linalg.norm(points[nearest] - queries, axis=1))


def gauss_length(curve: NurbsCurve, nodes: int, pieces: int = 1) -> float:
    """The length by a ``nodes``-point Gauss–Legendre rule on ``pieces`` parts of each knot span."""
    spline = homogeneous(curve)
    a, b = curve.domain
    knots = np.unique(curve.knots[(curve.knots >= a) & (curve.knots <= b)])
    edges = np.interp(np.linspace(0, len(knots) - 1, (len(knots) - 1) * pieces + 1),
                      np.arange(len(knots)), knots)
    x, weights = np.polynomial.legendre.leggauss(nodes)
    mid, half = (edges[1:] + edges[:-1]) / 2, (edges[1:] - edges[:-1]) / 2
    u = (mid[:, None] + half[:, None] * x[None, :]).ravel()
    _, d1 = scipy_derivatives(spline, curve, (u - a) / (b - a), 1)
    speed = np.linalg.norm(d1, axis=1).reshape(len(mid), nodes) / (b - a)
    return float((speed @ weights * half).sum())


def reference_length(curve: NurbsCurve) -> float:
    """The length by scipy's adaptive quadrature, span by span, to 1e-14."""
    spline = homogeneous(curve)
    a, b = curve.domain
    knots = np.unique(curve.knots[(curve.knots >= a) & (curve.knots <= b)])

    def speed(u: float) -> float:
        _, d1 = scipy_derivatives(spline, curve, np.array([(u - a) / (b - a)]), 1)
        return float(np.linalg.norm(d1)) / (b - a)

    return sum(quad(speed, lo, hi, epsabs=0.0, epsrel=2e-14, limit=200)[0] for lo, hi in pairwise(knots))


def loops_for(function: Callable[[], object], seconds: float = 0.01) -> int:
    """How many calls of ``function`` take about ``seconds`` (sub-millisecond calls vary too
    much on a loaded machine to be timed one by one)."""
    started = time.perf_counter()
    function()
    return max(1, round(seconds / max(time.perf_counter() - started, 1e-9)))


def timed_against(what: str, work: Callable[[], object], baseline: str, reference: Callable[[], object],
                  bar: float) -> float:
    loops = loops_for(reference)
    ratio = ratio_to_baseline(
        f"{what} (× {loops})" if loops > 1 else what,
        (lambda: [work() for _ in range(loops)]) if loops > 1 else work,
        baseline,
        (lambda: [reference() for _ in range(loops)]) if loops > 1 else reference,
        REPEATS,
    )
    assert ratio <= bar
    return ratio


# --------------------------------------------------------------------------- the benchmarks


def test_bench_polynomial_nurbs_evaluation_of_a_million_points_within_2x_scipy():
    spline = BSpline(POLYNOMIAL.knots, POLYNOMIAL.control_points, POLYNOMIAL.degree)
    u, _ = knot_parameters(POLYNOMIAL, MILLION)
    assert np.abs(POLYNOMIAL.point_at(MILLION) - spline(u)).max() < 1e-12 * 20
    timed_against("10^6 points, polynomial cubic NURBS (40 control points)",
                  lambda: POLYNOMIAL.point_at(MILLION), "scipy BSpline on the control points",
                  lambda: spline(knot_parameters(POLYNOMIAL, MILLION)[0]), 2.0)


def test_bench_rational_nurbs_evaluation_of_a_million_points_within_2x_scipy():
    spline = homogeneous(RATIONAL)
    (reference,) = scipy_derivatives(spline, RATIONAL, MILLION, 0)
    assert np.abs(RATIONAL.point_at(MILLION) - reference).max() < 1e-12 * 20
    timed_against("10^6 points, rational cubic NURBS (40 control points)", lambda: RATIONAL.point_at(MILLION),
                  "scipy BSpline on (w·P, w), divided by w",
                  lambda: scipy_derivatives(spline, RATIONAL, MILLION, 0), 2.0)


def test_bench_nurbs_second_derivatives_of_a_million_points_within_2x_scipy():
    spline = homogeneous(RATIONAL)
    timed_against("10^6 points + C' + C'', rational cubic NURBS", lambda: RATIONAL.derivatives(MILLION, 2),
                  "scipy BSpline derivatives and the quotient rule",
                  lambda: scipy_derivatives(spline, RATIONAL, MILLION, 2), 2.0)


def test_bench_curvature_and_torsion_of_a_hundred_thousand_points_within_2x_scipy():
    t = MILLION[::10]
    spline = homogeneous(RATIONAL)

    def curvature() -> np.ndarray:
        _, d1, d2 = scipy_derivatives(spline, RATIONAL, t, 2)
        return np.linalg.norm(np.cross(d1, d2), axis=1) / np.linalg.norm(d1, axis=1) ** 3

    def torsion() -> np.ndarray:
        _, d1, d2, d3 = scipy_derivatives(spline, RATIONAL, t, 3)
        b = np.cross(d1, d2)
        return np.einsum("ij,ij->i", b, d3) / np.einsum("ij,ij->i", b, b)

    assert np.abs(RATIONAL.curvature_at(t) / curvature() - 1).max() < 1e-9
    assert np.abs(RATIONAL.torsion_at(t) - torsion()).max() < 1e-9 * np.abs(torsion()).max()
    timed_against("10^5 curvatures, rational cubic NURBS", lambda: RATIONAL.curvature_at(t),
                  "|C' × C''| / |C'|³ from scipy's derivatives", curvature, 2.0)
    timed_against("10^5 torsions, rational cubic NURBS", lambda: RATIONAL.torsion_at(t),
                  "(C' × C'')·C''' / |C' × C''|² from scipy's derivatives", torsion, 2.5)


QUERIES = np.random.default_rng(1).uniform(-10, 10, (10_000, 3))


def test_bench_closest_points_of_ten_thousand_queries_within_3x_a_kd_tree_and_newton():
    spline = homogeneous(RATIONAL)
    timed_against("10^4 closest points, rational cubic NURBS", lambda: RATIONAL.closest_point(QUERIES),
                  "k-d tree of 4,000 scipy samples, 6 Newton steps in the sample's bracket",
                  lambda: scipy_closest(spline, RATIONAL, QUERIES, 4000), 3.0)


def test_closest_points_are_as_close_as_the_baselines():
    """The kernel's distances are no larger than a brute-force search's over 2·10⁶ samples
    (an upper bound on the true distance: measured 0 to −5.2e-7 on the first 500 queries)
    nor than the k-d tree baseline's (which misses a nearer stretch for one of those 500,
    by 0.124; the kernel is then the closer)."""
    spline = homogeneous(RATIONAL)
    dense = np.linspace(0.0, 1.0, 2_000_001)
    (points,) = scipy_derivatives(spline, RATIONAL, dense, 0)
    brute, _ = cKDTree(points).query(QUERIES[:500])
    ours = RATIONAL.closest_point(QUERIES).distances
    assert np.all(ours[:500] <= brute + 1e-12)
    assert np.all(ours - scipy_closest(spline, RATIONAL, QUERIES, 4000) < 1e-9)


def test_bench_closest_points_on_a_circle_within_12x_the_closed_form():
    """Measured 63–67× when Circle took the generic search of any curve (samples, a k-d
    tree, Newton); with its closed form (the plane's frame, the angle, its parameter, the
    distances) 4.9×."""
    queries = RNG.uniform(-10, 10, (10_000, 3))
    circle = Circle(radius=3.0)

    def closed_form() -> np.ndarray:
        flat = queries[:, :2] / np.linalg.norm(queries[:, :2], axis=1, keepdims=True)
        return np.column_stack([3.0 * flat, np.zeros(len(queries))])

    assert np.abs(circle.closest_point(queries).points - closed_form()).max() < 1e-12
    timed_against("10^4 closest points, circle", lambda: circle.closest_point(queries),
                  "the projection 3·(x, y)/|(x, y)|", closed_form, 12.0)


def test_bench_length_within_3x_the_cheapest_gauss_rule_as_accurate():
    exact = reference_length(RATIONAL)

    def fresh() -> float:
        return NurbsCurve(RATIONAL.control_points, 3, weights=RATIONAL.weights).length

    error = abs(fresh() - exact) / exact
    rule = next((n, p) for p in (1, 2, 4, 8, 16) for n in range(2, 21)
                if abs(gauss_length(RATIONAL, n, p) - exact) / exact <= max(error, 1e-14))
    print(f"\n  length error {error:.1e}; the cheapest Gauss rule as accurate: {rule[0]} points, "
          f"{rule[1]} part(s) a span")
    timed_against("length table (fresh curve), rational cubic NURBS", fresh,
                  f"Gauss–Legendre, {rule[0]} points on {rule[1]} part(s) of each span",
                  lambda: gauss_length(RATIONAL, *rule), 3.0)


def piece_lengths(spline: BSpline, t: np.ndarray, nodes: int, parts: int) -> np.ndarray:
    """The lengths of the pieces between parameters ``t``, by a ``nodes``-point Gauss rule on
    ``parts`` equal parts of each piece, split first at the knots (where the speed is only
    twice differentiable)."""
    a, b = RATIONAL.domain
    knots = (np.unique(RATIONAL.knots[(RATIONAL.knots > a) & (RATIONAL.knots < b)]) - a) / (b - a)
    cuts = np.union1d(t, knots)
    edges = np.interp(np.linspace(0, len(cuts) - 1, (len(cuts) - 1) * parts + 1), np.arange(len(cuts)), cuts)
    x, weights = np.polynomial.legendre.leggauss(nodes)
    mid, half = (edges[1:] + edges[:-1]) / 2, (edges[1:] - edges[:-1]) / 2
    _, d1 = scipy_derivatives(spline, RATIONAL, (mid[:, None] + half[:, None] * x).ravel(), 1)
    lengths = np.linalg.norm(d1, axis=1).reshape(len(mid), nodes) @ weights * half
    return np.add.reduceat(lengths, np.searchsorted(edges, t[:-1]))


def test_bench_division_within_4x_its_points_and_the_lengths_that_check_it():
    """Dividing into 1000 equal pieces. The baseline does what checking a given division
    takes, without having to find it: evaluates its 1001 points and the 1000 pieces'
    lengths by the cheapest Gauss rule that agrees with scipy's adaptive quadrature to the
    division's own accuracy (searched for in the run)."""
    t = RATIONAL.divide_by_count(1000)
    spline = homogeneous(RATIONAL)

    def speed(x: float) -> float:
        _, d1 = scipy_derivatives(spline, RATIONAL, np.array([x]), 1)
        return float(np.linalg.norm(d1))

    exact = np.array([quad(speed, a, b, epsabs=0.0, epsrel=2e-14)[0] for a, b in pairwise(t)])
    spread = np.abs(exact / exact.mean() - 1).max()
    assert spread < 1e-10  # equal pieces (measured 2.3e-12)
    target = max(spread, 1e-13) * exact.mean()
    rule = next((n, p) for p in (1, 2, 4, 8, 16) for n in (4, 6, 8, 12, 16, 24, 32)
                if np.abs(piece_lengths(spline, t, n, p) - exact).max() <= target)
    print(f"\n  pieces equal to {spread:.1e}; the cheapest Gauss rule as accurate: {rule[0]} points on "
          f"{rule[1]} part(s) of each piece")

    def points_and_lengths() -> np.ndarray:
        scipy_derivatives(spline, RATIONAL, t, 0)
        return piece_lengths(spline, t, *rule)

    timed_against("divide_by_count(1000), rational cubic NURBS", lambda: RATIONAL.divide_by_count(1000),
                  f"its 1001 points and 1000 lengths ({rule[0]}-point Gauss on {rule[1]} part(s))",
                  points_and_lengths, 4.0)


def test_bench_interpolation_through_ten_thousand_points_within_6x_make_interp_spline():
    u = np.linspace(0, 40 * np.pi, 10_000)
    points = np.column_stack([np.cos(u), np.sin(u), 0.05 * u])
    chords = np.linalg.norm(np.diff(points, axis=0), axis=1)

    def open_spline() -> BSpline:
        parameters = np.concatenate([[0.0], np.cumsum(chords)]) / chords.sum()
        return make_interp_spline(parameters, points, k=3)

    def closed_spline() -> BSpline:
        loop = np.vstack([points, points[:1]])
        steps = np.linalg.norm(np.diff(loop, axis=0), axis=1)
        parameters = np.concatenate([[0.0], np.cumsum(steps)]) / steps.sum()
        return make_interp_spline(parameters, loop, k=3, bc_type="periodic")

    curve = InterpolatedCurve(points)
    assert np.abs(curve.point_at(curve.parameters) - points).max() < 1e-12
    timed_against("interpolate 10^4 points (open)", lambda: InterpolatedCurve(points),
                  "make_interp_spline on chord-length parameters", open_spline, 6.0)
    timed_against("interpolate 10^4 points (closed)", lambda: InterpolatedCurve(points, closed=True),
                  "make_interp_spline, periodic", closed_spline, 6.0)


def test_bench_tessellation_to_a_micrometre_within_5x_the_cheapest_uniform_sampling():
    spline = homogeneous(RATIONAL)

    def deviation(count: int) -> float:
        """The largest gap between the polyline through ``count`` uniform samples and the
        curve, at the middle of each chord (the gap of a short chord peaks there)."""
        t = np.linspace(0.0, 1.0, 2 * count - 1)
        (c,) = scipy_derivatives(spline, RATIONAL, t, 0)
        return float(np.linalg.norm(c[1::2] - (c[:-2:2] + c[2::2]) / 2, axis=1).max())

    low, high = 2, 2
    while deviation(high) > 1e-6:
        low, high = high, 2 * high
    while high - low > 1:
        middle = (low + high) // 2
        low, high = (middle, high) if deviation(middle) > 1e-6 else (low, middle)
    ours = len(Polyline.from_curve(RATIONAL, 1e-6).points)
    print(f"\n  Polyline.from_curve(1e-6): {ours} points; the fewest uniform samples within 1e-6: {high}")
    timed_against("Polyline.from_curve(1e-6), rational cubic NURBS",
                  lambda: Polyline.from_curve(RATIONAL, 1e-6),
                  f"{high} uniform samples by scipy",
                  lambda: scipy_derivatives(spline, RATIONAL, np.linspace(0.0, 1.0, high), 0), 5.0)
