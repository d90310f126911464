"""A surface unrolled far from the origin gives the development it gives at the origin, to
the rounding of its coordinates over its size, also when its first ruling is short (a strip
that tapers from a point): the ruling laid up the +Y axis takes the surface's own direction
there, not the direction between its two rounded end points."""

from __future__ import annotations

import numpy as np
import pytest

from torsal.nodes.geometry.ruled import RuledSurface
from torsal.nodes.geometry.unroll import unroll_surface

SIZE = 140.0
APEX = np.array([3.0, -2.0, 1.0])


def tapered_cone(offset: np.ndarray) -> RuledSurface:
    """A 140 m cone fanning from its apex along a twisted curve: its first ruling has no
    length, the next one is 0.44 m."""
    t = np.linspace(0.0, 1.0, 41)
    ends = APEX + SIZE * np.column_stack([t, 0.3 * t**2, 0.2 * t**3])
    return RuledSurface.from_rulings(np.tile(APEX, (len(t), 1)) + offset, ends + offset)


@pytest.mark.parametrize("offset", [(1e6, 2e6, 300.0), (1e9, 1e9, 1e9)], ids=["1e6", "1e9"])
def test_a_tapered_strip_far_out_unrolls_as_at_the_origin_to_the_rounding_of_its_coordinates(offset):
    at_origin = unroll_surface(tapered_cone(np.zeros(3)), 40, 8)
    far = unroll_surface(tapered_cone(np.array(offset)), 40, 8)
    deviation = max(np.abs(far.starts2d - at_origin.starts2d).max(),
                    np.abs(far.ends2d - at_origin.ends2d).max())
    # 32 ulps of the offset over the size, as tests/app/test_site_coordinates.py asks (measured:
    # 1.2e-10 at 1e6 m, 5.4e-9 at 1e9 m, where the turn of the rounded first ruling gave 9.7e-8)
    assert deviation / SIZE <= 1e-9 + 32 * np.spacing(max(offset)) / SIZE


def test_the_first_ruling_still_runs_up_the_y_axis_from_the_origin():
    development = unroll_surface(tapered_cone(np.zeros(3)), 40, 8)
    start, end = development.starts2d[1], development.ends2d[1]
    assert np.abs(start).max() < 1e-15
    assert abs(end[0]) < 1e-15 * SIZE
    assert end[1] == pytest.approx(np.linalg.norm(development.ends3d[1] - development.starts3d[1]), rel=1e-14)
