"""Certified deviation (developable/certify.py): the bound is never below the true distance.

The strips here are built so that the largest distance is known in closed form: a roof of
two flat pieces over a plane, its ridge (where the distance peaks, with a kink) on a ruling
that no uniform sample grid holds.
"""

from __future__ import annotations

import numpy as np
import pytest

from torsal.nodes.geometry.curve_rail import ruled_between
from torsal.nodes.geometry.curves import Polyline
from torsal.nodes.geometry.developable.certify import AGREE, certified_deviation
from torsal.nodes.geometry.nurbs_surface import NurbsSurface


def plane() -> NurbsSurface:
    """z = 0 over [-5, 5]², a bilinear NURBS patch: a point's distance from it is |z|."""
    net = np.array([[[-5.0, -5.0, 0.0], [-5.0, 5.0, 0.0]], [[5.0, -5.0, 0.0], [5.0, 5.0, 0.0]]])
    knots = np.array([0.0, 0.0, 1.0, 1.0])
    return NurbsSurface(net, 1, 1, knots, knots)


@pytest.mark.parametrize("height", [0.0195, 0.01, 0.003])
def test_a_ridge_on_a_ruling_between_samples_is_certified_at_its_height(height):
    # the ridge at x = 1 of a roof 3 m long: ruling 1 of 4, at u = 1/3, between the first
    # grid's samples k/40; the distance from the plane is the roof's height, largest on the ridge
    a = Polyline([[0.0, 0.0, 0.0], [1.0, 0.0, height], [3.0, 0.0, 0.0]])
    b = Polyline([[0.0, 1.0, 0.0], [1.0, 1.0, height], [3.0, 1.0, 0.0]])
    ridge = a.vertex_parameters[1]
    s = np.array([0.0, ridge, 0.5 * (ridge + 1.0), 1.0])
    strip = ruled_between(a, s, b, s)
    tolerance = 0.02
    deviation = certified_deviation(plane(), strip, tolerance)
    assert deviation.bound >= height * (1 - 1e-12)
    assert deviation.bound - height <= AGREE * tolerance
    assert abs(deviation.where[0] - 1.0) <= 1e-9  # found on the ridge
