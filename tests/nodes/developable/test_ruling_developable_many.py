"""developable.RulingDevelopable's batched path (``solve_many``: every strip of a solve at once)
gives each row the outputs and messages ``solve`` gives it row by row."""

from __future__ import annotations

import math

import numpy as np
import pytest

from torsal.engine.datatree import DataTree
from torsal.engine.node import Node
from torsal.engine.solve_context import SolveContext, solving
from torsal.engine.solver import run_node
from torsal.nodes.developable.ruling_developable import RulingDevelopable
from torsal.nodes.geometry.curves import Circle, Line, NurbsCurve, Polyline
from torsal.nodes.geometry.vectors import Plane


class RowByRow(RulingDevelopable):
    """The node without its batched path."""

    solve_many = Node.solve_many


def _wavy(z: float, phase: float) -> NurbsCurve:
    u = np.linspace(0.0, 1.0, 9)
    points = np.column_stack([4 * u, np.sin(3 * u + phase), z + 0.2 * np.cos(5 * u)])
    return NurbsCurve(points, degree=3)


def _solved(node: Node, curves_a: list, curves_b: list, segments: list) -> tuple[dict, list]:
    context = SolveContext(node)
    trees = [DataTree({(0,): curves_a}), DataTree({(0,): curves_b}), DataTree({(0,): segments}),
             DataTree({(0,): [0.01]}), DataTree({(0,): [0.1]}), DataTree({(0,): [0.5]})]
    with solving(context):
        try:
            outputs = run_node(node, trees, [True, True, True, False, False, False])
        except Exception as exc:  # (the solver would make it the node's error)
            return {}, [*((m.level, m.text) for m in context.messages), ("raised", str(exc))]
    found = {}
    for name, tree in outputs.items():
        for path, branch in zip(tree.paths, tree.raw_branches, strict=True):
            for i, item in enumerate(branch):
                if name == "Rulings":
                    item = None if item is None else np.array([item.start, item.end]).tobytes()
                elif name == "Surface":
                    pieces = () if item is None else item.mesh_arrays()
                    item = None if item is None else b"".join(np.asarray(a).tobytes() for a in pieces)
                found[name, path, i] = item if name in ("Rulings", "Surface") else repr(item)
    return found, [(m.level, m.text) for m in context.messages]


def _pairs() -> tuple[list, list, list]:
    circle_a = Circle(Plane.from_normal([0, 0, 0], [0, 0, 1]), 2.0)
    circle_b = Circle(Plane.from_axes([0, 0, 2], [0, 1, 0], [-1, 0, 0]), 1.0)  # (its seam elsewhere)
    a = [_wavy(0.0, 0.0), Line([0, 0, 0], [2, 0, 0]), _wavy(0.0, 0.3), circle_a,
         Polyline([[0, 0, 0], [1, 0, 0], [2, 0.5, 0]])]
    b = [_wavy(1.0, 0.2), Line([0, 1, 0], [3, 2, 0]), _wavy(1.2, 1.5), circle_b,
         Polyline([[0, 1, 1], [1, 1.2, 1], [2, 1, 1.4]])]
    return a, b, [12, 2, 7, 16, 9]


def test_every_strip_at_once_gives_each_row_what_solve_gives_it_with_its_messages_in_order():
    a, b, segments = _pairs()
    batched = _solved(RulingDevelopable(), a, b, segments)
    assert batched == _solved(RowByRow(), a, b, segments)
    assert len(batched[0]) > 5 * len(a) and batched[1]  # (rows were made and said something)


def test_a_refused_row_gets_nothing_and_its_warning_in_its_place():
    a, b, segments = _pairs()
    a[2] = Line([1, 1, 1], [1, 1, 1])  # zero length: that row is refused, the others are made
    batched = _solved(RulingDevelopable(), a, b, segments)
    assert batched == _solved(RowByRow(), a, b, segments)
    assert any("zero length" in text for _, text in batched[1])
    assert batched[0]["Surface", (0,), 2] is None and ("Kind", (0, 2), 0) not in batched[0]


@pytest.mark.parametrize("bad", ["same curve", "segments"])
def test_an_error_at_a_row_comes_after_the_messages_of_the_rows_before_it(bad):
    a, b, segments = _pairs()
    if bad == "same curve":
        b[3] = a[3]
    else:
        segments[3] = math.nan
    batched = _solved(RulingDevelopable(), a, b, segments)
    assert batched == _solved(RowByRow(), a, b, segments)
    assert batched[1][-1][0] == "raised"


def test_strips_far_from_the_origin_that_taper_get_what_solve_gives_them():
    # at site coordinates (each row's frame and rounding its own) and meeting at a point
    shift = np.array([1e6, 2e6, 50.0])
    u = np.linspace(0.0, 1.0, 9)

    def wavy(z: float, phase: float) -> NurbsCurve:
        points = np.column_stack([4 * u, np.sin(3 * u + phase), z + 0.2 * np.cos(5 * u)])
        return NurbsCurve(points + shift, degree=3)

    a = [wavy(0.0, 0.0), Line(shift, shift + np.array([2.0, 0, 0])), wavy(0.0, 0.3)]
    b = [wavy(1.0, 0.2), Line(shift, shift + np.array([2.0, 1.0, 0.5])), wavy(1.2, 1.5)]
    batched = _solved(RulingDevelopable(), a, b, [8, 3, 6])
    assert batched == _solved(RowByRow(), a, b, [8, 3, 6])
    assert any("tapers to a point" in text for _, text in batched[1])
