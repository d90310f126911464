"""Surface.bounding_box (nodes/geometry/surface_box.py): each extreme found where it is, at a
corner, on an edge or inside, at the origin and at site coordinates.

Expected boxes are closed forms, or an independent search: scipy's ``NdBSpline`` evaluating
the B-spline surface on a dense grid, polished by ``minimize_scalar`` along each edge and
Nelder–Mead inside, in coordinates about the surface."""

from __future__ import annotations

import numpy as np
import pytest
from scipy import interpolate, optimize

from torsal.nodes.geometry.nurbs_surface import NurbsSurface
from torsal.nodes.geometry.parametric_surface import ParametricSurface
from torsal.nodes.geometry.ruled import RuledSurface

OFFSETS = [(0.0, 0.0, 0.0), (1e6, 2e6, 300.0), (1e9, 1e9, 1e9)]


def _rounding(offset) -> float:
    """A few ulps of the largest coordinate: how well a position is known there."""
    return 4 * float(np.spacing(max(abs(c) for c in offset) or 1.0))


def _helicoid(offset, turn: float = 4.0) -> ParametricSurface:
    """(v cos u, v sin u, 0.4 u) for u in [0, turn], v in [0.3, 1.7], moved by ``offset``."""
    ox, oy, oz = offset
    return ParametricSurface(
        lambda u, v: (ox + v * np.cos(u), oy + v * np.sin(u), oz + 0.4 * u),
        (0.0, turn), (0.3, 1.7),
        first_derivatives=lambda u, v: ((-v * np.sin(u), v * np.cos(u), 0.4 + 0 * u),
                                        (np.cos(u), np.sin(u), 0 * u)),
        second_derivatives=lambda u, v: ((-v * np.cos(u), -v * np.sin(u), 0 * u),
                                         (-np.sin(u), np.cos(u), 0 * u), (0 * u, 0 * u, 0 * u)),
    )


@pytest.mark.parametrize("offset", OFFSETS)
def test_a_helicoids_box_is_its_closed_form_wherever_it_is(offset):
    # x = v cos u is least at u = π inside edge v = 1.7 and greatest at the corner u = 0;
    # y = v sin u greatest at u = π/2 on that edge, least at the corner (4, 1.7)
    expected = np.array([[-1.7, 1.7 * np.sin(4.0), 0.0], [1.7, 1.7, 1.6]]) + offset
    box = _helicoid(offset).bounding_box()
    np.testing.assert_allclose(box, expected, rtol=0, atol=1e-12 * 3.4 + _rounding(offset))


def _shallow(offset, k: float = 1e-3, u0: float = 0.4137) -> ParametricSurface:
    """A ruled sheet whose x is least along edge v = 0 at u0, where it changes by k·δu²: a
    coordinate that moves 1e-8 m within 3e-3 of u0."""
    ox, oy, oz = offset
    return ParametricSurface(
        lambda u, v: (ox + 2 + k * (u - u0) ** 2 + 1.5 * v, oy + 6 * u, oz + 3 * v + 0.2 * u * u),
        first_derivatives=lambda u, v: ((2 * k * (u - u0), 6 + 0 * u, 0.4 * u),
                                        (1.5 + 0 * u, 0 * u, 3 + 0 * u)),
        second_derivatives=lambda u, v: ((2 * k + 0 * u, 0 * u, 0.4 + 0 * u), (0 * u,) * 3, (0 * u,) * 3),
    )


@pytest.mark.parametrize("offset", OFFSETS)
def test_a_shallow_extreme_on_an_edge_is_found_to_the_rounding_of_its_position(offset):
    # (a descent on the world coordinate stopped 5.5e-8 m short of it at 1e6 m)
    box = _shallow(offset).bounding_box()
    assert abs(box[0, 0] - (offset[0] + 2.0)) <= _rounding(offset)
    expected_max = np.array([2 + 1e-3 * 0.5863**2 + 1.5, 6.0, 3.2]) + offset
    np.testing.assert_allclose(box[1], expected_max, rtol=0, atol=1e-12 * 7 + _rounding(offset))


def _dome(offset) -> ParametricSurface:
    """z = 1 − (x − 0.3)² − 2(y + 0.2)² + 0.5xy over [−2, 2]²: greatest inside."""
    ox, oy, oz = offset

    def height(x, y):
        return 1 - (x - 0.3) ** 2 - 2 * (y + 0.2) ** 2 + 0.5 * x * y

    return ParametricSurface(
        lambda x, y: (ox + x, oy + y, oz + height(x, y)), (-2.0, 2.0), (-2.0, 2.0),
        first_derivatives=lambda x, y: ((1 + 0 * x, 0 * x, -2 * (x - 0.3) + 0.5 * y),
                                        (0 * x, 1 + 0 * x, -4 * (y + 0.2) + 0.5 * x)),
        second_derivatives=lambda x, y: ((0 * x, 0 * x, -2 + 0 * x), (0 * x, 0 * x, 0.5 + 0 * x),
                                         (0 * x, 0 * x, -4 + 0 * x)),
    ), height


@pytest.mark.parametrize("offset", OFFSETS)
def test_an_extreme_inside_is_where_both_derivatives_vanish(offset):
    surface, height = _dome(offset)
    top = np.linalg.solve([[-2.0, 0.5], [0.5, -4.0]], [-0.6, 0.8])  # ∇z = 0
    corners = [height(x, y) for x in (-2, 2) for y in (-2, 2)]  # z is concave: least at a corner
    expected = np.array([[-2, -2, min(corners)], [2, 2, height(*top)]]) + offset
    box = surface.bounding_box(samples=7)  # the top lies between samples
    np.testing.assert_allclose(box, expected, rtol=0, atol=1e-12 * 10 + _rounding(offset))


def test_a_polyline_strips_box_is_that_of_its_vertices_far_out():
    rng = np.random.default_rng(5)
    t = np.linspace(0.0, 3.0, 400)
    starts = np.column_stack([t, np.sin(3 * t), 0.1 * rng.standard_normal(len(t))]) + 1e6
    ends = starts + [0.2, 0.0, 1.0] + 0.05 * rng.standard_normal((len(t), 3))
    box = RuledSurface.from_rulings(starts, ends, degree=1).bounding_box()
    vertices = np.vstack([starts, ends])
    np.testing.assert_allclose(box, [vertices.min(axis=0), vertices.max(axis=0)], rtol=0,
                               atol=_rounding((1e6,)))


def _independent_box(tensor, size: float) -> np.ndarray:
    """The box of a B-spline surface by scipy: a 601² grid, then each extreme polished along
    the edges (minimize_scalar) and inside (Nelder–Mead), values about the surface's centre."""
    grid = np.linspace(0.0, 1.0, 601)
    uu, vv = np.meshgrid(grid, grid, indexing="ij")
    points = tensor(np.column_stack([uu.ravel(), vv.ravel()]))
    centre = 0.5 * (points.min(axis=0) + points.max(axis=0))
    box = np.empty((2, 3))
    for axis in range(3):
        for row, sign in ((0, 1.0), (1, -1.0)):

            def value(u, v, axis=axis, sign=sign):
                return sign * (tensor(np.array([[u, v]]))[0, axis] - centre[axis]) / size

            best = sign * (points[:, axis] - centre[axis]) / size
            found = [best.min()]
            for fixed, along in (("u", 0.0), ("u", 1.0), ("v", 0.0), ("v", 1.0)):
                line = best.reshape(601, 601)[:, int(along) * 600] if fixed == "v" else \
                    best.reshape(601, 601)[int(along) * 600]
                k = int(np.argmin(line))
                bracket = (grid[max(k - 1, 0)], grid[min(k + 1, 600)])
                f = (lambda s, a=along: value(s, a)) if fixed == "v" else (lambda s, a=along: value(a, s))
                found.append(optimize.minimize_scalar(f, bounds=bracket, method="bounded",
                                                      options={"xatol": 1e-13}).fun)
            k = int(np.argmin(best))
            inside = optimize.minimize(lambda x: value(*np.clip(x, 0.0, 1.0)), [uu.ravel()[k], vv.ravel()[k]],
                                       method="Nelder-Mead", options={"xatol": 1e-13, "fatol": 1e-16})
            found.append(inside.fun)
            box[row, axis] = centre[axis] + sign * size * min(found)
    return box


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_a_random_bicubic_patchs_box_agrees_with_an_independent_search(seed):
    rng = np.random.default_rng(seed)
    grid = np.stack(np.meshgrid(np.arange(6.0), np.arange(6.0), indexing="ij"), axis=-1)
    net = np.concatenate([grid, rng.uniform(-1.5, 1.5, (6, 6, 1))], axis=2) + rng.normal(0.0, 0.4, (6, 6, 3))
    surface = NurbsSurface(net, 3, 3)
    knots = np.r_[0.0, 0.0, 0.0, 0.0, 1 / 3, 2 / 3, 1.0, 1.0, 1.0, 1.0]
    np.testing.assert_allclose(surface.knots_u, knots)
    tensor = interpolate.NdBSpline((knots, knots), net, (3, 3))
    size = float(np.linalg.norm(np.ptp(net.reshape(-1, 3), axis=0)))
    expected = _independent_box(tensor, size)
    np.testing.assert_allclose(surface.bounding_box(), expected, rtol=0, atol=1e-10 * size)
    site = np.array([1e6, 2e6, 300.0])
    moved = NurbsSurface(net + site, 3, 3)
    np.testing.assert_allclose(moved.bounding_box() - site, expected, rtol=0,
                               atol=1e-10 * size + _rounding((2e6,)))
