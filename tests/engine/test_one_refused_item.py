"""One bad item is a warning naming its input and a null output for that item; the
node's other items are still made (the rule in nodes/common/checks.py)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from tests.support.node_helpers import out, run, texts, tree
from torsal.engine.values import Point
from torsal.nodes.analysis.bending import BendingCheck
from torsal.nodes.curves.splines import ParametricCurve
from torsal.nodes.geometry.parametric_surface import cylinder
from torsal.nodes.surfaces.freeform import ParametricSurface


def test_a_strip_that_is_not_a_surface_warns_and_gets_null_outputs_while_the_others_are_checked():
    strips = tree({(0,): [cylinder(radius=0.5, height=1.0), Point(0, 0, 0)]})
    result = run(BendingCheck(), Strips=strips, Material="Aluminium 1 mm")
    assert result.state == "warning"
    assert texts(result)[0].startswith("Strip 2 of Strips is Point ")
    assert out(result, "MinRadius")[(0,)] == [pytest.approx(500.0, rel=1e-12), None]  # r = 0.5 m
    assert out(result, "Ok")[(0,)] == [True, None]
    mesh, missing = out(result, "ColouredMesh")[(0,)]
    assert missing is None and len(mesh.vertices) == 24 * 24


def test_an_empty_strip_warns_that_it_is_null_and_gets_null_outputs():
    result = run(BendingCheck(), Strips=tree({(0,): [None, cylinder(radius=2.0, height=1.0)]}))
    assert texts(result)[0] == "Strip 1 of Strips is empty (null): it is not checked and its outputs are null"
    assert out(result, "MinRadius")[(0,)] == [None, pytest.approx(2000.0, rel=1e-12)]


def test_units_that_are_not_a_length_warn_naming_units():
    result = run(BendingCheck(), Strips=tree({(0,): [cylinder(radius=0.5, height=1.0)]}), Units="furlong")
    assert result.state == "warning"
    assert texts(result) == ["Units 'furlong' is not a length unit Torsal knows: use mm, cm, m, in or ft"]


def test_one_unreadable_curve_formula_gives_a_null_curve_and_the_other_formulas_their_curves():
    result = run(ParametricCurve(), X=tree({(0,): ["cos(t)", "cos(t"]}), Y="sin(t)", Z="0")
    assert result.state == "warning"
    assert texts(result)[0].startswith("X: Could not read the expression")
    good, bad = out(result, "Curve")[(0,)]
    assert bad is None
    t = np.linspace(0.0, 1.0, 9)
    assert np.allclose(np.linalg.norm(good.point_at(t), axis=1), 1.0, atol=1e-9)  # the unit circle


def test_one_surface_formula_in_an_unknown_variable_gives_a_null_surface_and_the_others_theirs():
    result = run(ParametricSurface(), Z=tree({(0,): ["u * v", "w"]}))
    assert result.state == "warning"
    assert texts(result)[0].startswith("Z: Unknown name 'w'")
    good, bad = out(result, "Surface")[(0,)]
    assert bad is None
    x, y, z = good.point_at(np.array([1.0]), np.array([0.25]))[0]  # the saddle z = xy over [-1, 1]²
    assert z == pytest.approx(x * y, abs=1e-12) and not math.isnan(z)
