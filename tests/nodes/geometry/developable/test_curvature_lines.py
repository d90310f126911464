"""Lines of curvature (torsal/nodes/geometry/developable/curvature_lines.py) against closed
forms: a paraboloid of revolution's rings are circles, a torus's principal directions are
its parameter lines, and on z = xy the lines of curvature are asinh x ± asinh y = const."""

from __future__ import annotations

import numpy as np
import pytest

from tests.support.freeform_designs import Design
from torsal.nodes.geometry.developable.curvature_lines import (
    plan_scale,
    principal_plan_directions,
    ring_family,
    trace_rings,
)
from torsal.nodes.geometry.surface_base import Surface, broadcast_uv


def _paraboloid(x, y):
    return (x * x + y * y) / 8, x / 4, y / 4, 0.25 + 0 * x, 0 * x, 0.25 + 0 * x


def _bump(x, y):
    """2·exp(−(x² + y²)/18): a surface of revolution whose meridians inflect at r = 3."""
    e = 2 * np.exp(-(x * x + y * y) / 18)
    gx, gy = -x / 9, -y / 9
    return e, e * gx, e * gy, e * (gx * gx - 1 / 9), e * gx * gy, e * (gy * gy - 1 / 9)


def _hypar(x, y):
    return x * y, y, x, 0 * x, 1 + 0 * x, 0 * x


class Torus(Surface):
    """R = 3, r = 1; u around the axis, v around the tube (over three quarters of each)."""

    def derivatives(self, u, v, order=1):
        a, b = broadcast_uv(u, v)
        a, b = 1.5 * np.pi * a, 1.5 * np.pi * b
        ca, sa, cb, sb = np.cos(a), np.sin(a), np.cos(b), np.sin(b)
        w = 3 + cb
        k = 1.5 * np.pi
        out = [np.column_stack([w * ca, w * sa, sb])]
        out += [k * np.column_stack([-w * sa, w * ca, 0 * a]), k * np.column_stack([-sb * ca, -sb * sa, cb])]
        if order >= 2:
            out += [k * k * np.column_stack([-w * ca, -w * sa, 0 * a]),
                    k * k * np.column_stack([sb * sa, -sb * ca, 0 * a]),
                    k * k * np.column_stack([-cb * ca, -cb * sa, -sb])]
        return out[: {0: 1, 1: 3, 2: 6}[order]]


def test_a_torus_principal_directions_are_its_parameter_lines():
    torus = Torus()
    rng = np.random.default_rng(3)
    u, v = rng.uniform(0.05, 0.95, 50), rng.uniform(0.05, 0.95, 50)
    scale = plan_scale(torus)
    k1, k2, d1, d2 = principal_plan_directions(torus, u, v, scale)
    # parallels (along u) bend by cos(b)/(3 + cos b) (outward normal sign aside), meridians by 1
    b = 1.5 * np.pi * v
    parallel, meridian = np.abs(np.cos(b) / (3 + np.cos(b))), np.ones_like(b)
    assert np.allclose(np.sort(np.abs([k1, k2]), axis=0), np.sort([parallel, meridian], axis=0), atol=1e-12)
    along_u = np.abs(d1[:, 0]) > np.abs(d1[:, 1])
    # each direction lies along one parameter line exactly, and the two are different lines
    assert np.allclose(np.minimum(np.abs(d1[:, 0]), np.abs(d1[:, 1])), 0.0, atol=1e-12)
    assert np.allclose(np.minimum(np.abs(d2[:, 0]), np.abs(d2[:, 1])), 0.0, atol=1e-12)
    assert np.all(along_u != (np.abs(d2[:, 0]) > np.abs(d2[:, 1])))


def test_hyperbolic_paraboloid_principal_directions_in_closed_form():
    """On z = xy (E = 1 + y², G = 1 + x², L = N = 0) the principal directions satisfy
    E·dx² = G·dy²: dx/dy = ±√((1 + x²)/(1 + y²))."""
    design = Design("hypar", _hypar, (-1.5, 1.5), (-1.0, 1.0))
    surface = design.surface()
    rng = np.random.default_rng(5)
    u, v = rng.uniform(0, 1, 40), rng.uniform(0, 1, 40)
    _, _, d1, d2 = principal_plan_directions(surface, u, v, [3.0, 2.0])  # the plan is (x + 1.5, y + 1)
    x, y = -1.5 + 3 * u, -1 + 2 * v
    ratio = np.sqrt((1 + x**2) / (1 + y**2))
    for d in (d1, d2):
        found = d[:, 0] / d[:, 1]
        assert np.allclose(np.abs(found), ratio, rtol=1e-9)
    assert np.all(np.sign(d1[:, 0] / d1[:, 1]) != np.sign(d2[:, 0] / d2[:, 1]))


def test_rings_on_a_paraboloid_and_a_bump_are_circles():
    for jet in (_paraboloid, _bump):
        design = Design("ring", jet, (-6.0, 6.0), (-6.0, 6.0))
        surface = design.surface()
        scale = plan_scale(surface)
        assert np.isclose(scale[0], scale[1])  # the plan is x, y scaled alike: circles stay circles
        centre = 0.5 * scale  # the plan point of x = y = 0
        radii = np.array([0.5, 2.0, 3.0, 4.5]) * scale[0] / 12.0
        family = ring_family(surface, centre, 2.0, scale)
        theta = np.linspace(0.0, 2.0 * np.pi, 33)
        rings = trace_rings(surface, centre, radii, theta, family, scale, start=1.0)
        assert np.allclose(rings, radii[:, None], rtol=2e-8)


def test_hyperbolic_paraboloid_lines_of_curvature_keep_asinh_sums():
    """Traced round a far centre where they run across its rays, the lines of curvature of
    z = xy keep asinh x + asinh y (one family) or asinh x − asinh y (the other) constant."""
    design = Design("hypar", _hypar, (-1.5, 1.5), (-1.0, 1.0))
    surface = design.surface()
    scale = np.array([3.0, 2.0])  # the plan is (x + 1.5, y + 1) exactly with these
    centre = np.array([3.0 - 40.0, 2.0 - 40.0])  # far down-left of the middle: rays run at 45°
    theta = np.linspace(np.pi / 4 - 0.04, np.pi / 4 + 0.04, 9)
    radii = np.hypot(40.0, 40.0) + np.array([-0.6, 0.0, 0.8])
    family = ring_family(surface, centre, float(radii[1]), scale)
    rings = trace_rings(surface, centre, radii, theta, family, scale, start=np.pi / 4)
    x = centre[0] + rings * np.cos(theta) - 1.5
    y = centre[1] + rings * np.sin(theta) - 1.0
    kept = np.arcsinh(x) + np.arcsinh(y)  # constant along lines running at −45°
    assert np.ptp(kept, axis=1).max() < 1e-6  # solved to rtol 1e-9 on radii of 56: 2.4e-7 measured
    assert np.ptp(kept[:, 0]) > 0.3  # and different from line to line


def test_a_line_that_runs_along_a_ray_is_refused():
    design = Design("hypar", _hypar, (-1.5, 1.5), (-1.0, 1.0))
    surface = design.surface()
    scale = np.array([3.0, 2.0])
    with pytest.raises(ValueError, match="no ring"):
        trace_rings(surface, np.array([1.5, 1.0]), np.array([0.5]), np.linspace(0.0, np.pi, 9), 0, scale)
