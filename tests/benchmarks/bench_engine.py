"""Engine overhead, measured side by side with direct calls in the same run (``make bench``).

Ratios, not absolute times: these machines are shared and noisy, so each figure is the
best of several repeats.
"""

from __future__ import annotations

import statistics
import subprocess
import sys
import time
from collections.abc import Callable
from pathlib import Path

import numpy as np

from tests.benchmarks.timing import ratio_to_baseline
from torsal.engine.graph import Graph
from torsal.engine.node import In, Node, Out, Setting
from torsal.engine.solver import Solver
from torsal.engine.types import GENERIC, NUMBER

ROOT = Path(__file__).resolve().parents[2]
REPEATS = 7
#: Bars, about twice the ratios measured: the chain 38–57× a plain dataflow loop (13–30 ms
#: for 1000 nodes), item access 10–11× a list comprehension, a cold run 2.1–2.5× starting
#: Python with numpy (0.9 s). They replace the absolute bars of 30 ms, 5 µs per item and 1 s.
BAR_CHAIN, BAR_ITEMS, BAR_COLD = 100.0, 20.0, 5.0


def best_of(function: Callable[[], object], repeats: int = REPEATS) -> float:
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        function()
        times.append(time.perf_counter() - start)
    return min(times)


def _calibrated_data(target_seconds: float = 1e-3) -> np.ndarray:
    """Random data whose sort takes about ``target_seconds`` on this machine, today."""
    size = 60_000
    data = np.random.default_rng(0).random(size)
    seconds = best_of(lambda: np.sort(data * 1.1).sum(), 15)
    return np.random.default_rng(0).random(max(1000, int(size * target_seconds / seconds)))


DATA = _calibrated_data()


def millisecond_of_numpy(seed: float) -> float:
    """About 1 ms of real numpy work (calibrated when the module loads)."""
    return float(np.sort(DATA * seed).sum())


class Work(Node):
    type_id = "bench.Work"
    inputs = (In("Seed", NUMBER, "S", "Scale.", default=1.0),)
    outputs = (Out("Result", NUMBER, "R", "A sum."),)

    def solve(self, seed: float) -> float:
        return millisecond_of_numpy(seed)


class Constant(Node):
    type_id = "bench.Constant"
    outputs = (Out("Value", NUMBER, "V", "A number."),)
    settings_spec = (Setting("value", float, 1.0),)

    def solve(self) -> float:
        return self.settings["value"]


class Increment(Node):
    type_id = "bench.Increment"
    inputs = (In("X", NUMBER, "X", "A number."),)
    outputs = (Out("Result", NUMBER, "R", "X + 1."),)

    def solve(self, x: float) -> float:
        return x + 1.0


class Identity(Node):
    type_id = "bench.Identity"
    inputs = (In("X", GENERIC, "X", "Anything."),)
    outputs = (Out("Result", GENERIC, "R", "The same."),)

    def solve(self, x: object) -> object:
        return x


def test_200_nodes_of_1ms_numpy_work_cost_at_most_5_percent_over_direct_calls():
    graph = Graph()
    for i in range(200):
        graph.add_node(Work(), f"w{i}")
        graph.set_input_value(f"w{i}", "Seed", 1.0 + i / 200)
    solver = Solver(graph)

    def through_graph() -> None:
        graph.expire_all()
        solver.solve()

    def direct() -> None:
        for i in range(200):
            millisecond_of_numpy(1.0 + i / 200)

    through_graph()
    direct()
    # pairs measured back to back see the same machine load; the median pair ratio
    # shrugs off the pairs another process disturbed
    graph_times, direct_times = [], []
    for _ in range(2 * REPEATS + 1):
        graph_times.append(best_of(through_graph, 1))
        direct_times.append(best_of(direct, 1))
    ratio = statistics.median(g / d for g, d in zip(graph_times, direct_times, strict=True))
    print(f"\n200 × 1 ms nodes: graph {min(graph_times)*1e3:.1f} ms, direct {min(direct_times)*1e3:.1f} ms "
          f"(best of {len(graph_times)}), median paired ratio {ratio:.3f}")
    assert ratio <= 1.05


def test_1000_node_chain_of_trivial_nodes_solves_within_100x_a_plain_dataflow_loop():
    """The baseline is the least any dataflow does: the same 1000 nodes' solve called in
    order, each input looked up in a dict of the outputs before it and wrapped in a list
    (a branch) and back. What is left is the engine's bookkeeping per node: expiry, list
    matching, trees, results."""
    graph = Graph()
    graph.add_node(Constant(), "n0")
    for i in range(1, 1000):
        graph.add_node(Increment(), f"n{i}")
        graph.connect(f"n{i - 1}", "Value" if i == 1 else "Result", f"n{i}", "X")
    solver = Solver(graph)
    nodes = [graph.nodes[f"n{i}"].node for i in range(1000)]

    def edit_first_and_solve() -> None:
        graph.set_setting("n0", "value", 2.0)
        solver.solve()

    def plain_dataflow() -> float:
        outputs = {"n0": [nodes[0].solve()]}
        for i in range(1, 1000):
            outputs[f"n{i}"] = [nodes[i].solve(outputs[f"n{i - 1}"][0])]
        return outputs["n999"][0]

    ratio = ratio_to_baseline("1000-node chain, first node edited", edit_first_and_solve,
                              "the nodes' solve in order through a dict", plain_dataflow, REPEATS)
    assert solver.result("n999").outputs["Result"].first() == 1001.0 == plain_dataflow()
    assert ratio <= BAR_CHAIN


def test_item_access_over_100000_items_within_20x_a_plain_loop():
    items = [float(i) for i in range(100_000)]
    graph = Graph()
    graph.add_node(Identity(), "id")
    graph.set_input_value("id", "X", items)
    solver = Solver(graph)
    node = graph.nodes["id"].node

    def through_graph() -> None:
        graph.expire("id")
        solver.solve()

    def plain_loop() -> list[object]:
        return [node.solve(x) for x in items]

    ratio = ratio_to_baseline("item access, 100,000 calls through the graph", through_graph,
                              "the same calls in a list comprehension", plain_loop, 5)
    assert ratio <= BAR_ITEMS


def test_torsal_run_of_a_20_node_graph_cold_within_5x_starting_python_with_numpy():
    """The floor of any cold run: a Python process importing numpy (a 20-node run imports
    no scipy)."""
    example = ROOT / "tests" / "fixtures" / "twenty-nodes.graph"
    command = [str(Path(sys.executable).with_name("torsal")), "run", str(example), "--json"]
    floor = [sys.executable, "-c", "import numpy"]
    subprocess.run(command, check=True, capture_output=True)  # warm the disk cache only
    ratio = ratio_to_baseline("torsal run (20 nodes), cold process",
                              lambda: subprocess.run(command, check=True, capture_output=True),
                              "python importing numpy",
                              lambda: subprocess.run(floor, check=True), 3)
    assert ratio <= BAR_COLD
