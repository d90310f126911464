"""A ruling that runs almost along an edge's tangent: its end normal R × T̂ is shorter than
1e-9·|R|, rounding decides its direction, and the warp there is undefined (NaN), never a
number; just outside that, the warp is the closed-form angle."""

from __future__ import annotations

import math

import numpy as np
import pytest

from torsal.nodes.geometry.developable import warp_angles
from torsal.nodes.geometry.developable.warp import consistently_oriented


def _tilted(theta: float, phi: float) -> np.ndarray:
    """A unit tangent θ rad off the ruling (along x), leaning φ about it from the z axis'
    side: the normal R × T̂ turns by φ from that of a tangent along y."""
    return np.array([[math.cos(theta), math.sin(theta) * math.cos(phi), math.sin(theta) * math.sin(phi)]])


def test_a_ruling_within_1e_9_rad_of_b_tangent_has_no_warp():
    w = warp_angles([[0, 0, 0]], [[3.7, 0, 0]], [[0, 1, 0]], _tilted(5e-10, 0.3))
    assert np.isnan(w[0])


def test_a_ruling_within_1e_9_rad_of_a_tangent_has_no_warp():
    w = warp_angles([[0, 0, 0]], [[3.7, 0, 0]], _tilted(5e-10, 0.3), [[0, 1, 0]])
    assert np.isnan(w[0])


def test_a_ruling_within_1e_9_rad_of_a_tangent_is_not_consistently_oriented():
    oriented = consistently_oriented(np.zeros((1, 3)), np.array([[3.7, 0, 0]]), np.array([[0.0, 1, 0]]),
                                     _tilted(5e-10, 0.0))
    assert not oriented[0]


@pytest.mark.parametrize("theta", [3e-9, 1e-6, 0.5])
def test_just_off_the_tangent_the_warp_is_the_turn_of_the_normal(theta):
    # N1 = x × y = z; N2 = x × T̂ ∝ (0, −sin φ, cos φ): the angle between them is φ
    w = warp_angles([[0, 0, 0]], [[3.7, 0, 0]], [[0, 1, 0]], _tilted(theta, 0.3))
    assert w[0] == pytest.approx(0.3, abs=1e-15)  # measured: ≤ 4.4e-16 for φ in [0.05, 3]
