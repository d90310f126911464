"""The boundaries and creases of a ring layout's half (torsal/nodes/geometry/developable/
ring_boundaries.py), on a Gaussian bump z = 2·exp(−r²/18), a surface of revolution.

Its rings of curvature are its parallels, circles r = const, and the developable between
two of them is the cone (a frustum) through both: its generators lie in meridian planes,
along the chord of the profile z(r) from one circle to the other. Two such strips meet
along their shared circle at the angle between their chords, the same all round:
|atan(slope(r0, r1)) − atan(slope(r1, r2))|, slope the chord's dz/dr — the closed form.
The fold is also recomputed here from the two strips' normals by central differences of
their points (nothing of the module's closest-point search), at points along the circle.
"""

from __future__ import annotations

import itertools
from functools import cache

import numpy as np
import shapely

from tests.support.freeform_designs import Design
from torsal.nodes.geometry.developable.guided import IsoBoundaries
from torsal.nodes.geometry.developable.ring_boundaries import half_boundaries
from torsal.nodes.geometry.developable.rings import RingPatch, _pieces, region_inside


def _bump(x, y):
    e = 2 * np.exp(-(x * x + y * y) / 18)
    gx, gy = -x / 9, -y / 9
    return e, e * gx, e * gy, e * (gx * gx - 1 / 9), e * gx * gy, e * (gy * gy - 1 / 9)


DESIGN = Design("bump", _bump, (-6.0, 6.0), (-6.0, 6.0))
SCALE = np.array([12.0, 12.0])  # the plan is (x + 6, y + 6)
CENTRE = np.array([6.0, 6.0])
#: Ring levels of the patch (seed radii 1 … 5): the circles r = 2, 3 and 4.
LEVELS = (0.25, 0.5, 0.75)
RADII = np.array([2.0, 3.0, 4.0])


def _profile(r):
    return 2 * np.exp(-r * r / 18)


@cache
def _half():
    """Two strips between the circles r = 2, 3 and 4, cut to the half y ≥ 0 (the patch's
    rings run 0.2 rad past it at both ends), and the half's boundaries and creases."""
    surface = DESIGN.surface()
    patch = RingPatch(surface, CENTRE, SCALE, np.linspace(1.0, 5.0, 9), (-0.2, np.pi + 0.2), 1, 0.5 * np.pi)
    inside = region_inside(surface, shapely.box(0.0, 6.0, 12.0, 12.0), SCALE)
    on_design = region_inside(surface, shapely.box(0.0, 0.0, 12.0, 12.0), SCALE)
    boundaries = IsoBoundaries(patch, "u")
    pieces = [p for lo, hi in itertools.pairwise(LEVELS)
              for p in _pieces(surface, boundaries, lo, hi, inside, 0.05, 24, 1e-7)]
    rings, creases = half_boundaries(patch, pieces, inside, on_design, DESIGN.size)
    return pieces, rings, creases


def _chord_angle(r0, r1):
    return np.arctan((_profile(r1) - _profile(r0)) / (r1 - r0))


def test_a_half_has_one_boundary_more_than_strips_each_a_circle_cut_to_the_half():
    pieces, rings, creases = _half()
    assert len(pieces) == 2 and len(rings) == 3 and len(creases) == 1
    for ring, r in zip(rings, RADII, strict=True):
        points = ring.point_at(np.linspace(0.0, 1.0, 101))
        assert np.abs(np.hypot(points[:, 0], points[:, 1]) - r).max() <= 1e-6  # the patch's rings: 1e-7
        assert np.abs(points[:, 2] - _profile(r)).max() <= 1e-6
        # from the half's edge y = 0 to itself (its ends interpolated between samples: 2.8e-8)
        assert np.abs(points[[0, -1], 1]).max() <= 1e-6 * r
        assert points[:, 1].min() >= -1e-6 * r
        assert abs(abs(points[-1, 0] - points[0, 0]) - 2 * r) <= 1e-6 * r


def test_the_crease_is_the_angle_between_the_two_cones_chords():
    _, _, (crease,) = _half()
    expected = abs(_chord_angle(2.0, 3.0) - _chord_angle(3.0, 4.0))  # 0.0794 rad
    assert abs(crease - expected) <= 1e-6 * expected + 1e-9


def _normals(surface, u, v, h=1e-6):
    """Unit normals of ``surface`` at (u, v) by central differences of its points."""
    su = (surface.point_at(u + h, v) - surface.point_at(u - h, v)) / (2 * h)
    sv = (surface.point_at(u, v + h) - surface.point_at(u, v - h)) / (2 * h)
    n = np.cross(su, sv)
    return n / np.linalg.norm(n, axis=1, keepdims=True)


def test_the_crease_matches_the_strips_normals_recomputed_along_the_circle():
    (lower, upper), _, (crease,) = _half()
    theta = np.linspace(0.1, np.pi - 0.1, 25)
    points = np.column_stack([3.0 * np.cos(theta), 3.0 * np.sin(theta), np.full(25, _profile(3.0))])
    folds = []
    for strip, v, inward in ((lower, 1.0, -1e-4), (upper, 0.0, 1e-4)):
        u = np.linspace(0.0, 1.0, 20001)
        edge = strip.surface.point_at(u, np.full_like(u, v))
        nearest = np.argmin(np.linalg.norm(edge[None] - points[:, None], axis=2), axis=1)
        assert np.linalg.norm(edge[nearest] - points, axis=1).max() <= 2e-3  # the circle is its edge
        folds.append(_normals(strip.surface, u[nearest], np.full(25, v + inward)))
    angle = np.arccos(np.clip(np.einsum("ij,ij->i", *folds), -1.0, 1.0))
    assert np.ptp(angle) <= 1e-3 * angle.max()  # the same all round (a surface of revolution)
    assert abs(angle.max() - crease) <= 2e-3 * crease
