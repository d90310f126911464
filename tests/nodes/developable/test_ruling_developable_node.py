"""developable.RulingDevelopable through real graphs: curves drawn by curves.ParametricCurve
nodes (or handed in by a source node) wired into the node and solved by the Solver."""

from __future__ import annotations

import math

import numpy as np

from tests.support.direct_graphs import Chain
from tests.support.node_helpers import out, run, texts, tree
from tests.support.warp_check import shared_both_sides
from torsal.engine.values import Domain
from torsal.nodes.curves.splines import ParametricCurve
from torsal.nodes.developable.ruling_developable import RulingDevelopable
from torsal.nodes.geometry.curves import Line

#: Cone with its apex at the origin, axis z, half-angle 0.5 rad: w·(sin α cos u, sin α sin u, cos α).
SIN, COS = math.sin(0.5), math.cos(0.5)
#: B's parameter is warped: τ(t) = (e^{1.5 t} − 1)/(e^{1.5} − 1), so B is re-parameterised non-uniformly.
TAU = "((exp(1.5 * t) - 1) / (exp(1.5) - 1))"


def cone_curve(chain: Chain, node_id: str, angle: str, distance: str) -> str:
    """A curves.ParametricCurve on the cone: generator angle u(t), distance w(t) from the apex."""
    return chain.add(
        node_id, ParametricCurve(),
        X=f"({distance}) * {SIN!r} * cos({angle})",
        Y=f"({distance}) * {SIN!r} * sin({angle})",
        Z=f"({distance}) * {COS!r}",
        Domain=Domain(0.0, 1.0),
    )


def cone_graph(segments: int = 40) -> Chain:
    """Two wavy, non-planar curves cut from one cone over 2.5 rad of its generators."""
    chain = Chain()
    cone_curve(chain, "a", "2.5 * t", "2 + 0.3 * sin(17.5 * t)")
    cone_curve(chain, "b", f"2.5 * {TAU}", f"4 + 0.5 * sin(12.5 * {TAU} + 1)")
    chain.add("strip", RulingDevelopable(), Segments=segments)
    chain.wire("a", "Curve", "strip", "CurveA")
    chain.wire("b", "Curve", "strip", "CurveB")
    return chain.solve()


def lines(result, port: str = "Rulings") -> list:
    return out(result, port)[(0,)]


def test_cone_cut_curves_give_rulings_with_warp_below_1e_11_all_valid():
    chain = cone_graph()
    assert chain.result("strip").state == "ok"
    warp = chain.items("strip", "WarpAngles")
    assert len(warp) == 41
    assert max(warp) < 1e-11  # measured 1.9e-12
    assert all(chain.items("strip", "Valid"))


def test_cone_cut_curves_give_rulings_along_the_cones_generators():
    """Each recovered ruling, extended, passes through the apex (the origin)."""
    chain = cone_graph()
    rulings = chain.items("strip", "Rulings")
    starts = np.array([r.start for r in rulings])
    ends = np.array([r.end for r in rulings])
    apex_distance = np.linalg.norm(np.cross(starts, ends), axis=1) / np.linalg.norm(ends - starts, axis=1)
    assert apex_distance.max() < 2e-12  # measured 2.2e-13, the curves about 2 from the apex


def test_cone_cut_surface_passes_exactly_through_its_rulings():
    chain = cone_graph(segments=10)
    surface = chain.item("strip", "Surface")
    rulings = chain.items("strip", "Rulings")
    u = np.linspace(0.0, 1.0, len(rulings))
    assert np.allclose(surface.point_at(u, np.zeros_like(u)), [r.start for r in rulings], atol=1e-12)
    assert np.allclose(surface.point_at(u, np.ones_like(u)), [r.end for r in rulings], atol=1e-12)


def zve_middle():
    """The ZVE roof's middle: two straight segments at an angle, in one (tilted) plane."""
    frame = np.array([[1.0, 0.0, 0.0], [0.0, 0.6, 0.8], [0.0, -0.8, 0.6]])  # plane tilted about x
    a0, a1 = np.array([0.0, 0.0, 0.0]) @ frame, np.array([2.0, 0.0, 0.0]) @ frame
    b0, b1 = np.array([0.0, 1.0, 0.0]) @ frame, np.array([3.0, 2.0, 0.0]) @ frame
    return Line(a0, a1), Line(b0, b1)


def test_two_straight_segments_at_an_angle_give_two_triangle_fans():
    a, b = zve_middle()
    result = run(RulingDevelopable(), CurveA=tree({(0,): [a]}), CurveB=tree({(0,): [b]}), Segments=4)
    rulings = lines(result)
    starts = np.array([r.start for r in rulings])
    ends = np.array([r.end for r in rulings])
    to_b_start = np.all(np.isclose(ends, b.start, atol=1e-12), axis=1)
    from_a_end = np.all(np.isclose(starts, a.end, atol=1e-12), axis=1)
    # first triangle: every station of A to B's first corner; second: A's last corner to all of B
    assert to_b_start.tolist() == [True] * 5 + [False] * (len(rulings) - 5)
    assert from_a_end[4:].all() and not from_a_end[:4].any()
    assert np.allclose(ends[-1], b.end, atol=1e-12)
    assert max(out(result, "WarpAngles")[(0,)]) < 1e-12
    assert all(out(result, "Valid")[(0,)])


def test_two_triangle_fans_are_announced_with_their_ruling_count():
    a, b = zve_middle()
    result = run(RulingDevelopable(), CurveA=tree({(0,): [a]}), CurveB=tree({(0,): [b]}), Segments=4)
    assert result.state == "ok"
    count = len(lines(result))
    assert texts(result) == [
        f"{count} rulings: 5 from the stations and {count - 5} in fans through single points "
        "(the flat triangles of the strip)"
    ]


def test_curves_that_bound_no_developable_warn_with_the_fan_share_and_mark_every_ruling_fan():
    """Two skew straight lines: det[B − A, A', B'] is the same non-zero number everywhere, so
    the strip is closed by flat triangles end to end; swapping or reversing does not help,
    so no hint is given."""
    a, b = Line([0, 0, 0], [2, 0, 0]), Line([0, 1, 1], [3, 1, 2])
    result = run(RulingDevelopable(), CurveA=tree({(0,): [a]}), CurveB=tree({(0,): [b]}), Segments=39)
    assert result.state == "warning"
    assert texts(result) == [
        "no torsal ruling within 0.01 rad keeps the rulings' order at 40 of 40 stations: closed by flat "
        "triangles (100 % of the strip's area), above FanLimit 10 %"
    ]
    # no ruling is torsal: the strip's end rulings lie beside one flat triangle each (a fan);
    # every other one has a triangle through a point of A on one side and through a point of
    # B on the other, whose planes (through the ruling and A', and through it and B') differ:
    # det[R, A', B'] is the same non-zero number on every ruling, so each is a crease
    kinds = np.array(out(result, "Kind")[(0,)])
    starts = np.array([line.start for line in lines(result)])
    ends = np.array([line.end for line in lines(result)])
    in_fan = shared_both_sides(starts) | shared_both_sides(ends)
    np.testing.assert_array_equal(kinds, np.where(in_fan, "fan", "crease"))
    assert (kinds == "crease").sum() > 20
    assert out(result, "Torsal")[(0,)] == [0.0]
    assert not np.array(out(result, "Valid")[(0,)])[~in_fan].any()
    assert len(lines(result)) >= 40  # still drawn (as flat triangles), never hidden


def test_a_fan_share_within_fan_limit_is_reported_without_a_warning():
    a, b = Line([0, 0, 0], [2, 0, 0]), Line([0, 1, 1], [3, 1, 2])
    result = run(RulingDevelopable(), CurveA=tree({(0,): [a]}), CurveB=tree({(0,): [b]}), Segments=9,
                 FanLimit=1.0)
    assert result.state == "ok"
    assert texts(result) == [
        "no torsal ruling within 0.01 rad keeps the rulings' order at 10 of 10 stations: closed by flat "
        "triangles (100 % of the strip's area)"
    ]


def test_a_fan_limit_outside_0_to_1_is_an_error():
    a, b = Line([0, 0, 0], [2, 0, 0]), Line([0, 1, 1], [3, 1, 2])
    result = run(RulingDevelopable(), CurveA=tree({(0,): [a]}), CurveB=tree({(0,): [b]}), FanLimit=1.5)
    assert result.state == "error"
    assert texts(result) == ["FanLimit must be a share of the strip's area from 0 to 1, such as 0.1, not 1.5"]


def test_a_looser_warp_tolerance_accepts_the_same_rulings():
    a, b = Line([0, 0, 0], [2, 0, 0]), Line([0, 1, 1], [3, 1, 2])
    result = run(RulingDevelopable(), CurveA=tree({(0,): [a]}), CurveB=tree({(0,): [b]}), Segments=4,
                 WarpTolerance=0.3)
    assert result.state == "ok"
    assert all(out(result, "Valid")[(0,)])


def test_coincident_curves_are_an_error_saying_so():
    a = Line([0, 0, 0], [2, 0, 0])
    result = run(RulingDevelopable(), CurveA=tree({(0,): [a]}), CurveB=tree({(0,): [a.reversed()]}))
    assert result.state == "error"
    assert texts(result) == [
        "CurveA and CurveB are the same curve, so there is no strip between them: give two "
        "different edges (e.g. a bottom and a top curve)"
    ]


def test_zero_segments_is_a_warning_saying_what_to_give():
    a, b = Line([0, 0, 0], [2, 0, 0]), Line([0, 1, 0], [2, 1, 0])
    result = run(RulingDevelopable(), CurveA=tree({(0,): [a]}), CurveB=tree({(0,): [b]}), Segments=0)
    assert result.state == "warning"
    assert texts(result) == ["Segments must be at least 1, not 0"]


def test_a_nan_warp_tolerance_is_a_warning():
    a, b = Line([0, 0, 0], [2, 0, 0]), Line([0, 1, 0], [2, 1, 0])
    result = run(RulingDevelopable(), CurveA=tree({(0,): [a]}), CurveB=tree({(0,): [b]}),
                 WarpTolerance=float("nan"))
    assert result.state == "warning"
    assert texts(result) == ["WarpTolerance must be an angle of 0 rad or more, such as 0.01, not nan"]


def test_a_missing_curve_is_a_warning_naming_it():
    a = Line([0, 0, 0], [2, 0, 0])
    result = run(RulingDevelopable(), CurveA=tree({(0,): [a]}), CurveB=tree({(0,): [None]}))
    assert result.state == "warning"
    assert texts(result) == ["CurveB is empty: connect a curve"]
