"""The helpers list nodes use on a branch held as a list, an array or Triples (torsal.engine.datatree)."""

from __future__ import annotations

import numpy as np

from torsal.engine.datatree import Triples, concatenated, item_at, take
from torsal.engine.values import Point, Vector


def points(*rows: tuple[float, float, float]) -> Triples:
    return Triples(np.array(rows, dtype=float), Point)


def test_item_at_gives_a_python_float_from_an_array():
    item = item_at(np.array([1.5, 2.5]), 1)
    assert item == 2.5 and type(item) is float


def test_item_at_gives_a_python_bool_from_a_boolean_array():
    item = item_at(np.array([True, False]), -1)
    assert item is False


def test_item_at_gives_a_point_from_triples():
    item = item_at(points((1, 2, 3), (4, 5, 6)), 0)
    assert item == Point(1, 2, 3) and type(item) is Point


def test_take_keeps_an_array_an_array_in_the_order_given():
    taken = take(np.array([10, 11, 12]), np.array([2, 0]))
    assert isinstance(taken, np.ndarray) and taken.tolist() == [12, 10]


def test_take_from_a_list_gives_a_list():
    assert take(["a", "b", "c"], np.array([1, 1, 0])) == ["b", "b", "a"]


def test_triples_indexed_by_a_mask_keep_their_item_class():
    picked = Triples(np.eye(3), Vector)[np.array([True, False, True])]
    assert isinstance(picked, Triples) and picked.tolist() == [Vector(1, 0, 0), Vector(0, 0, 1)]


def test_concatenated_arrays_of_one_dtype_are_one_array():
    joined = concatenated(np.array([1.0]), np.array([2.0, 3.0]))
    assert isinstance(joined, np.ndarray) and joined.tolist() == [1.0, 2.0, 3.0]


def test_concatenated_arrays_of_two_dtypes_are_a_list_of_both():
    joined = concatenated(np.array([1.0]), np.array([2]))
    assert joined == [1.0, 2] and [type(v) for v in joined] == [float, int]


def test_concatenated_points_and_vectors_are_a_list_that_keeps_each_kind():
    joined = concatenated(points((1, 0, 0)), Triples(np.array([[0.0, 1.0, 0.0]]), Vector))
    assert [type(v) for v in joined] == [Point, Vector]


def test_concatenated_with_an_empty_branch_is_the_other_branch():
    branch = np.array([1.0, 2.0])
    assert concatenated(branch, []) is branch
    assert concatenated([], branch) is branch
