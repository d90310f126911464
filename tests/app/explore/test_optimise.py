"""``torsal optimise``: a bowl, a multi-modal function in a box, and a two-objective front."""

from __future__ import annotations

import numpy as np
import pytest
from pymoo.indicators.hv import HV

from tests.support.explore_graphs import formula_graph
from torsal.app.explore.executors import InlineExecutor
from torsal.app.explore.optimise import dominates, optimise
from torsal.app.explore.study import open_study


@pytest.fixture
def bowl(tmp_path):
    """(x - 1.3)² + 2 (y + 0.7)²: its minimum 0 is at (1.3, -0.7)."""
    path = formula_graph(tmp_path / "bowl.graph", {"x": (-5, 5, 4), "y": (-5, 5, -3)},
                         {"f": "(x - 1.3)**2 + 2*(y + 0.7)**2"})
    return open_study(path, ["x=-5:5", "y=-5:5"], ["f.Result"], steps=False)


def test_cma_finds_the_bowls_minimum_within_1e_3_in_400_evaluations(bowl):
    result = optimise(bowl, InlineExecutor(), [1], budget=400, seed=0)
    assert result.evaluations <= 400
    assert result.best.values["x"] == pytest.approx(1.3, abs=1e-3)
    assert result.best.values["y"] == pytest.approx(-0.7, abs=1e-3)


def test_maximising_the_negated_bowl_finds_the_same_point(tmp_path):
    path = formula_graph(tmp_path / "cap.graph", {"x": (-5, 5, 4), "y": (-5, 5, -3)},
                         {"f": "-((x - 1.3)**2 + 2*(y + 0.7)**2)"})
    study = open_study(path, ["x=-5:5", "y=-5:5"], ["f.Result"], steps=False)
    result = optimise(study, InlineExecutor(), [-1], budget=400, seed=0)
    assert (result.best.values["x"], result.best.values["y"]) == pytest.approx((1.3, -0.7), abs=1e-3)


def test_himmelblaus_minimum_in_the_positive_quadrant_is_found_from_a_far_start(tmp_path):
    # four minima of value 0; in 0 … 5 × 0 … 5 only (3, 2); the start (0.5, 4.5) is far from it
    path = formula_graph(tmp_path / "himmelblau.graph", {"x": (0, 5, 0.5), "y": (0, 5, 4.5)},
                         {"f": "(x**2 + y - 11)**2 + (x + y**2 - 7)**2"})
    study = open_study(path, ["x=0:5", "y=0:5"], ["f.Result"], steps=False)
    result = optimise(study, InlineExecutor(), [1], budget=400, seed=1)
    assert (result.best.values["x"], result.best.values["y"]) == pytest.approx((3.0, 2.0), abs=1e-3)


def test_differential_evolution_also_finds_the_bowls_minimum_roughly(bowl):
    result = optimise(bowl, InlineExecutor(), [1], budget=400, seed=0, method="de")
    assert result.evaluations <= 400
    assert (result.best.values["x"], result.best.values["y"]) == pytest.approx((1.3, -0.7), abs=2e-2)


def test_the_same_seed_gives_the_same_search(bowl):
    first = optimise(bowl, InlineExecutor(), [1], budget=60, seed=5)
    second = optimise(bowl, InlineExecutor(), [1], budget=60, seed=5)
    assert [e.values for e in first.evaluated] == [e.values for e in second.evaluated]
    other = optimise(bowl, InlineExecutor(), [1], budget=60, seed=6)
    assert [e.values for e in other.evaluated] != [e.values for e in first.evaluated]


def test_stop_ends_the_search_after_the_current_generation(bowl):
    result = optimise(bowl, InlineExecutor(), [1], budget=400, seed=0, should_stop=lambda: True)
    assert result.stopped and len(result.generations) == 1


def test_nsga2_front_dominates_a_random_sample_of_the_same_size(tmp_path):
    # f1 = x² + y², f2 = (x - 1)² + y²: the front is y = 0, 0 ≤ x ≤ 1
    path = formula_graph(tmp_path / "two.graph", {"x": (-2, 2, 1.5), "y": (-2, 2, 1.5)},
                         {"f1": "x**2 + y**2", "f2": "(x - 1)**2 + y**2"})
    study = open_study(path, ["x=-2:2", "y=-2:2"], ["f1.Result", "f2.Result"], steps=False)
    result = optimise(study, InlineExecutor(), [1, 1], budget=400, seed=0)
    front = [e.objectives for e in result.front]
    assert len(front) >= 10 and result.evaluations <= 400
    off = []  # y² of each front point: 0 on the true front
    for f1, f2 in front:
        x = (f1 - f2 + 1) / 2
        off.append(f1 - x * x)
        assert -0.05 <= x <= 1.05
    assert np.median(off) < 5e-3 and max(off) < 0.02  # |y| ≲ 0.07, at worst 0.14 (measured 0.05, 0.11)
    rng = np.random.default_rng(7)
    sample = rng.uniform(-2, 2, size=(result.evaluations, 2))
    randoms = [[x * x + y * y, (x - 1) ** 2 + y * y] for x, y in sample]
    beaten = sum(any(dominates(f, r) for f in front) for r in randoms)
    assert beaten >= 0.95 * len(randoms)  # a few random points land near the front: 396 of 400 measured
    reference = np.max(np.vstack([front, randoms]), axis=0) + 1.0
    assert HV(ref_point=reference)(np.array(front)) > HV(ref_point=reference)(np.array(randoms))
