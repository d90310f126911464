"""analysis.BendingCheck against closed forms: a cylinder bends at its radius r, a cone at
d·tan α a distance d from its apex, a plane not at all (infinite: every material passes)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from tests.support.node_helpers import out, run, texts, tree
from torsal.engine.solver import OK
from torsal.nodes.analysis.bending import MATERIALS, BendingCheck, bending_radii
from torsal.nodes.geometry.parametric_surface import cone, cylinder
from torsal.nodes.geometry.ruled import RuledSurface


def check(strips, **inputs):
    result = run(BendingCheck(), Strips=tree({(0,): strips}), **inputs)
    assert result.state == OK, texts(result)
    return result


def test_a_cylinder_bends_at_its_radius_everywhere():
    radii = bending_radii(cylinder(radius=0.35, height=2.0), *np.meshgrid(np.linspace(0, 1, 7),
                                                                         np.linspace(0, 1, 5)))
    assert np.allclose(radii, 0.35, rtol=1e-12)


@pytest.mark.parametrize("v", [0.0, 0.4, 0.8])
def test_a_cone_bends_at_d_tan_alpha_a_distance_d_from_its_apex(v):
    r, h = 0.6, 1.5
    alpha = math.atan2(r, h)  # half-angle at the apex
    d = (1.0 - v) * math.hypot(r, h)  # v = 1 is the apex
    (radius,) = bending_radii(cone(radius=r, height=h), np.array([0.3]), np.array([v]))
    assert radius == pytest.approx(d * math.tan(alpha), rel=1e-12)


def test_a_plane_is_infinitely_flat_and_passes_every_material():
    starts = np.column_stack([np.linspace(0, 2, 6), np.zeros(6), np.zeros(6)])
    plane = RuledSurface.from_rulings(starts, starts + np.array([0.0, 0.5, 0.0]))
    for material in MATERIALS:
        result = check([plane], Material=material)
        assert out(result, "MinRadius")[(0,)] == [math.inf]
        assert out(result, "Ok")[(0,)] == [True]
        assert out(result, "Failing") == {(0,): []}


def test_the_node_reports_the_cylinders_radius_in_mm_and_judges_each_material():
    result = check([cylinder(radius=0.5, height=1.0)], Material="Aluminium 1 mm")  # 269 mm: passes
    assert out(result, "MinRadius")[(0,)] == [pytest.approx(500.0, rel=1e-12)]
    assert out(result, "Ok")[(0,)] == [True]
    result = check([cylinder(radius=0.5, height=1.0)], Material="Steel 1.5 mm")  # 670 mm: fails
    assert out(result, "Ok")[(0,)] == [False]
    assert len(out(result, "Failing")[(0,)]) == 24 * 24  # every grid point bends too tightly
    assert "1 of 1 strips bend tighter than Steel 1.5 mm allows (670 mm)" in texts(result)[0]


def test_a_model_scale_divides_the_radius_and_a_number_is_a_radius_in_mm():
    result = check([cylinder(radius=2.0, height=1.0)], Material=50.0, ModelScale=50.0)
    assert out(result, "MinRadius")[(0,)] == [pytest.approx(40.0, rel=1e-12)]  # 2000 mm / 50
    assert out(result, "Ok")[(0,)] == [False]
    assert out(result, "MaterialRadius")[(0,)] == [50.0]


def test_failing_points_are_where_a_cone_bends_too_tightly():
    r, h = 1.0, 1.0  # alpha = 45°: the radius is the distance from the apex
    result = check([cone(radius=r, height=h)], Material=700.0, Density=11)
    failing = np.array([np.asarray(p, dtype=float) for p in out(result, "Failing")[(0,)]])
    distance = np.linalg.norm(failing - [0.0, 0.0, h], axis=1)
    assert np.all(distance < 0.7)
    assert len(failing) == 11 * 5  # rows v = 0.6 … 1: (1 - v)·√2 m from the apex, under 0.7 m
    (mesh,) = out(result, "ColouredMesh")[(0,)]
    assert len(mesh.vertices) == 121 and mesh.visual.vertex_colors.shape == (121, 4)


def test_an_unknown_material_is_a_warning_naming_the_table():
    result = run(BendingCheck(), Strips=tree({(0,): [cylinder()]}), Material="Glass")
    assert "Material 'Glass' is not in the table" in texts(result)[0]


def test_every_material_has_a_source_and_a_sane_radius():
    for material in MATERIALS.values():
        assert material.source and 0 <= material.radius < 1e4
    assert MATERIALS["Aluminium 1 mm"].radius == pytest.approx(70_000 * 1.0 / (2 * 130))
