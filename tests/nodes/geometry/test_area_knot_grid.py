"""A bumpy NURBS surface's area: the adaptive cubature starts from the knot grid, and stops
when cancelled.

A 24 × 24 bicubic net with random heights is bumpy enough that the 8- and 12-point rules
per knot span disagree, so the adaptive cubature decides. On power-of-two cells (which
straddle the knots, where the area element is not smooth) it took 8–55 s and was 9e-11
off; started from the knot grid it agrees with the reference to rounding. The reference
is independent of the code under test: scipy's ``NdBSpline`` gives the derivatives and a
20-point Gauss–Legendre product rule on each quarter of every knot span integrates them
(the element is smooth inside a span). How fast: tests/benchmarks/bench_kernels.py.
"""

from __future__ import annotations

import itertools
import threading
import time

import numpy as np
import pytest
from scipy.interpolate import NdBSpline

from torsal.engine.node import Cancelled
from torsal.nodes.geometry.area import integrate_unit_square, watched
from torsal.nodes.geometry.nurbs_surface import NurbsSurface, clamped_knots
from torsal.nodes.surfaces.analysis import Area


def bumpy_net(n: int, seed: int = 7) -> np.ndarray:
    """An n × n net over a 10 × 10 square, heights random with deviation 0.6."""
    rng = np.random.default_rng(seed)
    x, y = np.meshgrid(np.linspace(0, 10, n), np.linspace(0, 10, n), indexing="ij")
    return np.stack([x, y, 0.6 * rng.standard_normal((n, n))], axis=-1)


def reference_area(net: np.ndarray, order: int = 16, parts: int = 2) -> float:
    """Area by scipy's tensor B-spline and a dense Gauss product on sub-spans of the knots."""
    n = net.shape[0]
    knots = clamped_knots(n, 3)
    spline = NdBSpline((knots, knots), net, 3)
    breaks = np.unique(knots)
    fine = np.unique(np.concatenate([np.linspace(a, b, parts + 1) for a, b in itertools.pairwise(breaks)]))
    x, w = np.polynomial.legendre.leggauss(order)
    width = np.diff(fine)[:, None]
    nodes = (fine[:-1, None] + width * (x + 1) / 2).ravel()
    weights = (width * w / 2).ravel()
    uu, vv = np.meshgrid(nodes, nodes, indexing="ij")
    xi = np.column_stack([uu.ravel(), vv.ravel()])
    su, sv = spline(xi, nu=(1, 0)), spline(xi, nu=(0, 1))
    return float((np.linalg.norm(np.cross(su, sv), axis=1) * np.outer(weights, weights).ravel()).sum())


def test_bumpy_bicubic_surface_area_matches_a_dense_scipy_reference_to_1e_12():
    # measured 2e-14; the power-of-two cells that ignored the knots were 9e-11 off
    net = bumpy_net(24)
    area = NurbsSurface(net, 3, 3).area()
    assert area == pytest.approx(reference_area(net), rel=1e-12)


def test_cubature_from_given_breaks_integrates_a_kinked_function_exactly():
    # |u − 0.3| · (1 + v) has a kink at u = 0.3; with a break there each cell is a polynomial
    exact = (0.3**2 / 2 + 0.7**2 / 2) * 1.5
    result = integrate_unit_square(lambda u, v: np.abs(u - 0.3) * (1 + v), breaks_u=[0.3], max_level=1)
    assert result[0] == pytest.approx(exact, rel=1e-14)


def test_cubature_reports_progress_rising_to_one():
    heard: list[float] = []
    integrate_unit_square(lambda u, v: np.sqrt(1 + u + v), progress=heard.append)
    assert heard and heard == sorted(heard) and heard[-1] == pytest.approx(1.0)


def test_watched_block_passes_its_check_to_a_surface_area():
    calls: list[int] = []
    with watched(lambda: calls.append(1)):
        NurbsSurface(bumpy_net(8), 3, 3).area()
    assert calls


def test_area_node_stops_when_its_token_is_cancelled():
    """A 48 × 48 bumpy surface's area takes seconds; cancelled after 0.2 s it stops well
    before (the 0.2 s bar is timed in bench_kernels.py; this bound is generous)."""
    node = Area()
    surface = NurbsSurface(bumpy_net(48), 3, 3)
    threading.Timer(0.2, node.token.cancel).start()
    started = time.perf_counter()
    with pytest.raises(Cancelled):
        node.solve(surface)
    assert time.perf_counter() - started < 2.0
