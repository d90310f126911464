"""developable.ConicalSurface, solved in real graphs."""

from __future__ import annotations

import math

import numpy as np
import pytest

from tests.support.direct_graphs import Chain, helix
from torsal.engine.values import Point
from torsal.nodes.curves.primitives import Circle
from torsal.nodes.developable.conical import ConicalSurface

APEX = np.array([0.5, -0.3, 6.0])


def cone_on(curve_node, curve_port: str, **values) -> Chain:
    chain = Chain()
    curve_node(chain)
    chain.add("cone", ConicalSurface(), **values)
    chain.wire("curve", curve_port, "cone", "Curve")
    return chain.solve()


def on_helix(**values) -> Chain:
    return cone_on(lambda c: helix(c, 2.0, 0.3, 1.5, "curve"), "Curve", Apex=Point(*APEX), **values)


def on_circle(**values) -> Chain:
    return cone_on(lambda c: c.add("curve", Circle(), Radius=3.0), "Circle", **values)


def lines(chain: Chain) -> np.ndarray:
    return np.array([[r.start, r.end] for r in chain.items("cone", "Rulings")])


def test_cone_on_a_helix_has_warp_below_1e_14():
    chain = on_helix(Height=2.5, Segments=60)
    warp = chain.items("cone", "WarpAngles")
    assert chain.result("cone").state == "ok"
    assert len(warp) == 61
    assert max(warp) < 1e-14  # measured 1.6e-16


def test_cone_rulings_end_at_the_apex_when_height_reaches_it():
    chain = on_helix(Height=100.0, Segments=30)
    r = lines(chain)
    assert np.array_equal(r[:, 1], np.broadcast_to(APEX, r[:, 1].shape))
    assert chain.texts("cone") == ["31 of 31 rulings reach the Apex within Height and stop there"]


def test_rulings_ending_at_the_apex_are_measured_in_the_plane_of_their_fan():
    """At the apex the far edge stands still (a fan of flat triangles): the warp there is
    taken in the triangles' plane, so it is 0 — a number, not NaN and not a guess."""
    chain = on_helix(Height=100.0, Segments=30)
    warp = chain.items("cone", "WarpAngles")
    assert warp == [0.0] * 31
    assert chain.result("cone").state == "ok"


def test_cone_rulings_are_height_long_and_aim_at_the_apex_below_it():
    chain = on_helix(Height=2.5, Segments=30)
    r = lines(chain)
    span = r[:, 1] - r[:, 0]
    to_apex = APEX - r[:, 0]
    assert np.abs(np.linalg.norm(span, axis=1) - 2.5).max() < 1e-12
    along = span / 2.5 - to_apex / np.linalg.norm(to_apex, axis=1)[:, None]
    assert np.abs(along).max() < 1e-14
    assert chain.texts("cone") == []


def test_only_rulings_nearer_than_height_are_clamped_at_the_apex():
    # circle of radius 3 at z = 0, apex 4 above its centre: every ruling is 5 long
    chain = on_circle(Apex=Point(1.0, 0.0, 4.0), Height=5.0, Segments=12)
    r = lines(chain)
    distance = np.linalg.norm(np.array([1.0, 0.0, 4.0]) - r[:, 0], axis=1)
    clamped = distance <= 5.0
    assert 0 < clamped.sum() < len(r)
    assert np.allclose(r[clamped, 1], [1.0, 0.0, 4.0], atol=0.0)
    assert np.abs(np.linalg.norm(r[~clamped, 1] - r[~clamped, 0], axis=1) - 5.0).max() < 1e-12


def test_full_cone_surface_on_a_circle_lies_on_the_exact_cone():
    # radius 3 at z = 0, apex 4 above the centre: at height z the radius is 3·(1 − z/4)
    chain = on_circle(Apex=Point(0.0, 0.0, 4.0), Height=10.0, Segments=96)
    surface = chain.item("cone", "Surface")
    u, v = np.random.default_rng(1).random((2, 500))
    p = surface.point_at(u, v)
    # between its 97 rulings the surface strays from the cone by its cubic interpolation
    # (measured 1.4e-7, under (5/384)·(2π/96)⁴·r = 7.2e-7 at the base)
    assert np.abs(np.linalg.norm(p[:, :2], axis=1) - 3.0 * (1 - p[:, 2] / 4.0)).max() < 3e-7
    assert np.abs(p[:, 2] - 4.0 * v).max() < 1e-14


def test_negative_height_runs_the_rulings_away_from_the_apex():
    r = lines(on_circle(Apex=Point(0.0, 0.0, 4.0), Height=-5.0, Segments=8))
    assert np.abs(r[:, 1] - 2 * r[:, 0] + [0.0, 0.0, 4.0]).max() < 1e-12


def test_curve_through_the_apex_says_move_the_apex():
    chain = on_circle(Apex=Point(3.0, 0.0, 0.0), Height=1.0, Segments=8)
    assert chain.result("cone").state == "warning"
    assert chain.texts("cone") == [
        "The curve passes through the Apex at 2 of 9 stations (first at t = 0): a ruling there would "
        "have no length; move the Apex off the curve"
    ]
    assert chain.items("cone", "Surface") == [None]


@pytest.mark.parametrize(
    ("values", "message"),
    [
        ({"Segments": -3}, "Segments must be at least 1, not -3"),
        ({"Height": 0.0}, "Height is 0, so the rulings would have no length: give a length"),
    ],
)
def test_invalid_inputs_warn_with_what_to_change(values, message):
    chain = on_circle(**values)
    assert chain.result("cone").state == "warning"
    assert chain.texts("cone") == [message]


def test_apex_with_an_infinite_coordinate_warns():
    chain = Chain()
    chain.add("curve", Circle(), Radius=3.0)
    chain.source("apex", Point(math.inf, 0.0, 0.0))
    chain.add("cone", ConicalSurface())
    chain.wire("curve", "Circle", "cone", "Curve")
    chain.wire("apex", "Tree", "cone", "Apex")
    chain.solve()
    assert chain.result("cone").state == "warning"
    assert chain.texts("cone") == ["Apex has a coordinate that is not a finite number"]
