"""A cone pair next to a fan whose rail stands still at the fan's point, read back by Rhino.

The strip runs between two arcs (radius 4 at z = 0, radius 2 at z = 2); rail A's curve
runs along its arc with its parameter φ(s) = 0.3 ± (s − 0.3)²/…, so it stands still at
s = 0.3 (speed 0, second derivative not), where rulings 4-6 fan out from one point of it.
Rulings 6-7 are not the cone's generators and rail A is at rest at ruling 6: no
developable pairing joins them, so that interval goes out as two cones on its diagonal
(a_6, b_7). The cone over rail A from there had a line across where both its rails stood
still (the diagonal): Rhino found its Jacobian degenerate there and turned its normals by
0.041 rad between the line's two ends (the double bump's strips: up to 2.75 rad); with
rail B brought down to 8 mm of rail A at ruling 7 (a short ruling beside the fan, as on the
double bump), 2.5e-3 rad. The
normals are read with rhino3dm at 1 % in from each end of every isoparametric line across
the face, 1,001 lines and every knot of the face (the joints of its pieces).
"""

from __future__ import annotations

import itertools

import numpy as np
import pytest
import rhino3dm as rh

from tests.support.node_helpers import tree
from torsal.nodes.geometry.curve_rail import ruled_between
from torsal.nodes.geometry.curves import Arc
from torsal.nodes.geometry.curves.parametric import ParametricCurve
from torsal.nodes.geometry.vectors import Plane
from torsal.nodes.io.formats import threedm
from torsal.nodes.io.formats.threedm_unstall import Unstalled, stalled_ends

LOW = Arc(Plane.from_axes(np.zeros(3), np.array([1.0, 0, 0]), np.array([0, 1.0, 0])), 4.0, 0.0, 1.5)
HIGH = Arc(Plane.from_axes(np.array([0, 0, 2.0]), np.array([1.0, 0, 0]), np.array([0, 1.0, 0])),
           2.0, 0.0, 1.5)


def _phi(s: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """A monotone parameter of [0, 1] onto itself that stands still at 0.3 (C1, φ' = 0)."""
    d = np.asarray(s, dtype=float) - 0.3
    return 0.3 + np.where(d >= 0, d * d / 0.7, -d * d / 0.3), np.where(d >= 0, 2 * d / 0.7, -2 * d / 0.3)


def stalling_rail() -> ParametricCurve:
    def first(s):
        at, slope = _phi(s)
        return LOW.derivatives(at, 1)[1] * slope[:, None]

    return ParametricCurve(lambda s: LOW.point_at(_phi(s)[0]), (0.0, 1.0), [first])


def normal_turns(surface: rh.Surface, count: int = 1001) -> float:
    """The largest angle between the normals 1 % in from each end of an isoparametric line
    across the face, over ``count`` lines and one at each of its knots."""
    du, dv = surface.Domain(0), surface.Domain(1)
    knots = surface.ToNurbsSurface().KnotsU
    worst = 0.0
    for u in [*np.linspace(du.T0, du.T1, count), *(knots[i] for i in range(len(knots)))]:
        n0 = surface.NormalAt(u, dv.T0 + 0.01 * (dv.T1 - dv.T0))
        n1 = surface.NormalAt(u, dv.T0 + 0.99 * (dv.T1 - dv.T0))
        x, y = np.array([n0.X, n0.Y, n0.Z]), np.array([n1.X, n1.Y, n1.Z])
        worst = max(worst, float(np.arctan2(np.linalg.norm(np.cross(x, y)), x @ y)))
    return worst


def test_a_rail_that_stands_still_is_run_from_its_stall_at_a_pace_it_moves_at():
    rail = stalling_rail()
    assert stalled_ends(rail, 0.3, 0.7) == (True, False)
    assert stalled_ends(rail, 0.0, 0.3) == (False, True)
    moving = Unstalled(rail, 0.3, 0.7, True, False)
    u = np.linspace(0.3, 0.7, 9)
    # the same points of the same curve, the ends where they were
    assert np.allclose(moving.point_at(u[[0, -1]]), rail.point_at(u[[0, -1]]), atol=1e-15)
    assert np.abs(np.linalg.norm(moving.point_at(u) - np.array([0, 0, 0]), axis=1) - 4.0).max() <= 1e-12
    # it moves from the stall: its slope there is its points' (a difference quotient), |LOW'|·0.4/0.7
    slope = moving.derivatives(np.array([0.3]), 1)[1][0]
    step = 1e-8
    quotient = (moving.point_at([0.3 + step]) - moving.point_at([0.3]))[0] / step
    assert np.linalg.norm(slope) >= 0.5
    assert np.linalg.norm(slope - quotient) <= 1e-6 * np.linalg.norm(slope)


def descending_rail() -> ParametricCurve:
    """A curve over rail A's arc (radius 4) that comes down to 4 mm above it at t = 0.536
    (the angle of rail A at s = 0.7): a short ruling there."""

    def point(t):
        t = np.asarray(t, dtype=float)
        angle = 1.5 * (0.1 + 0.8 * t)
        return np.column_stack([4.0 * np.cos(angle), 4.0 * np.sin(angle), 0.004 + 1.5 * (t - 0.536) ** 2])

    def first(t):
        t = np.asarray(t, dtype=float)
        angle = 1.5 * (0.1 + 0.8 * t)
        return np.column_stack([-4.8 * np.sin(angle), 4.8 * np.cos(angle), 3.0 * (t - 0.536)])

    return ParametricCurve(point, (0.0, 1.0), [first])


@pytest.mark.parametrize(("rail_b", "t"), [
    # 1.2e-12 rad (0.041 rad before, at the diagonal of the cones after the fan)
    (HIGH, [0.0, 0.1, 0.2, 0.22, 0.3, 0.38, 0.42, 0.6, 0.7, 0.8, 1.0]),
    # ruling 7 is 8 mm long, beside the fan: 1.4e-11 rad (2.5e-3 before)
    (descending_rail(), [0.0, 0.05, 0.1, 0.12, 0.15, 0.18, 0.536, 0.6, 0.7, 0.8, 1.0]),
])
def test_a_cone_pair_over_a_rail_that_stands_still_has_normals_that_agree_in_rhino(tmp_path, rail_b, t):
    s = [0.0, 0.1, 0.2, 0.3, 0.3, 0.3, 0.7, 0.8, 0.9, 0.95, 1.0]
    strip = ruled_between(stalling_rail(), np.array(s), rail_b, np.array(t))
    threedm.write_3dm(tmp_path / "s.3dm", threedm.tree_entries(tree({(0,): [strip]}), "S", "Strip"))
    objects = list(rh.File3dm.Read(str(tmp_path / "s.3dm")).Objects)
    kinds = [(o.Attributes.GetUserString("TorsalFace"), o.Attributes.GetUserString("TorsalRulings"))
             for o in objects]
    assert kinds == [("torsal", "1-4"), ("fan", "4-6"), ("torsal", "6-11")]
    for obj in objects:
        if obj.Attributes.GetUserString("TorsalFace") == "torsal":
            assert normal_turns(obj.Geometry.Faces[0].UnderlyingSurface()) <= 1e-6
    # the faces still share their rulings' ends (Rhino's Join makes them one)
    size = float(np.ptp(strip.ruling_lines.reshape(-1, 3), axis=0).max())
    for before, after in itertools.pairwise(objects):
        a = np.array([[v.Location.X, v.Location.Y, v.Location.Z] for v in before.Geometry.Vertices])
        b = np.array([[v.Location.X, v.Location.Y, v.Location.Z] for v in after.Geometry.Vertices])
        assert np.sort(np.linalg.norm(a[:, None] - b[None], axis=2).min(axis=1))[1] <= 1e-9 * size


class _WithBreaks(ParametricCurve):
    """The stalling rail with breaks of its own (as a Paced rail reports its curve's)."""

    def breaks(self) -> np.ndarray:
        return np.array([0.32, 0.45, 0.61, 0.69])


@pytest.mark.parametrize("ends", list(itertools.product((False, True), repeat=2)))
def test_an_unstalled_rails_breaks_are_where_its_own_parameter_reaches_the_rails(ends):
    rail = _WithBreaks(lambda s: LOW.point_at(_phi(s)[0]), (0.0, 1.0))
    moving = Unstalled(rail, 0.3, 0.7, *ends)
    found = moving.breaks()
    assert np.all(np.diff(found) > 0) and found[0] > 0.3 and found[-1] < 0.7
    # there the unstalled rail's points are the rail's at its breaks (its map, √x, 1 − √(1 − x)
    # or arccos(1 − 2x)/π, undone by the table's inverse)
    np.testing.assert_allclose(moving.point_at(found), rail.point_at(rail.breaks()), atol=1e-12)
