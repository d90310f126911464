"""CurveOfRegression's kernel: the sharp edge of a developable from its rulings."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.optimize import minimize_scalar

from torsal.nodes.geometry.regression import closest_points_of_lines, curve_of_regression

R, H = 2.0, 0.5  # helix (R cos t, R sin t, H t)


def helix(t: np.ndarray) -> np.ndarray:
    return np.column_stack([R * np.cos(t), R * np.sin(t), H * t])


def helix_tangent(t: np.ndarray) -> np.ndarray:
    d = np.column_stack([-R * np.sin(t), R * np.cos(t), np.full_like(t, H)])
    return d / np.linalg.norm(d, axis=1, keepdims=True)


def distance_to_helix(points: np.ndarray, t_max: float) -> np.ndarray:
    def one(p):
        res = minimize_scalar(lambda s: float(np.sum((helix(np.array([s]))[0] - p) ** 2)),
                              bounds=(-0.5, t_max + 0.5), method="bounded", options={"xatol": 1e-12})
        return math.sqrt(res.fun)

    return np.array([one(p) for p in points])


def test_tangent_developable_of_a_helix_gives_back_the_helix_within_1e_3_at_200_segments():
    t = np.linspace(0.0, 2.0 * np.pi, 201)
    c, d = helix(t), helix_tangent(t)
    reg = curve_of_regression(c + 0.5 * d, c + 3.0 * d, deviation=0.01)  # rulings cut off the edge
    assert reg.kind == "curve" and len(reg.curves) == 1 and reg.valid.all()
    assert len(reg.curves[0]) == 201
    assert distance_to_helix(reg.points, 2.0 * np.pi).max() < 1e-3
    # by the helix's symmetry the inner points are the tangency points themselves
    assert np.abs(reg.points[1:-1] - c[1:-1]).max() < 1e-12


def test_regression_of_a_twisted_cubic_tangent_surface_converges_at_second_order():
    def curve(t):
        return np.column_stack([t, t**2, t**3])

    def tangent(t):
        d = np.column_stack([np.ones_like(t), 2 * t, 3 * t**2])
        return d / np.linalg.norm(d, axis=1, keepdims=True)

    errors = []
    for n in (40, 80):
        t = np.linspace(0.2, 1.2, n + 1) ** 1.3  # uneven stations
        reg = curve_of_regression(curve(t), curve(t) + 2.0 * tangent(t), deviation=0.01)
        assert reg.kind == "curve" and reg.valid.all()
        # distance of each point to the cubic, through the closest parameter
        dist = [minimize_scalar(lambda s, p=p: float(np.sum((curve(np.array([s]))[0] - p) ** 2)),
                                bounds=(0.0, 1.5), method="bounded",
                                options={"xatol": 1e-13}).fun ** 0.5 for p in reg.points]
        errors.append(max(dist))
    assert errors[0] < 1e-6
    assert errors[0] / errors[1] > 3.0


def test_cone_gives_its_apex_within_1e_9():
    phi = np.linspace(0.0, 2.0 * np.pi, 60)
    base = np.column_stack([np.cos(phi), 1.3 * np.sin(phi), 0.2 * np.cos(2 * phi)])
    apex = np.array([0.3, -0.2, 2.0])
    reg = curve_of_regression(base, base + 0.6 * (apex - base), deviation=0.01)  # stops short of it
    assert reg.kind == "apex" and not reg.has_curve
    assert np.linalg.norm(reg.apex - apex) < 1e-9
    assert "cone" in reg.message and reg.curves == []


def test_cylinder_has_no_curve_of_regression():
    phi = np.linspace(0.0, np.pi, 30)
    base = np.column_stack([np.cos(phi), np.sin(phi), 0 * phi])
    reg = curve_of_regression(base, base + np.array([0.1, 0.2, 2.0]), deviation=0.01)
    assert reg.kind == "parallel" and not reg.has_curve
    assert reg.message.startswith("no curve of regression")


def test_plane_has_no_curve_of_regression():
    u = np.linspace(0.0, 1.0, 12)
    starts = np.column_stack([u, 0 * u, u])  # a fan of converging rulings in the plane z = x
    ends = np.column_stack([0.3 + 0.5 * u, 1 + 0 * u, 0.3 + 0.5 * u])
    reg = curve_of_regression(starts, ends, deviation=0.01)
    assert reg.kind == "planar" and reg.message.startswith("no curve of regression")


def test_hyperbolic_paraboloid_has_no_curve_of_regression():
    u = np.linspace(0.0, 1.0, 12)
    reg = curve_of_regression(np.column_stack([u, 0 * u, 0 * u]), np.column_stack([u, 1 + 0 * u, u]), 0.01)
    assert reg.kind == "warped" and reg.message.startswith("no curve of regression")
    # z = xy: the striction line is the x axis, square to every ruling, and the lines
    # of neighbouring rulings are a whole station apart
    assert np.allclose(reg.deviations, math.pi / 2, atol=1e-12)
    assert np.allclose(reg.gaps, 1.0 / 11, rtol=1e-12)


def test_curve_is_split_where_it_turns_away_from_the_rulings():
    t = np.linspace(0.0, 2.0 * np.pi, 101)
    c, d = helix(t), helix_tangent(t)
    ends = c + 3.0 * d
    ends[50] += [0.0, 0.0, 0.4]  # one ruling knocked out of its tangent plane
    reg = curve_of_regression(c, ends, deviation=0.01)
    assert reg.kind == "curve" and len(reg.curves) == 2
    assert not reg.valid[48:51].all() and reg.valid[:45].all() and reg.valid[55:].all()
    assert "pieces" in reg.message


def test_closest_points_of_two_crossing_lines_are_their_intersection():
    starts = np.array([[0.0, 0.0, 0.0], [1.0, -1.0, 0.0]])
    directions = np.array([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]])
    s, t, parallel = closest_points_of_lines(starts, directions)
    assert s[0] == pytest.approx(1.0) and t[0] == pytest.approx(1.0) and not parallel[0]


# ----------------------------------------------------------------------------- with the kernel


def test_regression_of_the_kernels_tangent_developable_reproduces_its_curve():
    from torsal.nodes.geometry.curves import ParametricCurve
    from torsal.nodes.geometry.developable import tangent_developable_rulings

    curve = ParametricCurve(helix, (0.0, 2.0 * np.pi))
    rulings = tangent_developable_rulings(curve, 200, length=3.0, cutting_length=0.2)
    reg = curve_of_regression(rulings.starts, rulings.ends, deviation=0.01)
    assert reg.kind == "curve" and reg.valid.all()
    assert distance_to_helix(reg.points, 2.0 * np.pi).max() < 1e-3


def test_the_kernels_cone_unrolls_and_gives_its_apex():
    from torsal.nodes.geometry.curves import ParametricCurve
    from torsal.nodes.geometry.developable import cone_rulings
    from torsal.nodes.geometry.unroll import unroll_rulings

    apex = np.array([0.0, 0.0, math.sqrt(3.0)])
    base = ParametricCurve(lambda u: np.column_stack([np.cos(u), np.sin(u), 0 * u]), (0.0, np.pi))
    rulings = cone_rulings(base, apex, 10.0, 100)  # clamped at the apex: slant length 2
    assert np.linalg.norm(curve_of_regression(rulings.starts, rulings.ends, 0.01).apex - apex) < 1e-9
    dev = unroll_rulings(rulings.starts, rulings.ends, area_3d=math.pi * 1.0 * 2.0 / 2.0)
    assert dev.max_edge_length_error < 1e-12 and abs(dev.area_error) < 1e-4
