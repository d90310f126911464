"""analysis.CurveOfRegression: a helix recovered from its tangent developable; planes,
cylinders and twisted surfaces have none; a cone gives its apex."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.spatial import cKDTree

from tests.support.analysis_shapes import hypar
from tests.support.analysis_shapes import tangent_developable as kernel_tangent_developable
from tests.support.direct_graphs import Chain, helix
from tests.support.node_helpers import out, run, texts, tree
from torsal.engine.values import Point
from torsal.nodes.analysis.curve_of_regression import CurveOfRegression
from torsal.nodes.developable.conical import ConicalSurface
from torsal.nodes.developable.tangent import TangentDevelopable
from torsal.nodes.geometry.curves import Circle
from torsal.nodes.geometry.developable import cone_rulings
from torsal.nodes.geometry.parametric_surface import ParametricSurface, cylinder, sphere
from torsal.nodes.geometry.ruled import RuledSurface

R_HELIX, RISE, TURNS = 2.0, 0.5, 1.5


def regression(surface, deviation: float = 0.01, segments: int = 200):
    result = run(CurveOfRegression(), Surface=tree({(0,): [surface]}), Deviation=deviation,
                 Segments=segments)
    return result, out(result, "Curves").get((0,), []), out(result, "Points").get((0,), [])


def distance_to_helix(points: np.ndarray) -> np.ndarray:
    """Distance of each point to the helix (R cos t, R sin t, c·t), t over TURNS turns."""
    t = np.linspace(0.0, 2 * math.pi * TURNS, 200_001)
    samples = np.column_stack([R_HELIX * np.cos(t), R_HELIX * np.sin(t), RISE * t])
    _, nearest = cKDTree(samples).query(points)
    t = t[nearest]
    for _ in range(3):  # Newton on d/dt |H(t) − p|² / 2 = 0
        h = np.column_stack([R_HELIX * np.cos(t), R_HELIX * np.sin(t), RISE * t])
        h1 = np.column_stack([-R_HELIX * np.sin(t), R_HELIX * np.cos(t), np.full_like(t, RISE)])
        h2 = np.column_stack([-R_HELIX * np.cos(t), -R_HELIX * np.sin(t), np.zeros_like(t)])
        d = h - points
        t = t - np.einsum("ij,ij->i", d, h1) / (np.einsum("ij,ij->i", h1, h1) + np.einsum("ij,ij->i", d, h2))
    h = np.column_stack([R_HELIX * np.cos(t), R_HELIX * np.sin(t), RISE * t])
    return np.linalg.norm(h - points, axis=1)


def test_curve_of_regression_of_a_helix_tangent_developable_is_the_helix():
    """helix → developable.TangentDevelopable (rulings from 0.5 to 3 along the tangent, so
    the curve lies off the sheet) → analysis.CurveOfRegression at 200 segments.

    The 201 Points are where neighbouring rulings meet, on the helix to rounding (measured
    1.9e-15). The Curve is a cubic through them: between the points it strays by the
    interpolation error, (5/384) Δt⁴ R = 1.3e-7 for a clamped cubic with the helix's
    parameter step Δt = 3π/200 (R bounds its fourth derivative), about twice that at the
    free ends (measured 2.8e-7); its length is the helix's, 2π·turns·√(R² + c²), to 5.8e-9.
    """
    chain = Chain()
    helix(chain, R_HELIX, RISE, TURNS)
    chain.add("tangent", TangentDevelopable(), Segments=200, Length=3.0, CuttingLength=0.5)
    chain.add("regression", CurveOfRegression(), Deviation=0.01, Segments=200)
    chain.wire("helix", "Curve", "tangent", "Curve")
    chain.wire("tangent", "Surface", "regression", "Surface")
    chain.solve()
    assert chain.result("regression").state == "ok"
    (curve,) = chain.items("regression", "Curves")
    points = np.asarray(chain.items("regression", "Points"))
    assert len(points) == 201 and distance_to_helix(points).max() < 1e-14 * R_HELIX
    step = 2 * math.pi * TURNS / 200
    interpolation = 5 / 384 * step**4 * R_HELIX
    assert distance_to_helix(curve.point_at(np.linspace(0.0, 1.0, 4001))).max() < 3 * interpolation
    assert curve.length == pytest.approx(2 * math.pi * TURNS * math.hypot(R_HELIX, RISE), rel=2e-8)


def test_recovered_curve_converges_to_the_helix_at_fourth_order():
    """Cubic interpolation: each doubling of the segments divides the error by 2⁴ (measured
    15.9, 16.0 and 16.0 from 50 to 400 segments)."""
    surface = kernel_tangent_developable(R_HELIX, RISE, TURNS, 3.0, 0.5, segments=400)
    errors = []
    for segments in (50, 100, 200):
        _, (curve,), _ = regression(surface, segments=segments)
        errors.append(distance_to_helix(curve.point_at(np.linspace(0.0, 1.0, 2001))).max())
    assert errors[0] / errors[1] > 12 and errors[1] / errors[2] > 12


@pytest.mark.parametrize("name, surface, why", [
    ("cylinder", cylinder(1.0, 2.0), "the rulings are parallel (a cylinder)"),
    ("plane", ParametricSurface(lambda u, v: (u, v, 0 * u), (0, 2), (0, 1)), "the strip is planar"),
])
def test_plane_and_cylinder_warn_no_curve_of_regression(name, surface, why):
    result, curves, points = regression(surface)
    assert result.state == "warning"
    assert texts(result) == [f"No curve of regression: {why}"]
    assert curves == [] and points == []


def test_hyperbolic_paraboloid_warns_no_curve_of_regression_as_its_rulings_never_meet():
    result, curves, _ = regression(hypar())
    assert result.state == "warning"
    assert texts(result)[0].startswith("No curve of regression: neighbouring rulings do not meet")
    assert curves == []


def test_cone_gives_its_apex_as_the_point_with_a_remark():
    # a truncated cone: rulings from a circle of radius 2 at z = 0 towards (1, 1, 4), 2 long
    rulings = cone_rulings(Circle(radius=2.0), [1.0, 1.0, 4.0], 2.0, 80)
    result, curves, points = regression(RuledSurface.from_rulings(rulings.starts, rulings.ends))
    assert result.state == "ok" and curves == []
    # measured 1.6e-8 off: the apex is met by rulings 2 long, 4.5 away from their feet
    assert np.abs(np.asarray(points) - [1.0, 1.0, 4.0]).max() < 5e-8
    assert texts(result) == ["The surface is a cone: every ruling passes through its apex (1, 1, 4), so "
                             "it has an apex, not a curve of regression; Points holds the apex"]


def test_conical_surface_node_gives_its_apex():
    chain = Chain()
    chain.source("circle", Circle(radius=3.0))
    chain.add("cone", ConicalSurface(), Apex=Point(0.0, 0.0, 5.0), Height=2.5, Segments=40)
    chain.add("regression", CurveOfRegression())
    chain.wire("circle", "Curve", "cone", "Curve")
    chain.wire("cone", "Surface", "regression", "Surface")
    chain.solve()
    assert chain.items("regression", "Curves") == []
    assert np.abs(np.asarray(chain.items("regression", "Points")) - [0.0, 0.0, 5.0]).max() < 1e-14


def test_non_ruled_surface_is_a_warning_saying_it_has_no_straight_rulings():
    result, _, _ = regression(sphere(1.0))
    assert result.state == "warning"
    assert texts(result)[0].startswith("surface has no straight rulings")


@pytest.mark.parametrize("deviation", [0.0, -0.1, math.nan])
def test_deviation_must_be_a_positive_angle(deviation):
    result, _, _ = regression(cylinder(1.0, 1.0), deviation=deviation)
    assert result.state == "warning"
    assert "Deviation" in texts(result)[0]


def test_a_locally_twisted_strip_splits_the_curve_and_warns():
    # the helix's tangent developable with a twist added to a few rulings in the middle
    surface = kernel_tangent_developable(R_HELIX, RISE, TURNS, 3.0, 0.5, segments=200)
    lines = surface.ruling_lines.copy()
    lines[95:105, 1] += np.array([0.0, 0.0, 0.3])  # lift the far ends: neighbours no longer meet
    twisted = RuledSurface.from_rulings(lines[:, 0], lines[:, 1])
    result, curves, _ = regression(twisted, deviation=0.01, segments=200)
    assert result.state == "warning"
    assert len(curves) >= 2
    assert texts(result)[0].startswith(f"The curve of regression is split into {len(curves)} pieces")
