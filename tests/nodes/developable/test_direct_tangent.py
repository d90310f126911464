"""developable.TangentDevelopable, solved in real graphs."""

from __future__ import annotations

import numpy as np
import pytest

from tests.support.direct_graphs import Chain, helix
from torsal.engine.values import Point
from torsal.nodes.curves.primitives import Line, Polyline
from torsal.nodes.developable.tangent import TangentDevelopable

R, C = 2.0, 0.5  # helix (R cos t, R sin t, C t)


def on_helix(**values) -> Chain:
    chain = Chain()
    helix(chain, R, C, 2.0, "curve")
    chain.add("tan", TangentDevelopable(), **values)
    chain.wire("curve", "Curve", "tan", "Curve")
    return chain.solve()


def lines(chain: Chain) -> np.ndarray:
    return np.array([[r.start, r.end] for r in chain.items("tan", "Rulings")])


def helix_point_and_tangent(t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    point = np.column_stack([R * np.cos(t), R * np.sin(t), C * t])
    tangent = np.column_stack([-R * np.sin(t), R * np.cos(t), np.full_like(t, C)]) / np.hypot(R, C)
    return point, tangent


@pytest.mark.parametrize("two_sided", [False, True])
def test_tangent_developable_of_a_helix_has_warp_below_1e_14(two_sided):
    chain = on_helix(Segments=80, Length=3.0, CuttingLength=0.25, TwoSided=two_sided)
    warp = chain.items("tan", "WarpAngles")
    assert len(warp) == 81
    assert max(warp) < 1e-14  # measured 2.0e-15 and 0


def test_rulings_run_along_the_exact_tangent_from_cutting_length_to_length():
    r = lines(on_helix(Segments=40, Length=3.0, CuttingLength=0.25))
    span = r[:, 1] - r[:, 0]
    assert np.abs(np.linalg.norm(span, axis=1) - 2.75).max() < 1e-12
    # the foot of each ruling on the helix, 0.25 back along the ruling, and its parameter
    direction = span / 2.75
    foot = r[:, 0] - 0.25 * direction
    t = foot[:, 2] / C
    point, tangent = helix_point_and_tangent(t)
    assert np.abs(foot - point).max() < 1e-12
    assert np.abs(direction - tangent).max() < 1e-12


def test_two_sided_rulings_run_from_minus_length_to_length_through_the_curve():
    chain = on_helix(Segments=40, Length=1.5, CuttingLength=0.3, TwoSided=True)
    r = lines(chain)
    assert np.abs(np.linalg.norm(r[:, 1] - r[:, 0], axis=1) - 3.0).max() < 1e-12
    middle = r.mean(axis=1)
    point, tangent = helix_point_and_tangent(middle[:, 2] / C)
    assert np.abs(middle - point).max() < 1e-12
    assert np.abs((r[:, 1] - r[:, 0]) / 3.0 - tangent).max() < 1e-12
    assert chain.texts("tan") == [
        "CuttingLength is not used when TwoSided is on: each ruling runs from −Length to Length "
        "through the curve"
    ]


def test_a_straight_curve_warns_that_the_surface_degenerates_to_a_line():
    chain = Chain()
    chain.add("curve", Line(), Start=Point(0, 0, 0), End=Point(3, 4, 0))
    chain.add("tan", TangentDevelopable(), Segments=6, Length=2.0)
    chain.wire("curve", "Line", "tan", "Curve")
    chain.solve()
    assert chain.result("tan").state == "warning"
    assert chain.texts("tan") == [
        "The curve is straight, so all its tangents lie on one line: the tangent developable "
        "degenerates to that line (no area, no tangent plane: WarpAngles NaN); give the curve some bend"
    ]
    r = lines(chain)
    assert np.abs(np.cross(r[:, 1] - r[:, 0], [3.0, 4.0, 0.0])).max() < 1e-12


def test_a_polyline_has_no_bend_at_its_stations_and_warns():
    chain = Chain()
    chain.add("curve", Polyline(), Vertices=[Point(0, 0, 0), Point(1, 0, 0), Point(1, 1, 1)])
    chain.add("tan", TangentDevelopable(), Segments=5)
    chain.wire("curve", "Polyline", "tan", "Curve")
    chain.solve()
    assert chain.result("tan").state == "warning"
    assert chain.texts("tan")[0].startswith("The curve has no bend at any station")


def test_length_not_above_cutting_length_warns():
    chain = on_helix(Length=0.5, CuttingLength=0.5)
    assert chain.result("tan").state == "warning"
    assert chain.texts("tan") == [
        "Length (0.5) must be greater than CuttingLength (0.5): the ruling runs from CuttingLength "
        "to Length along the tangent"
    ]


def test_two_sided_needs_a_positive_length():
    chain = on_helix(Length=-1.0, TwoSided=True)
    assert chain.result("tan").state == "warning"
    assert chain.texts("tan") == [
        "Length is -1: two-sided rulings run from −Length to Length, so give a positive Length"
    ]


def test_segments_zero_warns():
    chain = on_helix(Segments=0)
    assert chain.texts("tan") == [
        "Segments must be at least 1, not 0"
    ]
