"""Curve kernel timings (``make bench``): evaluation, derivatives, closest point, division.

Each benchmark prints its time; the evaluation bar (10^6 NURBS points well under a
second) is asserted.
"""

from __future__ import annotations

import time
from collections.abc import Callable

import numpy as np

from nodes.geometry.curves import Circle, InterpolatedCurve, NurbsCurve

RNG = np.random.default_rng(0)
MILLION = np.linspace(0.0, 1.0, 1_000_000)
RATIONAL = NurbsCurve(RNG.uniform(-10, 10, (40, 3)), 3, weights=RNG.uniform(0.5, 2.0, 40))
POLYNOMIAL = NurbsCurve(RNG.uniform(-10, 10, (40, 3)), 3)


def best_of(function: Callable[[], object], repeat: int = 3) -> float:
    """Best wall time of ``repeat`` runs, in seconds."""
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        function()
        times.append(time.perf_counter() - start)
    return min(times)


def report(name: str, seconds: float) -> None:
    print(f"\n  {name:<58} {seconds * 1e3:9.1f} ms")


def test_bench_nurbs_evaluation_of_a_million_points_well_under_a_second():
    polynomial = best_of(lambda: POLYNOMIAL.point_at(MILLION))
    rational = best_of(lambda: RATIONAL.point_at(MILLION))
    report("10^6 points, polynomial cubic NURBS (40 control points)", polynomial)
    report("10^6 points, rational cubic NURBS (40 control points)", rational)
    assert rational < 0.5 and polynomial < 0.5


def test_bench_nurbs_second_derivatives_of_a_million_points():
    seconds = best_of(lambda: RATIONAL.derivatives(MILLION, 2))
    report("10^6 points + C' + C'', rational cubic NURBS", seconds)


def test_bench_curvature_and_torsion_of_a_hundred_thousand_points():
    t = MILLION[::10]
    report("10^5 curvatures, rational cubic NURBS", best_of(lambda: RATIONAL.curvature_at(t)))
    report("10^5 torsions, rational cubic NURBS", best_of(lambda: RATIONAL.torsion_at(t)))


def test_bench_closest_points_of_ten_thousand_queries():
    queries = RNG.uniform(-10, 10, (10_000, 3))
    report("10^4 closest points, rational cubic NURBS", best_of(lambda: RATIONAL.closest_point(queries)))
    circle = Circle(radius=3.0)
    report("10^4 closest points, circle", best_of(lambda: circle.closest_point(queries)))


def test_bench_length_table_and_division():
    report(
        "length table (fresh curve), rational cubic NURBS",
        best_of(lambda: NurbsCurve(RATIONAL.control_points, 3, weights=RATIONAL.weights).length),
    )
    report("divide_by_count(1000), rational cubic NURBS", best_of(lambda: RATIONAL.divide_by_count(1000)))


def test_bench_interpolation_through_ten_thousand_points():
    u = np.linspace(0, 40 * np.pi, 10_000)
    points = np.column_stack([np.cos(u), np.sin(u), 0.05 * u])
    report("interpolate 10^4 points (open)", best_of(lambda: InterpolatedCurve(points)))
    report("interpolate 10^4 points (closed)", best_of(lambda: InterpolatedCurve(points, closed=True)))


def test_bench_tessellation_to_a_micrometre():
    report("to_polyline(1e-6), rational cubic NURBS", best_of(lambda: RATIONAL.to_polyline(1e-6)))
