"""A ruled face fitted to a developable's rails is moved until its normals agree along its lines.

The developable is a cone (apex (0, 0, 4)) between a circle of radius 4 at z = 0 and a
curve on the cone from half to 0.7 of the way to it, paired at the same angle: every
line through the apex, so the
exact face is developable. Its rails are fitted by least squares on few knots (the fit's
tangents are off, and the face twists); after :func:`untwisted` the face's normals 1 % in
from either end of each line across agree, measured from finite differences of the face's
points (not from the code under test), and its rails stay within the tolerance.
"""

from __future__ import annotations

import numpy as np
from scipy.interpolate import BSpline, make_lsq_spline

from torsal.nodes.io.formats.threedm_untwist import untwisted


def cone_rails(s: np.ndarray, pace: float = 0.6) -> np.ndarray:
    """Both rails side by side at parameters ``s`` in [0, 1]: the angle runs unevenly
    (θ = 1.5 (s + pace s (1 − s))) so a cubic needs several spans."""
    theta = 1.5 * (s + pace * s * (1.0 - s))
    low = np.column_stack([4.0 * np.cos(theta), 4.0 * np.sin(theta), np.zeros_like(s)])
    apex = np.array([0.0, 0.0, 4.0])
    share = (0.5 + 0.2 * s)[:, None]  # rail B not an affine image of A (a fit of both is no cone)
    return np.hstack([low, apex + share * (low - apex)])


def twist(spline: BSpline, count: int = 401) -> float:
    """The largest angle between the face's normals at v = 0.01 and v = 0.99, its tangents
    along by central differences of its points."""
    u = np.linspace(0.0, 1.0, count)[1:-1]
    step = 1e-6

    def point(at: np.ndarray, v: float) -> np.ndarray:
        rails = spline(at)
        return (1.0 - v) * rails[:, :3] + v * rails[:, 3:]

    angles = []
    for v in (0.01, 0.99):
        along = point(u + step, v) - point(u - step, v)
        across = point(u, 1.0) - point(u, 0.0)
        angles.append(np.cross(along, across))
    near, far = angles
    scale = np.linalg.norm(near, axis=1) * np.linalg.norm(far, axis=1)
    cosine = np.einsum("ij,ij->i", near, far) / scale
    sine = np.linalg.norm(np.cross(near, far), axis=1) / scale
    return float(np.arctan2(sine, cosine).max())


def cone_slopes(s: np.ndarray, pace: float = 0.6) -> np.ndarray:
    """d/ds of :func:`cone_rails`, in closed form."""
    theta = 1.5 * (s + pace * s * (1.0 - s))
    turn = 1.5 * (1.0 + pace * (1.0 - 2.0 * s))
    low = np.column_stack([4.0 * np.cos(theta), 4.0 * np.sin(theta), np.zeros_like(s)])
    slope = np.column_stack([-4.0 * np.sin(theta), 4.0 * np.cos(theta), np.zeros_like(s)]) * turn[:, None]
    apex = np.array([0.0, 0.0, 4.0])
    share = (0.5 + 0.2 * s)[:, None]
    return np.hstack([slope, 0.2 * (low - apex) + share * slope])


def fitted(knots_inside: int) -> tuple[BSpline, np.ndarray, np.ndarray]:
    """The rails fitted as the exporter fits them: clamped to the end rulings, the next
    control points on the rails' end tangents, the others by least squares."""
    at = np.linspace(0.0, 1.0, 401)
    data = cone_rails(at)
    inner = np.linspace(0.0, 1.0, knots_inside + 2)[1:-1]
    knots = np.concatenate([[0.0] * 4, inner, [1.0] * 4])
    count = len(knots) - 4
    controls = np.zeros((count, 6))
    slopes = cone_slopes(np.array([0.0, 1.0]))
    controls[0], controls[-1] = data[0], data[-1]
    controls[1] = data[0] + knots[4] / 3.0 * slopes[0]
    controls[-2] = data[-1] - (1.0 - knots[count - 1]) / 3.0 * slopes[1]
    basis = BSpline.design_matrix(at, knots, 3).toarray()
    ends = [0, 1, count - 2, count - 1]
    rest = data - basis[:, ends] @ controls[ends]
    controls[2:count - 2] = np.linalg.lstsq(basis[:, 2:count - 2], rest, rcond=None)[0]
    return BSpline(knots, controls, 3), at, data


def test_a_fitted_cone_face_is_made_developable_within_the_tolerance():
    spline, at, data = fitted(4)
    tolerance = 1e-3  # of a face 4 m across
    assert np.abs(spline(at) - data).max() <= tolerance  # measured 8.5e-4
    before = twist(spline)
    assert before > 1e-4  # the least squares fit twists (measured 4.5e-4 rad)
    moved, distance, angle = untwisted(spline, at, data, tolerance, 1e-5)
    assert twist(moved) <= 1e-5, (before, twist(moved), angle)  # measured 9.6e-6
    rails = moved(at)
    off = np.maximum(np.linalg.norm(rails[:, :3] - data[:, :3], axis=1),
                     np.linalg.norm(rails[:, 3:] - data[:, 3:], axis=1))
    assert off.max() <= tolerance and abs(off.max() - distance) <= 1e-12
    # its ends stay: the end rulings and the rails' end tangents
    count = len(moved.t) - 4
    first = np.asarray(spline.c)[[0, len(spline.t) - 5]]
    np.testing.assert_array_equal(np.asarray(moved.c)[[0, count - 1]], first)
    ends = np.array([0.0, 1.0])
    np.testing.assert_allclose(moved.derivative()(ends), spline.derivative()(ends), rtol=1e-12, atol=1e-12)


def test_a_face_that_cannot_be_developable_nearby_is_returned_as_twisted_as_it_is():
    """Rails of a hyperbolic paraboloid (lines (s, 0, 0) → (s, 1, s)): no developable face
    lies within 1e-6 of them; the result says how much it still twists."""
    at = np.linspace(0.0, 1.0, 201)
    data = np.column_stack([at, 0 * at, 0 * at, at, 1 + 0 * at, at])
    spline = make_lsq_spline(at, data, np.array([0.0] * 4 + [0.5] + [1.0] * 4), 3)
    moved, distance, angle = untwisted(spline, at, data, 1e-6, 1e-7)
    assert angle > 0.1 and twist(moved) > 0.1  # the paraboloid turns by 45° along a line
    assert distance <= 1e-6
