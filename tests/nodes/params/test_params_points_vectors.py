"""Point, Vector and the unit vectors."""

from __future__ import annotations

from tests.support.node_helpers import out, run, texts, tree
from torsal.engine.values import Point, Vector
from torsal.nodes.params.points import Point as PointNode
from torsal.nodes.params.vectors import UnitX, UnitY, UnitZ
from torsal.nodes.params.vectors import Vector as VectorNode


def test_point_defaults_to_the_origin():
    assert out(run(PointNode())) == {(0,): [Point(0, 0, 0)]}


def test_point_from_coordinates():
    assert out(run(PointNode(), X=1.5, Y=-2, Z=3)) == {(0,): [Point(1.5, -2, 3)]}


def test_point_over_a_list_of_x_makes_one_point_per_item():
    result = run(PointNode(), X=[0, 1, 2], Z=5)
    assert out(result) == {(0,): [Point(0, 0, 5), Point(1, 0, 5), Point(2, 0, 5)]}


def test_point_with_nan_coordinate_warns_and_skips_that_point():
    result = run(PointNode(), X=tree({(0,): [1.0, float("nan")]}))
    assert result.state == "warning"
    assert texts(result) == ["X is not a number (NaN)"]
    assert out(result) == {(0,): [Point(1, 0, 0), None]}


def test_vector_from_components():
    assert out(run(VectorNode(), X=1, Y=2, Z=3)) == {(0,): [Vector(1, 2, 3)]}
    assert type(out(run(VectorNode(), X=1))[(0,)][0]) is Vector


def test_zero_vector_is_allowed_with_a_remark():
    result = run(VectorNode())
    assert result.state == "ok"
    assert out(result) == {(0,): [Vector(0, 0, 0)]}
    assert texts(result) == ["The vector has zero length, so it has no direction"]


def test_unit_vectors_default_to_length_one():
    assert out(run(UnitX())) == {(0,): [Vector(1, 0, 0)]}
    assert out(run(UnitY())) == {(0,): [Vector(0, 1, 0)]}
    assert out(run(UnitZ())) == {(0,): [Vector(0, 0, 1)]}


def test_unit_z_scaled_by_each_factor():
    result = run(UnitZ(), Factor=[2.0, -0.5])
    assert out(result) == {(0,): [Vector(0, 0, 2), Vector(0, 0, -0.5)]}


def test_negative_factor_leaves_no_negative_zero_components():
    (vector,) = out(run(UnitX(), Factor=-1.0))[(0,)]
    assert str(vector) == "Vector(-1, 0, 0)"


def test_unit_vector_with_infinite_factor_warns():
    result = run(UnitY(), Factor=tree({(0,): [float("inf")]}))
    assert texts(result) == ["Factor is infinite"]
