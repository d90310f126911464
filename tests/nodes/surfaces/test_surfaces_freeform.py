"""surfaces.Loft, RuledSurface, NurbsSurface and ParametricSurface: shapes and plain messages."""

from __future__ import annotations

import numpy as np
import pytest

from tests.support.node_helpers import out, run, texts, tree
from torsal.engine.graph import Graph
from torsal.engine.solver import Solver
from torsal.engine.types import encode_value
from torsal.engine.values import Domain, Point
from torsal.nodes.curves.primitives import Circle
from torsal.nodes.geometry import curves as kernel
from torsal.nodes.geometry.vectors import Plane as KernelPlane
from torsal.nodes.surfaces.analysis import Area, Isocurve
from torsal.nodes.surfaces.freeform import Loft, NurbsSurface, ParametricSurface, RuledSurface


def only(result, port=None):
    (value,) = out(result, port)[(0,)]
    return value


def grid(nu, nv, height=lambda x, y: 0.0 * x):
    """Points of an nu × nv grid on [0, nu-1] × [0, nv-1], rows along x (u) stacked along y (v)."""
    return [Point(x, y, height(x, y)) for y in range(nv) for x in range(nu)]


# --------------------------------------------------------------------------- Loft

def test_loft_through_circles_at_heights_is_a_cylinder():
    graph = Graph()
    graph.add_node(Circle(), "circles")
    graph.add_node(Loft(), "loft")
    heights = [Point(0, 0, 0), Point(0, 0, 1.5), Point(0, 0, 4.0)]
    graph.set_input_value("circles", "Plane", [encode_value(p) for p in heights])
    graph.set_input_value("circles", "Radius", 2.0)
    graph.connect("circles", "Circle", "loft", "Curves")
    solver = Solver(graph)
    solver.solve()
    assert solver.result("loft").state == "ok"
    (surface,) = solver.result("loft").output("Surface").branches[0]
    u, v = (a.ravel() for a in np.meshgrid(np.linspace(0, 1, 101), np.linspace(0, 1, 101)))
    p = surface.point_at(u, v)
    assert np.abs(np.hypot(p[:, 0], p[:, 1]) - 2.0).max() < 1e-6
    assert p[:, 2].min() > -1e-9 and p[:, 2].max() < 4.0 + 1e-9
    assert surface.closed_u


def test_loft_through_circles_has_the_area_and_centroid_of_the_cylinder():
    circles = [kernel.Circle(KernelPlane.from_normal([0, 0, z], [0, 0, 1]), 2.0) for z in (0.0, 1.5, 4.0)]
    surface = only(run(Loft(), Curves=tree({(0,): circles})))
    result = run(Area(), Geometry=tree({(0,): [surface]}))
    assert only(result, "Area") == pytest.approx(2 * np.pi * 2.0 * 4.0, rel=1e-9)
    assert np.allclose(only(result, "Centroid"), [0, 0, 2.0], atol=1e-9)


def test_loft_passes_through_each_curve():
    lines = [kernel.Line([0, 0, z], [3, 0, z * z]) for z in (0.0, 1.0, 2.0, 3.0)]
    surface = only(run(Loft(), Curves=tree({(0,): lines})))
    t = np.linspace(0, 1, 7)
    for j, v in enumerate(surface.curve_parameters):
        assert np.abs(surface.point_at(t, v) - lines[j].point_at(t)).max() < 1e-9


def test_loft_of_one_curve_warns():
    result = run(Loft(), Curves=tree({(0,): [kernel.Circle(radius=1.0)]}))
    assert texts(result) == ["A loft needs at least 2 curves; got 1"]


def test_loft_through_the_same_curve_twice_in_a_row_warns():
    circle = kernel.Circle(radius=1.0)
    result = run(Loft(), Curves=tree({(0,): [circle, circle, kernel.Circle(radius=2.0)]}))
    assert texts(result) == [
        "Curves 0 and 1 are the same curve: a loft cannot pass through one curve twice in a row "
        "(remove the duplicate)"
    ]


def test_loft_with_an_empty_item_says_so():
    result = run(Loft(), Curves=tree({(0,): [kernel.Circle(radius=1.0), None]}))
    assert texts(result) == ["Curves contains empty (null) items: remove them or fix what made them"]


# --------------------------------------------------------------------------- RuledSurface

A = kernel.Line([0, 0, 0], [4, 0, 0])
B = kernel.Line([0, 3, 1], [2, 3, 5])


@pytest.mark.parametrize("u", [0.0, 0.3, 1.0])
def test_ruled_surface_isocurve_at_u_is_the_segment_from_a_to_b(u):
    surface = only(run(RuledSurface(), CurveA=tree({(0,): [A]}), CurveB=tree({(0,): [B]})))
    result = run(Isocurve(), Surface=tree({(0,): [surface]}), UV=Point(u, 0.25, 0))
    ruling, along = only(result, "V"), only(result, "U")
    t = np.linspace(0, 1, 11)[:, None]
    assert np.abs(ruling.point_at(t.ravel()) - ((1 - t) * A.point_at(u) + t * B.point_at(u))).max() < 1e-12
    assert np.abs(along.point_at(t.ravel()) - (0.75 * A.point_at(t.ravel()) + 0.25 * B.point_at(t.ravel()))
                  ).max() < 1e-12


def test_ruled_surface_between_the_same_curve_warns():
    result = run(RuledSurface(), CurveA=tree({(0,): [A]}), CurveB=tree({(0,): [A]}))
    assert texts(result) == ["CurveA and CurveB are the same curve, so the ruled surface would have no area"]


def test_ruled_surface_between_opposite_curves_remarks_that_the_rulings_cross():
    flipped = kernel.Line([2, 3, 0], [0, 3, 0])
    result = run(RuledSurface(), CurveA=tree({(0,): [kernel.Line([0, 0, 0], [2, 0, 0])]}),
                 CurveB=tree({(0,): [flipped]}))
    assert result.state == "ok"
    assert texts(result) == ["CurveA and CurveB run in opposite directions, so the rulings cross: Flip one"]


def test_ruled_surface_needs_both_curves():
    assert texts(run(RuledSurface(), CurveA=tree({(0,): [A]}))) == ["Input CurveB collected no data"]


# --------------------------------------------------------------------------- NurbsSurface

def test_nurbs_surface_from_a_list_reads_rows_of_ucount_along_u():
    points = grid(4, 3, lambda x, y: x * y)
    surface = only(run(NurbsSurface(), Points=points, UCount=4, DegreeU=1, DegreeV=1))
    assert surface.control_points.shape == (4, 3, 3)
    assert np.allclose(surface.point_at(1.0, 0.0), [3, 0, 0])
    assert np.allclose(surface.point_at(0.0, 1.0), [0, 2, 0])
    assert np.allclose(surface.point_at(1 / 3, 0.5), [1, 1, 1])  # bilinear: passes through the grid


def test_nurbs_surface_from_one_branch_per_row_equals_the_flat_list():
    points = grid(5, 4, lambda x, y: np.sin(x) * y)
    rows = tree({(0, j): points[5 * j: 5 * j + 5] for j in range(4)})
    from_rows = only(run(NurbsSurface(), Points=rows))
    from_list = only(run(NurbsSurface(), Points=points, UCount=5))
    assert np.array_equal(from_rows.control_points, from_list.control_points)
    assert (from_rows.degree_u, from_rows.degree_v) == (3, 3)


def test_nurbs_surface_makes_one_surface_per_grid():
    points = grid(2, 2)
    result = run(NurbsSurface(), Points=tree({(0,): points, (1,): [*points[:3], Point(1, 1, 5)]}),
                 UCount=2, DegreeU=1, DegreeV=1)
    surfaces = out(result)
    assert list(surfaces) == [(0,), (1,)]
    assert np.allclose(surfaces[(1,)][0].point_at(1.0, 1.0), [1, 1, 5])


def test_nurbs_surface_interpolates_its_points_when_asked():
    points = grid(5, 4, lambda x, y: np.cos(x) + y * y)
    surface = only(run(NurbsSurface(), Points=points, UCount=5, Interpolate=True))
    found = surface.closest_point(np.asarray(points, dtype=float))
    assert found.distances.max() < 1e-9


def test_nurbs_surface_interpolating_few_points_lowers_the_degree_with_a_remark():
    result = run(NurbsSurface(), Points=grid(3, 4), UCount=3, Interpolate=True)
    assert result.state == "ok"
    assert texts(result) == ["With 3 points along u the surface has degree 2 along u, not 3"]


def test_nurbs_surface_count_that_does_not_divide_the_points_warns():
    result = run(NurbsSurface(), Points=grid(5, 2), UCount=4)
    assert result.state == "warning"
    assert texts(result) == [
        "UCount is 4 but there are 10 points, not a multiple of 4: every row along u needs 4 points"
    ]


def test_nurbs_surface_with_too_few_points_for_its_degree_warns():
    result = run(NurbsSurface(), Points=grid(2, 5), UCount=2)
    assert texts(result) == [
        "DegreeU 3 needs at least 4 points along u; the grid has 2 (lower DegreeU to 1 or add points)"
    ]


def test_nurbs_surface_from_one_row_asks_for_ucount():
    result = run(NurbsSurface(), Points=grid(6, 1))
    assert texts(result) == [
        "Points has one row (6 points in branch {0}): give UCount to read it as a grid, or one branch per row"
    ]


def test_nurbs_surface_rows_of_different_lengths_warn():
    rows = tree({(0,): grid(4, 1), (1,): grid(3, 1)})
    assert texts(run(NurbsSurface(), Points=rows)) == [
        "Every row must have as many points as the first (4): branch {1} has 3"
    ]


def test_nurbs_surface_reports_which_grid_failed_and_makes_the_others():
    good = grid(2, 2)
    result = run(NurbsSurface(), Points=tree({(0,): good, (1,): good[:3]}), UCount=2, DegreeU=1, DegreeV=1)
    assert texts(result) == [
        "{1}: UCount is 2 but there are 3 points, not a multiple of 2: every row along u needs 2 points"
    ]
    assert out(result)[(1,)] == [None] and out(result)[(0,)][0] is not None


def test_nurbs_surface_degree_out_of_range_warns():
    result = run(NurbsSurface(), Points=grid(4, 4), UCount=4, DegreeV=0)
    assert texts(result) == ["DegreeV must be from 1 to 11, not 0"]


def test_nurbs_surface_through_a_repeated_row_warns():
    points = grid(4, 2) + grid(4, 2)[4:]
    result = run(NurbsSurface(), Points=points, UCount=4, Interpolate=True)
    assert texts(result) == ["Rows 1 and 2 are the same points: the surface cannot pass through a row twice"]


# --------------------------------------------------------------------------- ParametricSurface

def test_parametric_surface_default_is_the_saddle_z_equals_xy():
    surface = only(run(ParametricSurface()))
    assert np.allclose(surface.point_at(0.75, 0.25), [0.5, -0.5, -0.25])
    assert np.allclose(surface.point_at(0.0, 0.0), [-1, -1, 1])


def test_parametric_surface_points_follow_the_formulas_over_the_domains():
    surface = only(run(ParametricSurface(), X="u", Y="v**2", Z="3",
                       UDomain=Domain(-3.7, 12.1), VDomain=Domain(2.0, 1.0)))
    assert np.allclose(surface.point_at(0.0, 0.0), [-3.7, 4.0, 3.0])
    assert np.allclose(surface.point_at(1.0, 1.0), [12.1, 1.0, 3.0])


def test_parametric_surface_over_an_empty_domain_warns():
    result = run(ParametricSurface(), VDomain=Domain(2.0, 2.0))
    assert texts(result) == ["The VDomain is empty (2 to 2): v must run over an interval"]


def test_parametric_surface_with_an_unreadable_formula_warns_naming_it():
    result = run(ParametricSurface(), Z="sin(u")
    assert result.state == "warning"
    assert texts(result)[0].startswith("Z: Could not read the expression")


def test_parametric_surface_formula_in_an_unknown_variable_warns_naming_it():
    result = run(ParametricSurface(), X="t")
    assert result.state == "warning"
    assert texts(result)[0].startswith("X: ") and "'t'" in texts(result)[0]


def test_parametric_surface_with_an_empty_formula_warns():
    assert texts(run(ParametricSurface(), Y="  ")) == ["Y is empty: write a formula in u and v, such as 0"]


def test_parametric_surface_with_a_non_finite_point_warns_where():
    result = run(ParametricSurface(), Z="1 / u")
    assert result.state == "warning"
    assert texts(result) == [
        "The formulas give no finite point at u = 0, v = -1 (division by zero, or a square root of a "
        "negative number?)"
    ]


def test_parametric_surface_that_does_not_depend_on_v_warns():
    result = run(ParametricSurface(), X="u", Y="u * u", Z="0")
    assert texts(result) == ["The formulas do not change with v, so they trace a curve, not a surface"]


def test_parametric_surface_along_one_line_warns():
    result = run(ParametricSurface(), X="u + v", Y="0", Z="0")
    assert texts(result) == [
        "The formulas trace a curve, not a surface: the u and v directions are parallel everywhere"
    ]
