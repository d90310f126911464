"""Point, Vector and the unit vectors make (n, 3) arrays from array branches (issue 16, item 1).

Coordinates that come as an array branch (from Series, Range, an Expression) give one
Triples branch of points or vectors; the same numbers as a list give the same items, made
one by one as before. Expected values are worked out by hand.
"""

from __future__ import annotations

import json

import numpy as np

from tests.support.node_helpers import out, run, texts
from torsal.app.cli import main
from torsal.engine.datatree import DataTree, Triples
from torsal.engine.graph import Graph
from torsal.engine.graphfile import write_graph
from torsal.engine.solver import Solver
from torsal.engine.values import Point, Vector
from torsal.nodes.lists.ordering import Shift
from torsal.nodes.maths.sequences import Series
from torsal.nodes.params.points import Point as PointNode
from torsal.nodes.params.vectors import UnitZ
from torsal.nodes.params.vectors import Vector as VectorNode


def numbers(*values: float) -> DataTree:
    return DataTree({(0,): np.array(values, dtype=np.float64)})


def only_branch(tree: DataTree):
    (branch,) = tree.raw_branches
    return branch


def test_point_from_an_array_of_x_is_one_triples_branch_of_points():
    result = run(PointNode(), X=numbers(0.0, 1.0, 2.0), Z=5.0)
    branch = only_branch(result.output("Point"))
    assert isinstance(branch, Triples) and branch.item_class is Point
    assert np.array_equal(branch.array, [[0, 0, 5], [1, 0, 5], [2, 0, 5]])


def test_point_from_an_array_gives_the_points_a_list_gives():
    from_list = out(run(PointNode(), X=[0.0, 1.0, 2.0], Y=[4.0, 3.0]))
    from_array = out(run(PointNode(), X=numbers(0.0, 1.0, 2.0), Y=[4.0, 3.0]))
    assert from_array == from_list == {(0,): [Point(0, 4, 0), Point(1, 3, 0), Point(2, 3, 0)]}


def test_point_from_a_shorter_array_repeats_its_last_value_and_says_so():
    result = run(PointNode(), X=[0.0, 1.0, 2.0], Y=numbers(7.0, 8.0))
    assert out(result) == {(0,): [Point(0, 7, 0), Point(1, 8, 0), Point(2, 8, 0)]}
    assert texts(result) == ["X has 3 items, Y has 2: Y's last item is reused"]


def test_point_from_an_array_with_nan_warns_and_skips_that_point():
    result = run(PointNode(), X=numbers(1.0, float("nan")))
    assert result.state == "warning"
    assert texts(result) == ["X is not a number (NaN)"]
    assert out(result) == {(0,): [Point(1, 0, 0), None]}


def test_point_from_an_empty_array_makes_no_point():
    result = run(PointNode(), X=DataTree({(0,): np.array([]), (1,): np.array([2.0])}))
    assert result.output("Point").all_items() == [Point(2, 0, 0)]


def test_vector_from_arrays_is_one_triples_branch_of_vectors():
    result = run(VectorNode(), X=numbers(1.0, 0.0), Y=numbers(2.0, 0.0))
    branch = only_branch(result.output("Vector"))
    assert isinstance(branch, Triples) and branch.item_class is Vector
    assert result.output("Vector").all_items() == [Vector(1, 2, 0), Vector(0, 0, 0)]
    assert texts(result) == ["The vector has zero length, so it has no direction"]


def test_unit_z_from_an_array_of_factors_is_one_triples_branch():
    result = run(UnitZ(), Factor=numbers(2.0, -0.5))
    branch = only_branch(result.output("Vector"))
    assert isinstance(branch, Triples) and branch.item_class is Vector
    assert result.output("Vector").all_items() == [Vector(0, 0, 2), Vector(0, 0, -0.5)]


def _json_outputs(tmp_path, graph: Graph, capsys) -> dict:
    path = tmp_path / "points.graph"
    write_graph(graph, path)
    assert main(["run", str(path), "--json"]) == 0
    nodes = json.loads(capsys.readouterr().out)["nodes"]
    return {node_id: nodes[node_id]["outputs"] for node_id in ("p", "shift")}


def _points_then_shift(graph: Graph) -> Graph:
    graph.add_node(PointNode(), "p")
    graph.set_input_value("p", "Y", 2.0)
    graph.add_node(Shift(), "shift")
    graph.connect("p", "Point", "shift", "List")
    return graph


def test_series_to_point_to_shift_prints_the_json_a_list_of_numbers_prints(tmp_path, capsys):
    arrays = _points_then_shift(Graph())
    arrays.add_node(Series(), "s")
    arrays.set_input_value("s", "Count", 4)
    arrays.connect("s", "Series", "p", "X")
    lists = _points_then_shift(Graph())
    lists.set_input_value("p", "X", [0.0, 1.0, 2.0, 3.0])

    solver = Solver(arrays)
    solver.solve()
    assert all(isinstance(only_branch(solver.result(n).output(port)), Triples)
               for n, port in (("p", "Point"), ("shift", "List")))  # arrays end to end
    from_arrays = _json_outputs(tmp_path, arrays, capsys)
    from_lists = _json_outputs(tmp_path, lists, capsys)
    assert from_arrays == from_lists
    shifted = [[1.0, 2.0, 0.0], [2.0, 2.0, 0.0], [3.0, 2.0, 0.0], [0.0, 2.0, 0.0]]
    assert from_arrays["shift"] == {"List": {"{0}": [{"type": "Point", "xyz": xyz} for xyz in shifted]}}
