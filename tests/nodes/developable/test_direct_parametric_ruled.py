"""developable.ParametricRuledSurface: textbook ruled surfaces from Expression graphs.

Each graph is the thesis's: a Range of u values feeds one Expression per coordinate
of the directrix C(u) and of the direction a(u); params.Point and params.Vector join
them into lists, and ParametricRuledSurface builds S(u, v) = C(u) + v·a(u).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from tests.support.direct_graphs import Chain
from torsal.engine.values import Domain, Point, Vector
from torsal.nodes.curves.primitives import Circle
from torsal.nodes.developable.parametric_ruled import ParametricRuledSurface
from torsal.nodes.maths.expression import Expression
from torsal.nodes.maths.sequences import Range
from torsal.nodes.params.points import Point as PointNode
from torsal.nodes.params.vectors import Vector as VectorNode

STEPS = 48


def textbook(directrix: dict[str, str], direction: dict[str, str], **values) -> Chain:
    """The graph u → Expressions → Point, Vector → ParametricRuledSurface.

    ``directrix`` and ``direction`` map "X", "Y", "Z" to formulas in u (a missing
    coordinate keeps the Point/Vector node's own value, set in ``values`` as
    ``point_Z=…`` or ``vector_Z=…``)."""
    chain = Chain()
    chain.add("u", Range(), Domain=Domain(0.0, 2 * math.pi), Steps=STEPS)
    own = {k: v for k, v in values.items() if not k.startswith(("point_", "vector_"))}
    chain.add("point", PointNode(), **{k[6:]: v for k, v in values.items() if k.startswith("point_")})
    chain.add("vector", VectorNode(), **{k[7:]: v for k, v in values.items() if k.startswith("vector_")})
    for target, formulas in (("point", directrix), ("vector", direction)):
        for axis, formula in formulas.items():
            node_id = f"{target}_{axis}"
            chain.add(node_id, Expression({"expression": formula, "variables": ["u"]}))
            chain.wire("u", "Range", node_id, "u")
            chain.wire(node_id, "Result", target, axis)
    chain.add("prs", ParametricRuledSurface(), **own)
    chain.wire("point", "Point", "prs", "Directrix")
    chain.wire("vector", "Vector", "prs", "Direction")
    return chain.solve()


def lines(chain: Chain) -> np.ndarray:
    return np.array([[r.start, r.end] for r in chain.items("prs", "Rulings")])


def cylinder(**values) -> Chain:
    return textbook({"X": "cos(u)", "Y": "sin(u)"}, {}, vector_Z=2.0, VValues=Domain(0.0, 1.5), **values)


def test_textbook_cylinder_is_developable():
    chain = cylinder()
    warp = chain.items("prs", "WarpAngles")
    assert chain.result("prs").state == "ok"
    assert len(warp) == STEPS + 1
    assert max(warp) < 1e-12


def test_textbook_cylinder_rulings_are_vertical_and_v_times_a_long():
    r = lines(cylinder())
    assert np.abs(r[:, 1] - r[:, 0] - [0.0, 0.0, 3.0]).max() < 1e-15
    u = np.linspace(0.0, 2 * math.pi, STEPS + 1)
    assert np.abs(r[:, 0] - np.column_stack([np.cos(u), np.sin(u), 0 * u])).max() < 1e-15


def helicoid(pitch: float, half_width: float) -> Chain:
    return textbook(
        {"Z": f"{pitch!r} * u"}, {"X": "cos(u)", "Y": "sin(u)"},
        VValues=Domain(-half_width, half_width),
    )


def test_textbook_helicoid_is_not_developable_and_warps_as_closed_form():
    # S(u, v) = (v cos u, v sin u, c u). Along the edge v the (central- or one-sided-
    # difference) tangent over a step h is (−v sin u, v cos u, c·h/sin h) up to scale,
    # so the normals at v = ±w make the angle 2·atan(w·sin(h) / (h·c)) on every ruling;
    # it tends to the smooth helicoid's 2·atan(w / c) as h → 0.
    c, w = 1.0, 0.5
    h = 2 * math.pi / STEPS
    expected = 2 * math.atan(w * math.sin(h) / (h * c))
    warp = np.array(helicoid(c, w).items("prs", "WarpAngles"))
    assert expected > 0.9
    assert np.abs(warp - expected).max() < 1e-12
    assert expected == pytest.approx(2 * math.atan(w / c), rel=3e-3)


def test_wide_helicoid_warps_past_a_quarter_turn():
    """Half-width 3 on pitch 1: 2·atan(3·sin(h)/h) ≈ 2.5 rad, the turn of the tangent plane
    (folded into [0, π/2] it would read π minus that, about 0.64)."""
    c, w = 1.0, 3.0
    h = 2 * math.pi / STEPS
    expected = 2 * math.atan(w * math.sin(h) / (h * c))
    warp = np.array(helicoid(c, w).items("prs", "WarpAngles"))
    assert expected > 2.4
    assert np.abs(warp - expected).max() < 1e-12


def test_rulings_along_the_directrix_have_undefined_warp_and_say_so():
    chain = Chain()
    chain.add("prs", ParametricRuledSurface(), Directrix=[Point(0, 0, 0), Point(1, 0, 0), Point(2, 0, 0)],
              Direction=[Vector(1, 0, 0)])
    chain.solve()
    assert all(math.isnan(w) for w in chain.items("prs", "WarpAngles"))
    assert chain.result("prs").state == "warning"
    assert chain.texts("prs") == [
        "The warp is undefined (NaN) at 3 of 3 rulings (first: ruling 0): a ruling there has zero "
        "length or runs along an edge's tangent, so the sheet has no tangent plane to measure"
    ]


def mobius(**values) -> Chain:
    return textbook(
        {"X": "cos(u)", "Y": "sin(u)"},
        {"X": "cos(u / 2) * cos(u)", "Y": "cos(u / 2) * sin(u)", "Z": "sin(u / 2)"},
        VValues=Domain(0.0, 0.4), TwoSided=True, **values,
    )


def test_textbook_mobius_strip_has_one_side():
    chain = mobius()
    surface = chain.item("prs", "Surface")
    start, end = surface.normal_at(np.array([0.0, 1.0]), np.array([0.5, 0.5]))
    assert float(start @ end) < -0.999
    # its last ruling is its first, run the other way
    r = lines(chain)
    assert np.abs(r[-1, ::-1] - r[0]).max() < 1e-15
    assert not surface.closed_u


def test_two_sided_extends_the_rulings_to_minus_v():
    r = lines(mobius())
    assert np.abs(np.linalg.norm(r[:, 1] - r[:, 0], axis=1) - 0.8).max() < 1e-12
    u = np.linspace(0.0, 2 * math.pi, STEPS + 1)
    assert np.abs(r.mean(axis=1) - np.column_stack([np.cos(u), np.sin(u), 0 * u])).max() < 1e-15


def direct(**values) -> Chain:
    chain = Chain()
    chain.add("prs", ParametricRuledSurface(), **values)
    return chain.solve()


POINTS = [Point(0, 0, 0), Point(1, 0, 0), Point(2, 0, 1)]


def test_one_number_as_vvalues_runs_rulings_from_0_to_it():
    r = lines(direct(Directrix=POINTS, Direction=[Vector(0, 2, 0)], VValues=1.5))
    assert np.allclose(r[:, 1] - r[:, 0], [0.0, 3.0, 0.0], atol=0.0)


def test_several_numbers_as_vvalues_run_from_the_smallest_to_the_largest():
    r = lines(direct(Directrix=POINTS, Direction=[Vector(0, 1, 0)], VValues=[0.5, -1.0, 2.0]))
    assert np.allclose(r[:, 0], np.asarray(POINTS) + np.array([0.0, -1.0, 0.0]), atol=0.0)
    assert np.allclose(r[:, 1], np.asarray(POINTS) + np.array([0.0, 2.0, 0.0]), atol=0.0)


def test_a_curve_directrix_places_segments_plus_one_rulings_evenly_in_t():
    chain = Chain()
    chain.add("curve", Circle(), Radius=2.0)
    chain.add("prs", ParametricRuledSurface(), Direction=[Vector(0, 0, 1)], Segments=8)
    chain.wire("curve", "Circle", "prs", "Directrix")
    chain.solve()
    r = lines(chain)
    assert len(r) == 9
    assert np.abs(np.linalg.norm(r[:, 0, :2], axis=1) - 2.0).max() < 1e-12


@pytest.mark.parametrize(
    ("values", "message"),
    [
        ({"Direction": [Vector(0, 0, 1), Vector(0, 1, 0)]},
         "Give one Direction per Directrix point (3) or one for all; got 2"),
        ({"Direction": [Vector(0, 0, 1), Vector(0, 0, 0), Vector(0, 0, 1)]},
         "Direction 1 has zero length, so that ruling has no direction (1 such vectors)"),
        ({"Direction": [Vector(0, 0, 1)], "VValues": Domain(0.7, 0.7)},
         "VValues runs from 0.7 to 0.7: the rulings would have no length; give an interval"),
        ({"Directrix": [Point(0, 0, 0)], "Direction": [Vector(0, 0, 1)]},
         "Directrix has 1 point: give at least 2 points C(u), one per ruling"),
    ],
)
def test_invalid_inputs_warn_with_what_to_change(values, message):
    chain = direct(**({"Directrix": POINTS} | values))
    assert chain.result("prs").state == "warning"
    assert chain.texts("prs") == [message]
