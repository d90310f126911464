"""developable.CylindricalSurface, solved in real graphs."""

from __future__ import annotations

import math

import numpy as np
import pytest

from tests.support.direct_graphs import Chain, helix
from torsal.engine.values import Point, Vector
from torsal.nodes.curves.primitives import Circle, Line
from torsal.nodes.developable.cylindrical import CylindricalSurface


def cylinder_of(curve_node, curve_port: str, **values) -> Chain:
    chain = Chain()
    curve_node(chain)
    chain.add("cyl", CylindricalSurface(), **values)
    chain.wire("curve", curve_port, "cyl", "Curve")
    return chain.solve()


def on_helix(**values) -> Chain:
    return cylinder_of(lambda c: helix(c, 2.0, 0.5, 2.0, "curve"), "Curve", **values)


def on_circle(radius: float = 2.0, **values) -> Chain:
    return cylinder_of(lambda c: c.add("curve", Circle(), Radius=radius), "Circle", **values)


def lines(chain: Chain) -> np.ndarray:
    return np.array([[r.start, r.end] for r in chain.items("cyl", "Rulings")])


def test_cylinder_on_a_helix_has_warp_below_1e_14():
    chain = on_helix(Direction=Vector(0.3, -0.2, 1.0), Height=3.0, Segments=60)
    warp = chain.items("cyl", "WarpAngles")
    assert chain.result("cyl").state == "ok"
    assert len(warp) == 61
    assert max(warp) < 1e-14  # measured 0


def test_cylinder_rulings_are_parallel_to_direction_and_height_long():
    d = np.array([1.0, 0.0, 2.0])
    chain = on_helix(Direction=Vector(*d), Height=3.0, Segments=40)
    r = lines(chain)
    span = r[:, 1] - r[:, 0]
    assert np.abs(np.linalg.norm(span, axis=1) - 3.0).max() < 1e-12
    assert np.abs(span / 3.0 - d / np.linalg.norm(d)).max() < 1e-14


def test_cylinder_rulings_start_on_the_curve_evenly_spaced_by_arc_length():
    chain = on_helix(Height=1.0, Segments=20)
    starts = lines(chain)[:, 0]
    assert np.abs(np.linalg.norm(starts[:, :2], axis=1) - 2.0).max() < 1e-12
    # on a helix arc length is proportional to t = z / c
    t = starts[:, 2] / 0.5
    assert np.abs(t - np.linspace(0.0, 4 * math.pi, 21)).max() < 1e-12  # measured 3.9e-14


def test_negative_height_extrudes_against_direction():
    r = lines(on_circle(Height=-2.0, Segments=8))
    assert np.allclose(r[:, 1] - r[:, 0], [0.0, 0.0, -2.0], atol=1e-15)


def test_closed_curve_gives_a_closed_surface_whose_last_ruling_repeats_the_first():
    chain = on_circle(Height=3.0, Segments=24)
    r = lines(chain)
    assert np.abs(r[0] - r[-1]).max() < 1e-12
    surface = chain.item("cyl", "Surface")
    assert surface.closed_u


def test_cylinder_surface_on_a_circle_lies_on_the_exact_cylinder():
    surface = on_circle(radius=2.0, Height=3.0, Segments=96).item("cyl", "Surface")
    u, v = np.random.default_rng(1).random((2, 500))
    p = surface.point_at(u, v)
    # between its 97 rulings the surface strays from the circle by its cubic interpolation
    # (measured 9.6e-8, under (5/384)·(2π/96)⁴·r = 4.8e-7)
    assert np.abs(np.linalg.norm(p[:, :2], axis=1) - 2.0).max() < 2e-7
    assert np.abs(p[:, 2] - 3.0 * v).max() < 1e-14


def test_cylinder_surface_isocurves_are_the_rulings():
    chain = on_circle(Height=3.0, Segments=12)
    surface = chain.item("cyl", "Surface")
    r = lines(chain)
    u = np.linspace(0.0, 1.0, 13)
    assert np.abs(surface.point_at(u, np.zeros(13)) - r[:, 0]).max() < 1e-12
    assert np.abs(surface.point_at(u, np.ones(13)) - r[:, 1]).max() < 1e-12


@pytest.mark.parametrize(
    ("values", "message"),
    [
        ({"Direction": Vector(0, 0, 0)}, "Direction has zero length, so it has no direction"),
        ({"Height": 0.0}, "Height is 0, so the rulings would have no length: give a length"),
        ({"Height": math.nan}, "Height is not a number (NaN)"),
    ],
)
def test_invalid_inputs_warn_with_what_to_change(values, message):
    chain = on_circle(**values)
    assert chain.result("cyl").state == "warning"
    assert chain.texts("cyl") == [message]
    assert chain.items("cyl", "Surface") == [None]


def test_direction_along_a_straight_curve_warns_the_surface_has_no_width():
    chain = Chain()
    chain.add("curve", Line(), Start=Point(0, 0, 0), End=Point(0, 0, 5))
    chain.add("cyl", CylindricalSurface(), Segments=4)
    chain.wire("curve", "Line", "cyl", "Curve")
    chain.solve()
    assert chain.result("cyl").state == "warning"
    assert chain.texts("cyl") == [
        "Direction is parallel to the curve at 5 of 5 stations (first at t = 0): the surface has no "
        "width there (no tangent plane: its WarpAngles are NaN); tilt Direction away from the curve"
    ]
    assert all(math.isnan(w) for w in chain.items("cyl", "WarpAngles"))


def test_empty_curve_input_warns():
    chain = Chain()
    chain.add("cyl", CylindricalSurface())
    chain.solve()
    assert chain.result("cyl").state == "warning"
    assert chain.texts("cyl") == ["Input Curve collected no data"]
