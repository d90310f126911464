"""developable.Rationalise with Guides: the strips follow curves the designer draws.

The designs and the independent checks (Newton distance to the height field, triple
products with the design's exact tangents) are those of ``test_rationalise.py``; the
guides are curves written here in closed form, lying on the design: (x(y), y, f(x, y)).
"""

from __future__ import annotations

import itertools
from functools import cache

import numpy as np
import pytest
from scipy.interpolate import CubicSpline
from scipy.spatial import cKDTree

from tests.nodes.developable.test_rationalise import DOME, HALF, SIZE, TOL, WAVE, distance_to, grid, items
from tests.support.node_helpers import run, texts, tree
from torsal.nodes.developable.rationalise import Rationalise
from torsal.nodes.geometry.curves import InterpolatedCurve


def guide_on(field, across_of, start: float = -HALF, end: float = HALF, count: int = 201, along: int = 1):
    """The curve on ``field`` whose coordinate ``along`` (1: y, 0: x) runs from ``start`` to
    ``end`` and whose other one is ``across_of`` it, through ``count`` points; and those points."""
    t = np.linspace(start, end, count)
    x, y = (across_of(t), t) if along == 1 else (t, across_of(t))
    points = np.column_stack([x, y, field.f(x, y)])
    return InterpolatedCurve(points), points


#: The guides run across the design's more curved direction, so that the rulings, which
#: run across the strips, lie along the flatter one (the wave bends six times more in x
#: than in y: its guides run along x; the dome bends alike both ways).
ALONG = {"dome": 1, "wave": 0}


def wiggle(t):
    return 0.8 * np.sin(0.4 * t) + 0.5


def second(t):
    return -2.5 + 0.3 * np.cos(0.4 * t)


@cache
def guided(name: str):
    field = {"dome": DOME, "wave": WAVE}[name]
    curves = [guide_on(field, wiggle, along=ALONG[name])[0], guide_on(field, second, along=ALONG[name])[0]]
    result = run(Rationalise(), Surface=tree({(0,): [field.surface()]}), Tolerance=TOL, MaxStrips=40,
                 Guides=tree({(0,): curves}))
    assert result.state == "ok", texts(result)
    return result


def dense(curve, count: int = 2001) -> np.ndarray:
    return curve.point_at(np.linspace(0.0, 1.0, count))


@pytest.mark.parametrize("name", ["dome", "wave"])
def test_a_boundary_runs_along_each_guide(name):
    field = {"dome": DOME, "wave": WAVE}[name]
    boundaries = items(guided(name), "Boundaries")
    for x_of_y in (wiggle, second):
        _, points = guide_on(field, x_of_y, count=1001, along=ALONG[name])
        # the guide's points against the nearest boundary, sampled 4 mm apart
        gaps = [cKDTree(dense(b)).query(points)[0].max() for b in boundaries]
        # 65 projected samples interpolated by a cubic: ~h^4 |x''''| / 384 (h = 0.16 m),
        # plus the sampling's chord sagitta: measured 1.6e-4 and 3e-5 m
        assert min(gaps) <= 5e-4


@pytest.mark.parametrize("name", ["dome", "wave"])
def test_guided_strips_lie_within_the_tolerance_of_the_design(name):
    field = {"dome": DOME, "wave": WAVE}[name]
    worst = max(distance_to(field, grid(s).reshape(-1, 3)).max() for s in items(guided(name), "Strips"))
    assert worst <= TOL * 1.001


@pytest.mark.parametrize("name", ["dome", "wave"])
def test_guided_strips_are_torsal_by_the_triple_product_with_the_boundaries_tangents(name):
    result = guided(name)
    rulings, kinds = items(result, "Rulings"), items(result, "Kind")
    boundaries = items(result, "Boundaries")
    torsal = [r for r, k in zip(rulings, kinds, strict=True) if k == "torsal"]
    # the rest close the strips' ends at the design's edges (smooth cones, reported):
    # measured 85 % torsal on the wave, 93 % on the dome
    assert len(torsal) >= 0.8 * len(rulings)
    samples = [dense(b, 4001) for b in boundaries]
    trees = [cKDTree(s) for s in samples]

    def tangents(line):  # second-order differences: central inside, one-sided at the ends
        inner = line[2:] - line[:-2]
        first, last = -3 * line[0] + 4 * line[1] - line[2], 3 * line[-1] - 4 * line[-2] + line[-3]
        return np.vstack([first, inner, last])

    spans = [tangents(line) for line in samples]

    def tangent(p):
        """The tangent of the boundary through p: its dense samples' differences,
        interpolated linearly to the foot of p on the segment it lies on."""
        best = int(np.argmin([t.query(p)[0] for t in trees]))
        line, along = samples[best], spans[best]
        i = int(trees[best].query(p)[1])
        j = i - 1 if i > 0 and (i == len(line) - 1 or np.dot(p - line[i], line[i + 1] - line[i]) < 0) else i
        step = line[j + 1] - line[j]
        f = float(np.clip(np.dot(p - line[j], step) / np.dot(step, step), 0.0, 1.0))
        return (1 - f) * along[j] + f * along[j + 1]

    a = np.array([r.start for r in torsal], dtype=float)
    b = np.array([r.end for r in torsal], dtype=float)
    ta, tb = np.array([tangent(p) for p in a]), np.array([tangent(p) for p in b])
    n1, n2 = np.cross(b - a, ta), np.cross(b - a, tb)
    warp = np.arctan2(np.linalg.norm(np.cross(n1, n2), axis=1), np.einsum("ij,ij->i", n1, n2))
    # central differences of samples 2.5 mm apart turn the tangent by ~h^2 |C'''| / 6:
    # about 1e-6 rad here, far above the node's 1e-14; measured 2.4e-7
    assert warp.max() < 2e-6


@pytest.mark.parametrize("name", ["dome", "wave"])
def test_guided_neighbours_share_their_boundary(name):
    """The edges of two neighbours along a boundary meet at both ends, lie on the design
    and are one curve, across = X(along): the upper's edge, sampled 5 mm apart and
    interpolated by a cubic spline (error ~h^4 |X''''| / 384, about 1e-12 m here)."""
    field, along = {"dome": DOME, "wave": WAVE}[name], ALONG[name]
    strips = items(guided(name), "Strips")
    assert len(strips) >= 4
    for lower, upper in itertools.pairwise(strips):
        top, bottom = grid(lower, 2001, 2)[:, -1], grid(upper, 2001, 2)[:, 0]
        assert np.abs(top[[0, -1]] - bottom[[0, -1]]).max() <= 1e-9 * SIZE
        for edge in (top, bottom):
            assert np.abs(edge[:, 2] - field.f(edge[:, 0], edge[:, 1])).max() <= 1e-9 * SIZE
        keys, first = np.unique(bottom[:, along], return_index=True)  # (a tip repeats its point)
        same = CubicSpline(keys, bottom[first, 1 - along])
        assert np.abs(same(top[:, along]) - top[:, 1 - along]).max() <= 1e-9 * SIZE


def test_a_guide_that_stops_short_of_the_edges_is_refused_naming_guides():
    curve, _ = guide_on(DOME, wiggle, -HALF, 0.0)
    result = run(Rationalise(), Surface=tree({(0,): [DOME.surface()]}), Tolerance=TOL, MaxStrips=40,
                 Guides=tree({(0,): [curve]}))
    assert result.state == "warning"
    assert any(t.startswith("Guides:") and "edge to edge" in t for t in texts(result))


def test_crossing_guides_are_refused_naming_them():
    curves = [guide_on(DOME, lambda y: 0.4 * y)[0], guide_on(DOME, lambda y: -0.4 * y)[0]]
    result = run(Rationalise(), Surface=tree({(0,): [DOME.surface()]}), Tolerance=TOL, MaxStrips=40,
                 Guides=tree({(0,): curves}))
    assert result.state == "warning"
    assert any("guides 1 and 2 cross" in t for t in texts(result)), texts(result)
