"""More of the rule in nodes/common/checks.py: one bad item is a warning naming its input
and null outputs for that item, while the node's other items are still made (Partition's
sizes, the strip outputs every surface-making node shares, SurfaceCoupling's pairs)."""

from __future__ import annotations

import numpy as np
import pytest

from tests.support.node_helpers import out, run, texts, tree
from torsal.engine.node import LIST, In, Node, NodeWarning, Out
from torsal.engine.types import GENERIC, NUMBER
from torsal.nodes.common.strip_outputs import strip_outputs
from torsal.nodes.developable.surface_coupling import SurfaceCoupling
from torsal.nodes.geometry.curves import Line
from torsal.nodes.geometry.ruled import RuledSurface
from torsal.nodes.lists.trees import Partition

# -- Partition ------------------------------------------------------------------------------


def test_partition_a_size_below_one_leaves_only_its_own_list_uncut():
    lists = tree({(0,): [1, 2, 3], (1,): [4, 5, 6]})
    result = run(Partition(), List=lists, Size=tree({(0,): [0], (1,): [2]}))
    assert result.state == "warning"
    assert texts(result) == [
        "Size must be at least 1, not 0 (Size branch {0}): the list it cuts gets no chunks"]
    assert out(result) == {(0, 0): [], (1, 0): [4, 5], (1, 1): [6]}


def test_partition_an_empty_size_leaves_only_its_own_list_uncut():
    lists = tree({(0,): [1, 2, 3], (1,): [4, 5, 6]})
    result = run(Partition(), List=lists, Size=tree({(0,): [2], (1,): [1, None]}))
    assert texts(result) == [
        "Size has an empty (null) item (Size branch {1}): the list it cuts gets no chunks"]
    assert out(result) == {(0, 0): [1, 2], (0, 1): [3], (1, 0): []}


def test_partition_an_array_of_sizes_with_a_negative_one_is_refused_by_its_least_size():
    result = run(Partition(), List=np.arange(4.0), Size=np.array([2, -3]))
    assert texts(result) == ["Size must be at least 1, not -3: the list it cuts gets no chunks"]
    assert out(result) == {(0, 0): []}


# -- strip outputs --------------------------------------------------------------------------


class Strip(Node):
    """Test-only: a strip of two rulings Height high, through strip_outputs (NaN passes)."""

    type_id = "test.Strip"
    inputs = (In("Height", NUMBER, "H", "How high the rulings are."),)
    outputs = (Out("Surface", GENERIC, "S", "The strip."),
               Out("Rulings", GENERIC, "R", "Its rulings.", access=LIST))

    def solve(self, height: float):
        starts = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]])
        ends = starts + np.array([0.0, 0.0, height])
        strip = strip_outputs(starts, ends, source="Height")
        return strip.surface, strip.rulings


def test_a_strip_with_points_that_are_not_numbers_warns_naming_the_input_and_only_it_is_null():
    result = run(Strip(), Height=tree({(0,): [2.0, float("nan")]}))
    assert result.state == "warning"
    assert texts(result) == ["Some rulings have points that are not finite numbers: check Height for NaN"]
    good, bad = out(result, "Surface")[(0,)]
    assert bad is None and isinstance(good, RuledSurface)
    assert out(result, "Rulings")[(0, 1)] == []
    _, second = out(result, "Rulings")[(0, 0)]
    assert np.array_equal(second.end, [1.0, 0.0, 2.0])


def test_fewer_than_two_rulings_is_a_warning_naming_the_source():
    one = np.zeros((1, 3))
    with pytest.raises(NodeWarning, match=r"^A strip needs at least two rulings; CurveA gave 1: set"):
        strip_outputs(one, one + 1.0, source="CurveA")


def test_rulings_that_make_no_surface_are_a_warning_naming_the_source():
    starts, ends = np.zeros((3, 3)), np.ones((2, 3))
    with pytest.raises(NodeWarning, match=r"^The rulings from Surface do not make a surface: starts"):
        strip_outputs(starts, ends, warp=[0.0, 0.0, 0.0], source="Surface")


# -- SurfaceCoupling ------------------------------------------------------------------------


def flat_strip(foot: list[float], corner: list[float]) -> RuledSurface:
    """A vertical flat strip 1 high from ``foot`` to ``corner`` (its edge 1 stands at the corner)."""
    up = np.array([0.0, 0.0, 1.0])
    return RuledSurface(Line(foot, corner), Line(np.add(foot, up), np.add(corner, up)))


def test_a_pair_of_patches_that_cannot_be_coupled_is_null_and_the_other_pair_is_joined():
    a = flat_strip([-2.0, -2.0, 0.0], [-1.0, -1.0, 0.0])  # in the plane y = x, edge 1 at (-1, -1)
    apart = flat_strip([2.0, -2.0, 0.0], [1.0, -1.0, 0.0])  # in y = -x, edge 1 at (1, -1)
    touching = RuledSurface(Line([-1, -1, 0], [0, -2, 0]), Line([-1, -1, 1], [0, -2, 1]))
    result = run(SurfaceCoupling(), SurfaceA=tree({(0,): [a, a]}), SurfaceB=tree({(0,): [apart, touching]}),
                 EdgeA=1, EdgeB=tree({(0,): [1, 3]}), Segments=8)
    assert result.state == "warning"
    assert "The two edges share a corner: there is no gap for a connecting surface" in texts(result)
    joined, missing = out(result, "CurveA")[(0,)]
    assert missing is None
    assert np.allclose(joined.end, [1.0, -1.0, 0.0], atol=1e-14)  # on the other patch's edge corner
    assert out(result, "Surface")[(0,)][1] is None
