"""RulingDevelopable kernel: the developable strip between two curves.

The bars from the toolbox spec: on curve pairs cut from a cone, a cylinder and the
tangent developable of a helix (B re-parameterised non-uniformly) the rulings are the
true ones (partner error < 1e-8), every warp < 1e-7 rad and no two rulings cross;
swapping A and B gives the same surface; planar pieces become fans; curves that bound
no developable are flagged with a count.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from tests.support import curve_pairs
from tests.support.strip_triangles import hausdorff, strip_triangles
from torsal.nodes.geometry.curves import Arc, Circle, Line, Polyline
from torsal.nodes.geometry.developable import ruling_developable, ruling_developables
from torsal.nodes.geometry.developable.alternatives import better_pairing
from torsal.nodes.geometry.vectors import Plane

SMOOTH_PAIRS = ["cone", "cylinder", "helix_developable"]


@pytest.fixture(scope="module", params=[*SMOOTH_PAIRS, "nurbs_cone"])
def pair(request: pytest.FixtureRequest) -> curve_pairs.Pair:
    return curve_pairs.PAIRS[request.param]()


# -- curves cut from known developables ------------------------------------------------------


@pytest.mark.parametrize("segments", [40, 200])
def test_rulings_between_curves_on_a_developable_are_its_true_rulings(pair, segments):
    result = ruling_developable(pair.a, pair.b, segments)
    assert result.message is None
    assert result.valid.all()
    assert len(result.s) == segments + 1
    np.testing.assert_allclose(result.t, pair.partner(result.s), rtol=0, atol=1e-8)
    assert result.max_warp < 1e-7


def test_partner_parameters_are_exact_to_rounding(pair):
    result = ruling_developable(pair.a, pair.b, 100)
    assert np.abs(result.t - pair.partner(result.s)).max() < 1e-12
    assert result.max_warp < 1e-12


def test_no_two_rulings_cross(pair):
    result = ruling_developable(pair.a, pair.b, 200)
    assert np.all(np.diff(result.s) >= 0)
    assert np.all(np.diff(result.t) >= 0)


def test_normals_at_both_ends_point_the_same_way(pair):
    result = ruling_developable(pair.a, pair.b, 60)
    assert np.abs(result.signed_warp).max() < 1e-7


def test_ruling_ends_lie_on_their_curves(pair):
    result = ruling_developable(pair.a, pair.b, 30)
    np.testing.assert_allclose(result.starts, pair.a.point_at(result.s), atol=1e-14)
    np.testing.assert_allclose(result.ends, pair.b.point_at(result.t), atol=1e-14)


def test_stations_are_spaced_evenly_in_arc_length_along_a(pair):
    result = ruling_developable(pair.a, pair.b, 50)
    steps = np.diff(pair.a.length_at(result.s))
    np.testing.assert_allclose(steps, pair.a.length / 50, rtol=0, atol=1e-6 * pair.a.length)


def test_stations_can_be_spaced_evenly_in_parameter(pair):
    result = ruling_developable(pair.a, pair.b, 50, spacing="parameter")
    np.testing.assert_allclose(result.s, np.linspace(0, 1, 51))
    np.testing.assert_allclose(result.t, pair.partner(result.s), atol=1e-8)


@pytest.mark.parametrize("name", SMOOTH_PAIRS)
def test_swapping_curves_a_and_b_gives_the_same_surface(name):
    pair = curve_pairs.PAIRS[name]()
    forward = ruling_developable(pair.a, pair.b, 200)
    swapped = ruling_developable(pair.b, pair.a, 200)
    assert swapped.valid.all()
    distance = hausdorff((forward.starts, forward.ends), (swapped.ends, swapped.starts))
    assert distance < 1e-4 * pair.size


# -- plane sections of cylinders and cones whose cross-sections have inflection points -------
#
# Where a section inflects, the true root of det[B − A, A', B'] and a second root come
# within a sample interval of each other: a search by sign changes between samples of B
# misses both (before issue 10: rulings 0.013 rad off, partners off by 0.045, all Valid).

SECTION_PAIRS = ["cylinder_sections", "cone_sections"]


def independent_warp(pair: curve_pairs.Pair, s: np.ndarray, t: np.ndarray) -> np.ndarray:
    """The angle (0 to π) between the end normals R × A'(s) and R × B'(t), from the pair's
    analytic curves (not the solver's values, nor its warp function)."""
    a, ta = pair.a.derivatives(s, 1)
    b, tb = pair.b.derivatives(t, 1)
    n1, n2 = np.cross(b - a, ta), np.cross(b - a, tb)
    return np.arctan2(np.linalg.norm(np.cross(n1, n2), axis=1), np.einsum("ij,ij->i", n1, n2))


def test_the_section_directrix_has_more_than_one_inflection():
    u = np.linspace(0.01, curve_pairs.DIRECTRIX_U - 0.01, 4001)
    _, d1, d2 = curve_pairs._directrix(u)
    bending = np.cross(d1, d2)[:, 2]
    assert (np.diff(np.sign(bending)) != 0).sum() == 2


@pytest.mark.parametrize("segments", [100, 400, 2000])
@pytest.mark.parametrize("name", SECTION_PAIRS)
def test_sections_with_inflections_get_their_true_generators(name, segments):
    pair = curve_pairs.PAIRS[name]()
    result = ruling_developable(pair.a, pair.b, segments)
    assert result.message is None
    assert result.valid.all()
    assert np.abs(result.t - pair.partner(result.s)).max() < 1e-8
    assert independent_warp(pair, result.s, result.t).max() < 1e-7


@pytest.mark.parametrize("name", SECTION_PAIRS)
def test_rulings_between_sections_with_inflections_never_cross(name):
    pair = curve_pairs.PAIRS[name]()
    result = ruling_developable(pair.a, pair.b, 400)
    assert np.all(np.diff(result.s) >= 0) and np.all(np.diff(result.t) >= 0)



def f_and_f_t(pair: curve_pairs.Pair, s: np.ndarray, t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """det[B − A, A', B'] and its t-derivative det[B − A, A', B''] from the pair's analytic
    curves, each over the size of its terms (|B − A|·|A'|·|B'| and |B − A|·|A'|·|B''|)."""
    a, ta = pair.a.derivatives(s, 1)
    b, tb, tbb = pair.b.derivatives(t, 2)
    plane = np.cross(b - a, ta)
    scale = np.linalg.norm(b - a, axis=1) * np.linalg.norm(ta, axis=1)
    return (np.einsum("ij,ij->i", plane, tb) / (scale * np.linalg.norm(tb, axis=1)),
            np.einsum("ij,ij->i", plane, tbb) / (scale * np.linalg.norm(tbb, axis=1)))


@pytest.mark.parametrize("spacing", ["parameter", "length"])
def test_a_generator_through_inflections_of_both_sections_is_found_to_rounding(spacing):
    """A's stations s = 1/3 and 2/3 (30 segments) lie on the directrix's inflections
    u = 4/3 and 8/3 (by parameter: A is S(U·s); by length too: each third of the directrix
    is as long, y' running over the same values). There B'' lies along the generator, so
    f and f_t both vanish at the true partner: a double root, which rounding alone blurs
    over ~1e-9 of B (the partner was 1.4e-9 off; measured now 2.3e-14)."""
    pair = curve_pairs.cylinder_sections_pair()
    result = ruling_developable(pair.a, pair.b, 30, spacing=spacing)
    at = np.flatnonzero(np.abs(result.s[:, None] - [1 / 3, 2 / 3]).min(axis=1) <= 1e-12)
    assert len(at) == 2
    s = result.s[at]
    f, f_t = f_and_f_t(pair, s, pair.partner(s))
    assert np.abs(f).max() < 1e-14 and np.abs(f_t).max() < 1e-12  # (a double root: 2e-14 measured)
    np.testing.assert_allclose(result.t, pair.partner(result.s), rtol=0, atol=1e-12)
    assert result.valid.all()

# -- parallel planar curves: the orientation test -------------------------------------------------


def test_coaxial_arcs_give_the_frustum_not_the_double_cone_through_their_centre():
    """Two coaxial arcs sweeping 300° have antiparallel tangents at opposite angles too:
    that root (the double cone through the common centre) has flipped normals and is
    rejected; every torsal ruling joins points at the same angle. The upper arc runs 20°
    further at both ends: flat fans through the lower arc's ends reach them."""
    low = Arc(Plane.from_normal([0, 0, 0], [0, 0, 1]), 2.0, 0.0, math.radians(300))
    high = Arc(Plane.from_normal([0, 0, 1.5], [0, 0, 1]), 1.2, math.radians(-20), math.radians(320))
    result = ruling_developable(low, high, 60)
    torsal = ~result.fan
    assert torsal[result.stations].all() and result.valid[torsal].all()
    angle_low = np.arctan2(result.starts[torsal, 1], result.starts[torsal, 0])
    angle_high = np.arctan2(result.ends[torsal, 1], result.ends[torsal, 0])
    np.testing.assert_allclose(np.unwrap(angle_high), np.unwrap(angle_low), atol=1e-12)
    np.testing.assert_allclose(result.ends[[0, -1]], high.point_at(np.array([0.0, 1.0])), atol=1e-12)
    assert set(result.s[result.fan]) == {0.0, 1.0}


# -- planar pieces and fans ---------------------------------------------------------------------


def test_two_straight_segments_at_an_angle_give_two_triangles():
    """A planar quad: a fan through one corner of B, then a fan through the far corner of
    A, split along the shorter diagonal A(1)–B(0)."""
    a = Line([0, 0, 0], [4, 0, 0])
    b = Line([0.5, 2, 0], [3, 3, 0])
    result = ruling_developable(a, b, 8)
    assert result.message is None
    assert result.valid.all()
    through_b0 = np.linalg.norm(result.ends - b.start, axis=1) < 1e-12
    through_a1 = np.linalg.norm(result.starts - a.end, axis=1) < 1e-12
    assert np.all(through_b0 | through_a1)
    assert through_b0.sum() == 9  # the fan through B(0): one ruling per station
    assert through_a1.sum() >= 3  # the fan through A(1) spans B with its own rulings
    np.testing.assert_allclose(result.ends[through_a1][[0, -1]], [b.start, b.end], atol=1e-12)
    # the union of the two fans is the whole quad
    triangles = strip_triangles(result.starts, result.ends, ku=1, kv=1)
    area = 0.5 * np.linalg.norm(
        np.cross(triangles[:, 1] - triangles[:, 0], triangles[:, 2] - triangles[:, 0]), axis=1
    )
    quad = 0.5 * abs(np.cross(b.end - a.start, b.start - a.end)[2])
    assert area.sum() == pytest.approx(quad, rel=1e-12)


def test_planar_quad_splits_along_its_shorter_diagonal():
    a = Line([0, 0, 0], [4, 0, 0])
    b = Line([-1, 2, 0], [2, 3, 0])  # now A(0)–B(1) is the shorter diagonal
    result = ruling_developable(a, b, 6)
    through_a0 = np.linalg.norm(result.starts - a.start, axis=1) < 1e-12
    through_b1 = np.linalg.norm(result.ends - b.end, axis=1) < 1e-12
    assert np.all(through_a0 | through_b1)
    assert through_a0.any() and through_b1.any()


def zve_roof_middle() -> tuple[Arc, Polyline, list[float]]:
    """A façade arc below and, above it in a parallel plane, a polyline whose straight
    pieces are parallel to the arc's tangents at three angles (the ZVE roof's inset edge)."""
    radius, height = 5.0, 2.0
    first, last = math.radians(235), math.radians(305)
    middle = first + 0.37 * (last - first)
    arc = Arc(Plane.from_normal([0, 0, 0], [0, 0, 1]), radius, first, last)
    points = [np.array([0.7 * radius * math.cos(first), 0.7 * radius * math.sin(first), height])]
    for angle, length in ((first, 2.0), (middle, 2.5), (last, 2.0)):
        points.append(points[-1] + length * np.array([-math.sin(angle), math.cos(angle), 0.0]))
    return arc, Polyline(np.array(points)), [first, middle, last]


def test_straight_pieces_of_b_get_fans_from_one_point_of_a_and_corners_get_cones():
    arc, polyline, angles = zve_roof_middle()
    result = ruling_developable(arc, polyline, 20)
    assert result.message is None
    assert result.valid.all()
    assert result.max_warp < 1e-12
    # every ruling runs from a fan apex on the arc or to a corner of the polyline
    apex_angles = np.arctan2(result.starts[:, 1], result.starts[:, 0]) % (2 * math.pi)
    at_apex = np.min(np.abs(apex_angles[:, None] - np.array(angles)[None, :]), axis=1) < 1e-9
    corners = polyline.points[1:-1]
    at_corner = np.min(np.linalg.norm(result.ends[:, None, :] - corners[None], axis=2), axis=1) < 1e-12
    assert np.all(at_apex | at_corner)
    # three fans (one per straight piece) and two cones, covering both curves
    assert len(np.unique(result.s[~result.stations])) == 3
    assert result.s[0] == 0 and result.s[-1] == 1
    assert result.t[0] == 0 and result.t[-1] == 1
    for vertex in polyline.vertex_parameters:
        assert np.any(np.abs(result.t - vertex) < 1e-12)


def test_a_fan_through_an_interior_point_of_a_starts_where_a_is_parallel_to_the_straight_piece():
    arc, polyline, _ = zve_roof_middle()
    result = ruling_developable(arc, polyline, 20)
    s_star = np.unique(result.s[~result.stations])[1]
    tangent = arc.tangent_at(s_star)
    piece = polyline.points[2] - polyline.points[1]
    assert np.linalg.norm(np.cross(tangent, piece / np.linalg.norm(piece))) < 1e-12


def test_fan_rulings_are_about_as_far_apart_as_the_stations():
    arc, polyline, _ = zve_roof_middle()
    result = ruling_developable(arc, polyline, 40)
    station_step = arc.length / 40
    fan = ~result.stations
    fan_steps = np.linalg.norm(np.diff(result.ends[fan], axis=0), axis=1)
    fan_steps = fan_steps[(fan_steps > 0) & np.isclose(np.diff(result.s[fan]), 0)]
    assert fan_steps.max() <= station_step * (1 + 1e-9)
    assert fan_steps.min() >= 0.5 * station_step


def test_a_corner_of_a_gets_a_cone_of_rulings_and_its_straight_legs_fans_through_b():
    """A V below an arc in a parallel plane: each leg of the V leans on the one point of
    the arc whose tangent is parallel to it (a triangle), and between them the rulings
    fan out from the V's corner (a cone)."""
    v = Polyline([[-3, 0.5, 0], [0, -1, 0], [3, 0.5, 0]])
    arc = Arc(Plane.from_normal([0, 2, 2], [0, 0, 1]), 4.0, math.radians(200), math.radians(340))
    result = ruling_developable(v, arc, 12)
    # the arc runs on beyond the legs' partners: flat fans through the V's ends reach its ends
    assert set(result.s[result.fan]) == {0.0, 1.0}
    assert result.valid[~result.fan].all() and result.warp[~result.fan].max() < 1e-12
    corner = np.linalg.norm(result.starts - v.points[1], axis=1) < 1e-12
    assert corner.sum() > 2 and result.stations[corner].sum() == 1  # the station at the corner, plus its fan
    for leg, (start, end) in enumerate(((0, 1), (1, 2))):
        direction = v.points[end] - v.points[start]
        torsal = ~corner & ~result.fan
        on_leg = torsal & (result.s < 0.5) if leg == 0 else torsal & (result.s > 0.5)
        partner = result.ends[on_leg]
        np.testing.assert_allclose(partner, np.broadcast_to(partner[0], partner.shape), atol=1e-12)
        tangent = arc.tangent_at(result.t[on_leg][0])
        assert np.linalg.norm(np.cross(tangent, direction / np.linalg.norm(direction))) < 1e-12


def test_closed_curves_with_seams_apart_are_joined_all_round():
    """Two circles on one cone whose seams are a quarter turn apart."""
    tan = math.tan(0.5)
    low = Circle(Plane.from_normal([0, 0, 1], [0, 0, 1]), tan)
    high = Circle(Plane.from_axes([0, 0, 2], [0, 1, 0], [-1, 0, 0]), 2 * tan)
    result = ruling_developable(low, high, 24)
    assert result.message is None and result.valid.all()
    turn = np.angle(
        np.exp(
            1j
            * (
                np.arctan2(result.ends[:, 1], result.ends[:, 0])
                - np.arctan2(result.starts[:, 1], result.starts[:, 0])
            )
        )
    )
    assert np.abs(turn).max() < 1e-12
    # t rises from the partner of A's start, wraps once through B's seam, and returns to it
    assert result.t[0] == pytest.approx(0.75) and result.t[-1] == pytest.approx(0.75)
    assert (np.diff(result.t) < 0).sum() == 1


def test_one_segment_is_two_rulings_or_the_two_triangles_of_a_planar_quad():
    pair = curve_pairs.PAIRS["cone"]()
    cone = ruling_developable(pair.a, pair.b, 1)
    np.testing.assert_allclose(cone.t, pair.partner(np.array([0.0, 1.0])), atol=1e-12)
    planar = ruling_developable(Line([0, 0, 0], [1, 0, 0]), Line([0, 1, 1], [1, 1, 1]), 1)
    np.testing.assert_allclose(planar.t, [0, 0, 1])
    np.testing.assert_allclose(planar.s, [0, 1, 1])


# -- curves that bound no developable --------------------------------------------------------


def test_skew_lines_bound_no_developable_and_every_station_is_flagged():
    """Between two skew lines the only ruled surfaces are warped (a hyperbolic paraboloid
    for the even pairing): det[B − A, A', B'] is a non-zero constant."""
    result = ruling_developable(Line([0, 0, 0], [1, 0, 0]), Line([0, 1, 0], [1, 1, 1]), 10, 0.01)
    assert result.fan.all() and result.fan_share == 1.0
    assert result.message == (
        "no torsal ruling within 0.01 rad keeps the rulings' order at 11 of 11 stations: "
        "closed by flat triangles (100 % of the strip's area)"
    )


def test_where_no_ruling_is_torsal_the_strip_is_closed_by_flat_triangles_end_to_end():
    a, b = Line([0, 0, 0], [1, 0, 0]), Line([0, 1, 0], [1, 1, 1])
    result = ruling_developable(a, b, 10, 0.01)
    assert result.s[0] == result.t[0] == 0.0 and result.s[-1] == result.t[-1] == 1.0
    assert np.all(np.diff(result.s) >= 0) and np.all(np.diff(result.t) >= 0)
    # every two consecutive rulings share an end: each piece between them is a triangle
    same_start = np.linalg.norm(np.diff(result.starts, axis=0), axis=1) == 0
    same_end = np.linalg.norm(np.diff(result.ends, axis=0), axis=1) == 0
    assert np.all(same_start ^ same_end)


def overhanging_cone_pair():
    """A runs over 0.6 rad more of the cone than B: the generators there miss B."""
    a = curve_pairs._curve(
        curve_pairs.cone_surface, curve_pairs._lin(-0.6, 2.5), curve_pairs._wave(2.0, 0.3, 7.0), False
    )
    b = curve_pairs._curve(
        curve_pairs.cone_surface, curve_pairs._lin(0.0, 2.5), curve_pairs._wave(4.0, 0.5, 5.0, 1.0), True
    )
    return a, b


def test_stations_beyond_the_end_of_b_are_closed_by_fans_and_counted():
    a, b = overhanging_cone_pair()
    result = ruling_developable(a, b, 40)
    stations = result.stations
    angle = np.arctan2(result.starts[stations, 1], result.starts[stations, 0])
    np.testing.assert_array_equal(result.fan[stations], angle < 0)
    assert result.valid[~result.fan].all()
    missing = int((angle < 0).sum())
    assert result.message.startswith(
        f"closed by smooth cones through single points of the curves at {missing} of 41 stations"
    )
    assert result.creased_share == 0.0


def test_a_strip_end_with_no_torsal_partner_is_one_cone_joined_at_the_true_generator_through_bs_end():
    """The stations before B's start (angle < 0 on the cone) are closed by the cone through
    B(0); the ruling joining it to the torsal rulings is the cone's generator through B(0),
    which meets A at angle 0 (the construction's closed form)."""
    a, b = overhanging_cone_pair()
    result = ruling_developable(a, b, 40)
    first_torsal = int(np.argmin(result.fan))
    joint = result.starts[first_torsal]
    assert not result.stations[first_torsal]
    assert abs(np.arctan2(joint[1], joint[0])) <= 1e-10
    assert np.abs(result.ends[first_torsal] - b.point_at(0.0)).max() <= 1e-12
    apex = np.repeat(b.point_at(0.0)[None], first_torsal, 0)
    np.testing.assert_array_equal(result.ends[:first_torsal], apex)
    assert result.warp[first_torsal] <= 1e-9


def test_strips_solved_together_close_head_and_tail_with_the_generators_through_bs_ends():
    """Four strips in one solve: the overhang at A's start, at its end (both curves run
    backwards), the pairing swapped (B overhangs: no cone) and a cone pair without fans.
    The head's and the tail's cones each join the torsal rulings at the cone's generator
    through B's end point, which meets A at angle 0 (the construction's closed form)."""
    a, b = overhanging_cone_pair()
    jobs = [(a, b, 40, 0.01), (a.reversed(), b.reversed(), 40, 0.01), (b, a, 40, 0.01)]
    pair = curve_pairs.PAIRS["cone"]()
    head, tail, swapped, plain = ruling_developables([*jobs, (pair.a, pair.b, 20, 0.01)])
    for result, end in ((head, 0.0), (tail, 1.0)):
        torsal = np.flatnonzero(~result.fan)
        joint = torsal[0] if end == 0.0 else torsal[-1]
        assert not result.stations[joint]
        assert abs(np.arctan2(result.starts[joint, 1], result.starts[joint, 0])) <= 1e-10
        assert np.abs(result.ends[joint] - b.point_at(0.0)).max() <= 1e-12
        assert result.warp[joint] <= 1e-9
    # the tail's fans all run to B's last point, A's first stations to B's first
    last = np.flatnonzero(~tail.fan)[-1]
    np.testing.assert_array_equal(tail.ends[last:], np.repeat(b.point_at(0.0)[None], len(tail.s) - last, 0))
    assert not swapped.fan[swapped.stations].any() and not plain.fan.any()


def test_either_pairing_of_an_overhanging_cone_closes_the_same_smooth_cone_so_no_hint_is_given():
    """The cone through B's end point is the same surface whichever curve is A: the two
    closures cover the same share of the area (to the rulings' spacing), neither creases,
    and no alternative is named."""
    a, b = overhanging_cone_pair()
    result = ruling_developable(a, b, 40)
    swapped = ruling_developable(b, a, 40)
    assert swapped.fan[swapped.stations].sum() == 0  # every station torsal, B's overhang fanned
    assert result.creased_share == swapped.creased_share == 0.0
    assert swapped.fan_share == pytest.approx(result.fan_share, abs=1e-4)
    assert better_pairing(a, b, 40, 0.01, result) is None


def test_curve_b_running_the_other_way_gets_the_hint_to_reverse_it():
    pair = curve_pairs.PAIRS["cone"]()
    result = ruling_developable(pair.a, pair.b.reversed(), 40)
    assert not result.valid[result.stations].all()
    assert better_pairing(pair.a, pair.b.reversed(), 40, 0.01, result) == (
        "reverse CurveB: creased fans fall to 0 % of the area"
    )


def test_no_hint_is_given_when_no_alternative_helps():
    a, b = Line([0, 0, 0], [1, 0, 0]), Line([0, 1, 0], [1, 1, 1])  # skew: no pairing is developable
    assert better_pairing(a, b, 10, 0.01, ruling_developable(a, b, 10, 0.01)) is None


def test_warp_tolerance_decides_validity():
    """Between skew lines the loft's warp falls from 0.79 to 0.62 rad along the strip."""
    a, b = Line([0, 0, 0], [1, 0, 0]), Line([0, 1, 0], [1, 1, 1])
    assert ruling_developable(a, b, 10, warp_tolerance=0.8).valid.all()
    partly = ruling_developable(a, b, 10, warp_tolerance=0.7)
    np.testing.assert_array_equal(partly.valid, partly.warp <= 0.7)
    assert 0 < partly.valid.sum() < 11


# -- input checks ------------------------------------------------------------------------------


@pytest.mark.parametrize("segments", [0, -3, 2.5])
def test_segments_must_be_a_whole_number_of_at_least_one(segments):
    with pytest.raises(ValueError, match="Segments"):
        ruling_developable(Line([0, 0, 0], [1, 0, 0]), Line([0, 1, 0], [1, 1, 0]), segments)


@pytest.mark.parametrize("tolerance", [-0.1, float("nan")])
def test_warp_tolerance_must_be_a_non_negative_number(tolerance):
    with pytest.raises(ValueError, match="warp tolerance"):
        ruling_developable(Line([0, 0, 0], [1, 0, 0]), Line([0, 1, 0], [1, 1, 0]), 4, tolerance)


def test_a_curve_of_zero_length_is_refused():
    with pytest.raises(ValueError, match="zero length"):
        ruling_developable(Line([0, 0, 0], [0, 0, 0]), Line([0, 1, 0], [1, 1, 0]), 4)
    with pytest.raises(ValueError, match="zero length"):
        ruling_developable(Line([0, 0, 0], [1, 0, 0]), Line([0, 1, 0], [0, 1, 0]), 4)
