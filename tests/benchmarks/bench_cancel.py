"""Esc stops a node within 0.2 s; long kernels look at the cancel token at least every 50 ms (issue 16).

Run alone with::

    .venv/bin/python -m pytest tests/benchmarks/bench_cancel.py \\
        -o python_files='bench_*.py' -o norecursedirs='.*' -s

A cancel is seen at the token's next check, so what it costs is the wait for that check
plus the hand-over between threads. Both are measured in the run:

* **Cancelling the bumpy-NURBS area** (Area on a 48 × 48 bicubic net, seconds of work)
  from another thread, median of five, timed from when the cancel is due, against the two
  baselines it is made of, measured in the same run: the kernel's gap between checks (its
  90th percentile over 1.5 s of work, by a recording token, see
  :mod:`tests.benchmarks.check_gaps`; the longest gap would let one stall of the machine
  excuse anything) plus the median delay of cancelling a node that does nothing but check
  ("cancelling nothing": the threads' hand-over). The ratio must stay under 1.5: nothing
  but the wait for the next check delays a cancel. The bar itself, 0.2 s, is asserted as
  well: it is what a designer waits, an absolute by nature, and the 50 ms rule below
  leaves it a fourfold margin against a loaded machine.
* **The longest gap between checks** in a sample of long kernels (the area; RulingDevelopable
  at 2,000 stations and over Kaohsiung's strips; BendingCheck at Density 200; SurfacePatching;
  IsoMapping at 2,000 segments; the roof's cut sheets; Rationalise), against a reference
  block of work timed in the same run: :func:`tests.benchmarks.timing.check_interval_block`
  (small numpy calls, the kernels' kind of work, ≈ 50 ms on this machine when quiet), so
  "a kernel does no more work between two checks than that block" stands for the 50 ms on
  any machine and any load. The best of
  up to three runs counts: a kernel that does not check is over in every run, a stall of
  the shared machine in one. Kernels that do not check yet are strict xfails naming their
  owner (they must lose the mark once they check).
"""

from __future__ import annotations

import functools
import statistics
import threading
import time
from collections.abc import Callable
from itertools import pairwise
from pathlib import Path

import numpy as np
import pytest

from tests.benchmarks.check_gaps import RecordingToken, check_gaps
from tests.benchmarks.timing import check_interval_block, duration
from tests.nodes.geometry.test_area_knot_grid import bumpy_net
from tests.support.curve_pairs import PAIRS
from tests.support.node_helpers import Source
from torsal.engine.datatree import DataTree
from torsal.engine.graph import Graph
from torsal.engine.graphfile import read_graph
from torsal.engine.node import Cancelled, Node
from torsal.engine.solver import Solver
from torsal.nodes.analysis.bending import BendingCheck
from torsal.nodes.analysis.iso_mapping import IsoMapping
from torsal.nodes.catalogue import default_registry
from torsal.nodes.developable.ruling_developable import RulingDevelopable
from torsal.nodes.geometry.nurbs_surface import NurbsSurface
from torsal.nodes.surfaces.analysis import Area

EXAMPLES = Path(__file__).resolve().parents[2] / "torsal" / "resources" / "examples"


class CheckingOnly(Node):
    """Does nothing but look at its token (a little numpy work between looks)."""

    type_id = "test.CheckingOnly"

    def solve(self) -> None:
        numbers = np.linspace(0.0, 1.0, 64)
        while True:
            self.check_cancelled()
            np.sin(numbers)


def cancel_delays(make: Callable[[], Node], solve: Callable[[Node], object], runs: int = 5,
                  after: float = 0.3) -> list[float]:
    """Seconds from the moment a timer thread is due to cancel (``after`` s into the solve)
    to the node's ``Cancelled``, once per run. Counted from when the cancel is due, not from
    when the timer thread got to run: a front-end's thread waits for Python's lock too, and
    a kernel holding it in a long call delays the Esc as much as a missing check would."""
    delays = []
    for _ in range(runs):
        node = make()
        threading.Timer(after, node.token.cancel).start()
        start = time.perf_counter()
        with pytest.raises(Cancelled):
            solve(node)
        delays.append(time.perf_counter() - (start + after))
    return delays


def check_gaps_of(node: Node, solve: Callable[[Node], object], seconds: float) -> list[float]:
    """The times between successive checks of ``node``'s token in the first ``seconds`` of
    its solve (the first from its start)."""
    token = RecordingToken(stop_after=seconds)
    node.own_context().token = token
    start = time.perf_counter()
    with pytest.raises(Cancelled):
        solve(node)
    return [b - a for a, b in pairwise([start, *token.times])]


def test_cancelling_the_bumpy_nurbs_area_costs_no_more_than_its_check_gap_and_a_hand_over():
    surface = NurbsSurface(bumpy_net(48), 3, 3)
    gap = float(np.percentile(check_gaps_of(Area(), lambda node: node.solve(surface), 1.5), 90))
    hand_over = statistics.median(cancel_delays(CheckingOnly, lambda node: node.solve()))
    delays = cancel_delays(Area, lambda node: node.solve(surface))
    delay = statistics.median(delays)
    ratio = delay / (gap + hand_over)
    print(
        f"\nArea node (bumpy 48 × 48) stops {duration(delay)} after the cancel "
        f"(median of 5; worst {duration(max(delays))})\n"
        f"  baseline, its gap between checks (90th percentile) {duration(gap)} + cancelling nothing "
        f"{duration(hand_over)}\n  ratio {ratio:.2f}"
    )
    assert ratio <= 1.5
    assert delay < 0.2


# -- the longest gap between checks, kernel by kernel --------------------------------------

def _area_graph() -> tuple[Graph, str]:
    graph = Graph()
    graph.add_node(Source(DataTree.from_value(NurbsSurface(bumpy_net(48), 3, 3))), "surface")
    graph.add_node(Area(), "area")
    graph.connect("surface", "Tree", "area", "Geometry")
    return graph, "area"


def _ruling_graph() -> tuple[Graph, str]:
    pair = PAIRS["conic_sections"]()
    graph = Graph()
    graph.add_node(Source(DataTree.from_value(pair.a)), "a")
    graph.add_node(Source(DataTree.from_value(pair.b)), "b")
    graph.add_node(RulingDevelopable(), "strip")
    graph.connect("a", "Tree", "strip", "CurveA")
    graph.connect("b", "Tree", "strip", "CurveB")
    graph.set_input_value("strip", "Segments", 1999)
    return graph, "strip"


@functools.cache
def _roof_strips() -> DataTree:
    """The rationalised roof's eight strips (solved once)."""
    roof = read_graph(EXAMPLES / "rationalise-roof.graph", default_registry(plugins=False))
    solver = Solver(roof)
    solver.solve()
    return solver.result("strips").outputs["Strips"]


def _bending_graph() -> tuple[Graph, str]:
    """BendingCheck at Density 200 over the rationalised roof's strips (40,000 points a strip)."""
    graph = Graph()
    graph.add_node(Source(_roof_strips()), "strips")
    graph.add_node(BendingCheck(), "bending")
    graph.connect("strips", "Tree", "bending", "Strips")
    graph.set_input_value("bending", "Density", 200)
    return graph, "bending"


def _iso_mapping_graph() -> tuple[Graph, str]:
    """IsoMapping of one roof strip at Segments 2000 (16,001 rulings sampled)."""
    graph = Graph()
    graph.add_node(Source(DataTree.from_value(_roof_strips().all_items()[0])), "strip")
    graph.add_node(IsoMapping(), "unroll")
    graph.connect("strip", "Tree", "unroll", "Surface")
    graph.set_input_value("unroll", "Segments", 2000)
    return graph, "unroll"


def _example(name: str, node_id: str) -> Callable[[], tuple[Graph, str]]:
    return lambda: (read_graph(EXAMPLES / f"{name}.graph", default_registry(plugins=False)), node_id)


def _not_checking(owner: str, what: str, strict: bool = True):
    return pytest.mark.xfail(strict=strict, reason=f"{what} does not check its token yet ({owner})")


KERNELS = [
    pytest.param(_area_graph, id="area-of-bumpy-nurbs"),
    pytest.param(_example("kaohsiung-stadium", "strip"), id="ruling-developable-kaohsiung-strips"),
    pytest.param(_bending_graph, id="bending-check-density-200"),
    pytest.param(_ruling_graph, id="ruling-developable-2000-stations"),
    pytest.param(_example("development-and-panels", "patching"), id="surface-patching"),
    pytest.param(_iso_mapping_graph, id="iso-mapping-2000-segments"),
    pytest.param(_example("rationalise-roof", "cut"), id="nesting-cut-sheets"),
    pytest.param(_example("rationalise-roof", "strips"), id="rationalise-roof"),
]

#: Runs of a kernel's gap measurement at most: a missing check shows in every run, a stall
#: of the shared machine (another process holding both cores for 0.1-0.3 s) in one.
RUNS = 3


@pytest.mark.parametrize("build", KERNELS)
def test_a_long_kernel_checks_for_cancellation_at_least_every_50_ms(build, request):
    ratios = []
    for _ in range(RUNS):  # the best of up to RUNS runs (see RUNS), each on a fresh graph
        graph, node_id = build()
        gaps = check_gaps(graph, stop_after=3.0)[node_id]
        block = check_interval_block()
        ratios.append(gaps.longest / block)
        print(
            f"\n{request.node.callspec.id}: longest {duration(gaps.longest)} without a check "
            f"({gaps.checks} checks in {duration(gaps.seconds)})\n"
            f"  baseline, the 50 ms block: {duration(block)}\n  ratio {ratios[-1]:.2f}"
        )
        if ratios[-1] <= 1.0:
            break
    assert min(ratios) <= 1.0
