"""A list input multiplies a node's calls: the solver bounds them before the first call.

Caps on inputs limit one call of ``solve``; :attr:`torsal.engine.node.Node.max_calls` and
:attr:`~torsal.engine.node.Node.max_work` limit what a list of values (or of branches) turns
them into, with a message naming the input that drives the count.
"""

from __future__ import annotations

from typing import Any, ClassVar

import numpy as np

from tests.support.node_helpers import out, run, tree
from torsal.engine.node import LIST, MAX_CALLS, In, Node, NodeWarning, Out
from torsal.engine.types import INTEGER, NUMBER
from torsal.nodes.analysis.surface_analysis import SurfaceAnalysis
from torsal.nodes.geometry.parametric_surface import cylinder
from torsal.nodes.limits import MAX_NUMBERS


class Counted(Node):
    """Doubles a number; counts its calls; five at most."""

    type_id = "test.Counted"
    inputs = (In("Value", NUMBER, "V", "A number."), In("Other", NUMBER, "O", "Another.", default=0.0))
    outputs = (Out("Result", NUMBER, "R", "Twice Value."),)
    max_calls: ClassVar[int] = 5
    calls = 0

    def solve(self, value: float, other: float) -> float:
        type(self).calls += 1
        return 2 * value


class PerBranch(Counted):
    """A list-access node: one call per branch."""

    type_id = "test.PerBranch"
    inputs = (In("Values", NUMBER, "V", "Numbers.", access=LIST),)

    def solve(self, values: list[float]) -> float:
        type(self).calls += 1
        return sum(values)


class Weighed(Node):
    """Work Size per call; at most 10 in all."""

    type_id = "test.Weighed"
    inputs = (In("Size", INTEGER, "S", "How much work one call is."),)
    outputs = (Out("Result", INTEGER, "R", "Size."),)
    max_work: ClassVar[int | None] = 10
    work_unit = "steps"

    def call_work(self, size: Any) -> int:
        if size < 0:
            raise NodeWarning("Size must be 0 or more")  # solve would refuse it too
        return size

    def solve(self, size: int) -> int:
        return size


def test_a_node_runs_up_to_its_max_calls():
    Counted.calls = 0
    result = run(Counted(), Value=tree({(0,): [1.0, 2.0, 3.0, 4.0, 5.0]}))
    assert result.state == "ok"
    assert out(result) == {(0,): [2.0, 4.0, 6.0, 8.0, 10.0]}


def test_one_call_past_max_calls_is_refused_before_any_call_naming_the_input():
    Counted.calls = 0
    result = run(Counted(), Value=tree({(0,): [1.0] * 6}))
    assert result.state == "error"
    assert Counted.calls == 0
    texts = [m.text for m in result.messages]
    assert texts == ["Value has 6 values: Counted would run 6 times; at most 5 at once"]


def test_calls_are_counted_over_every_branch():
    Counted.calls = 0
    result = run(Counted(), Value=tree({(0,): [1.0] * 3, (1,): [1.0] * 3}))
    assert result.state == "error"
    assert Counted.calls == 0
    assert result.messages[0].text.startswith("Value has 6 values in 2 branches: Counted would run 6 times")


def test_a_list_access_node_counts_one_call_per_branch():
    PerBranch.calls = 0
    result = run(PerBranch(), Values=tree({(i,): [1.0] for i in range(6)}))
    assert PerBranch.calls == 0
    assert result.messages[0].text == "Values has 6 branches: PerBranch would run 6 times; at most 5 at once"


def test_work_summed_over_calls_within_max_work_runs():
    result = run(Weighed(), Size=tree({(0,): [4, 6]}))
    assert result.state == "ok"


def test_work_summed_over_calls_past_max_work_is_refused_in_the_nodes_unit():
    result = run(Weighed(), Size=tree({(0,): [4, 6, 1]}))
    assert result.state == "error"
    assert result.messages[0].text.startswith("Size has 3 values: Weighed would run 3 times; 11 steps in all")


def test_a_value_call_work_cannot_count_costs_one_and_solve_says_what_is_wrong():
    result = run(Weighed(), Size=tree({(0,): [9, -5]}))
    assert result.state == "ok"  # 9 + 1: within 10


def test_the_default_budget_passes_the_longest_list_series_makes():
    assert MAX_CALLS >= MAX_NUMBERS


def test_surface_analysis_over_200_densities_is_refused_at_once_naming_udensity():
    surfaces = tree({(0,): [cylinder(1.5, 2.0)]})
    result = run(SurfaceAnalysis(), Surface=surfaces, UDensity=tree({(0,): list(range(2, 202))}))
    assert result.state == "error"
    assert result.seconds < 1.0
    assert result.messages[0].text.startswith("UDensity has 200 values: SurfaceAnalysis would run 200 times")


def test_surface_analysis_of_a_few_strips_at_the_default_density_runs():
    result = run(SurfaceAnalysis(), Surface=tree({(0,): [cylinder(1.5, 2.0)] * 3}))
    assert result.state == "ok"


def _patching_inputs(scales: list[float]) -> dict[str, Any]:
    from torsal.nodes.geometry.curves.line import Polyline
    from torsal.nodes.geometry.unroll import unroll_surface

    surface = cylinder(1.0, 2.0)
    panel = Polyline(np.array([[0, 0, 0], [0.3, 0, 0], [0.3, 0.2, 0], [0, 0.2, 0], [0, 0, 0]], dtype=float))
    return {"Surface": tree({(0,): [surface]}), "Development": tree({(0,): [unroll_surface(surface, 48)]}),
            "Pattern": tree({(0,): [panel]}), "Scale": tree({(0,): scales})}


def test_surface_patching_over_200_small_scales_is_refused_at_once_naming_scale():
    from torsal.nodes.patching.surface_patching import SurfacePatching

    result = run(SurfacePatching(), **_patching_inputs([0.1 + 0.001 * i for i in range(200)]))
    assert result.state == "error"
    assert result.seconds < 1.0
    assert result.messages[0].text.startswith("Scale has 200 values: SurfacePatching would run 200 times")


def test_surface_patching_at_two_scales_runs():
    from torsal.nodes.patching.surface_patching import SurfacePatching

    result = run(SurfacePatching(), **_patching_inputs([1.0, 2.0]))
    assert result.state == "ok"
    assert len(out(result, "PanelsFlat")) == 2
