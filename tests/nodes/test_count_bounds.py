"""Counts bounded on their ports: a count of 0 or 1e12 is refused with one sentence naming
the input, before the node's solve runs (so before anything is allocated)."""

from __future__ import annotations

import pytest

from tests.support.node_helpers import run, texts, tree
from torsal.engine.node import Node
from torsal.engine.values import Point
from torsal.nodes.analysis.bending import BendingCheck
from torsal.nodes.analysis.curvature_histogram import MAX_BINS, CurvatureHistogram
from torsal.nodes.analysis.curve_of_regression import CurveOfRegression
from torsal.nodes.analysis.surface_analysis import SurfaceAnalysis
from torsal.nodes.curves.analysis import DivideCurve
from torsal.nodes.geometry.curves import Line
from torsal.nodes.limits import MAX_ANALYSIS_SEGMENTS, MAX_COPIES, MAX_DENSITY, MAX_DIVISIONS, MAX_NUMBERS
from torsal.nodes.maths.random_numbers import Random
from torsal.nodes.maths.sequences import Range, Series
from torsal.nodes.surfaces.freeform import NurbsSurface
from torsal.nodes.transform.arrays import Array, PolarArray

LINE = Line([0.0, 0.0, 0.0], [3.0, 4.0, 0.0])

#: (node, bounded input, its least, its greatest, the other inputs a solve would need)
COUNTS = [
    (DivideCurve, "Count", 1, MAX_DIVISIONS, {"Curve": tree({(0,): [LINE]})}),
    (Array, "Count", 1, MAX_COPIES, {"Geometry": tree({(0,): [Point(0, 0, 0)]})}),
    (PolarArray, "Count", 1, MAX_COPIES, {"Geometry": tree({(0,): [Point(1, 0, 0)]})}),
    (CurvatureHistogram, "UDensity", 2, MAX_DENSITY, {}),
    (CurvatureHistogram, "VDensity", 2, MAX_DENSITY, {}),
    (CurvatureHistogram, "Bins", 1, MAX_BINS, {}),
    (SurfaceAnalysis, "UDensity", 2, MAX_DENSITY, {}),
    (SurfaceAnalysis, "VDensity", 2, MAX_DENSITY, {}),
    (BendingCheck, "Density", 2, MAX_DENSITY, {}),
    (CurveOfRegression, "Segments", 1, MAX_ANALYSIS_SEGMENTS, {}),
    (Series, "Count", 0, MAX_NUMBERS, {}),
    (Range, "Steps", 1, MAX_NUMBERS, {}),
    (Random, "Number", 0, MAX_NUMBERS, {}),
]
IDS = [f"{node.__name__}.{name}" for node, name, *_ in COUNTS]
FROM_ONE = [pytest.param(*c, id=i) for c, i in zip(COUNTS, IDS, strict=True) if c[2] > 0]


def _never_solved(monkeypatch: pytest.MonkeyPatch, node: type[Node]) -> None:
    def solve(self: Node, *args: object) -> None:
        raise AssertionError("solve was called with a count outside the port's bounds")

    monkeypatch.setattr(node, "solve", solve)


@pytest.mark.parametrize(("node", "name", "least", "greatest", "others"), COUNTS, ids=IDS)
def test_the_count_port_declares_its_bounds(node, name, least, greatest, others):
    port = next(p for p in node.inputs if p.name == name)
    assert (port.min, port.max) == (least, greatest)


@pytest.mark.parametrize(("node", "name", "least", "greatest", "others"), COUNTS, ids=IDS)
def test_a_count_of_1e12_is_refused_naming_the_input_before_solve(monkeypatch, node, name, least,
                                                                   greatest, others):
    _never_solved(monkeypatch, node)
    result = run(node(), **others, **{name: 1e12})
    assert result.state == "warning"
    assert texts(result) == [f"{name} is 1,000,000,000,000; at most {greatest:,} can be made at once"]
    assert all(not branches.raw_branches for branches in result.outputs.values())


@pytest.mark.parametrize(("node", "name", "least", "greatest", "others"), FROM_ONE)
def test_a_count_of_0_is_refused_naming_the_input_before_solve(monkeypatch, node, name, least, greatest,
                                                                others):
    _never_solved(monkeypatch, node)
    result = run(node(), **others, **{name: 0})
    assert result.state == "warning"
    assert texts(result) == [f"{name} must be at least {least}, not 0"]


def test_a_negative_seed_is_refused_by_its_port():
    assert texts(run(Random(), Seed=-1)) == ["Seed must be at least 0, not -1"]


def test_a_ucount_of_1_is_refused_by_its_port():
    points = tree({(0,): [Point(float(i), 0.0, 0.0) for i in range(4)]})
    assert texts(run(NurbsSurface(), Points=points, UCount=1)) == ["UCount must be at least 2, not 1"]
