"""``torsal optimise``: find the slider values that minimise or maximise a graph's outputs.

One objective: CMA-ES (the ``cma`` package, the default: it converged in fewer solves
than differential evolution on every graph we measured, see the README) or scipy's
differential evolution. Two or more: NSGA-II (``pymoo``), returning the Pareto front of
every variant evaluated. The search runs on the sliders' ranges scaled to 0 … 1; the
same seed gives the same evaluations, whatever executor solves them.

A variant with a node in error, or whose objective is not a finite number, is
infeasible: it ranks below every feasible one.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from torsal.app.explore.evaluate import Job, Outcome, Stopped
from torsal.app.explore.executors import Executor
from torsal.app.explore.progress import Progress
from torsal.app.explore.study import Study
from torsal.app.explore.variables import values_key

METHODS = ("cma", "de")
DEFAULT_METHOD = "cma"
DEFAULT_BUDGET = 400


@dataclass
class Generation:
    """One generation: its number, the best and mean objective (first objective), evaluations so far."""

    index: int
    best: float
    mean: float
    evaluations: int


@dataclass
class Evaluated:
    values: dict[str, Any]
    objectives: list[float]  # as the user sees them (not negated); nan when infeasible
    outcome: Outcome

    @property
    def feasible(self) -> bool:
        return all(math.isfinite(f) for f in self.objectives)


@dataclass
class OptimiseResult:
    method: str
    evaluated: list[Evaluated] = field(default_factory=list)
    evaluations: int = 0
    solves: int = 0
    generations: list[Generation] = field(default_factory=list)
    best: Evaluated | None = None
    front: list[Evaluated] = field(default_factory=list)
    stopped: bool = False

    def to_json(self, study: Study, seed: int) -> dict[str, Any]:
        data: dict[str, Any] = {}
        names = [t.name for t in study.targets]
        if len(names) == 1:
            best = self.best
            data["best"] = None if best is None else {
                "values": best.values, "objective": best.objectives[0], "status": best.outcome.status,
            }
        else:
            data["front"] = [
                {"values": e.values, "objectives": dict(zip(names, e.objectives, strict=True))}
                for e in self.front
            ]
        data.update(
            evaluations=self.evaluations, solves=self.solves, generations=len(self.generations),
            method=self.method, seed=seed, stopped=self.stopped,
        )
        return data


class Objective:
    """Evaluates batches of points in 0 … 1 (one row per point) through an executor.

    Returns the objectives to minimise (maximised ones negated), ``inf`` when infeasible.
    A point already solved (an integer slider makes repeats) is not solved again.
    """

    def __init__(self, study: Study, executor: Executor, senses: list[int], budget: int,
                 progress: Progress | None = None) -> None:
        self.study = study
        self.executor = executor
        self.senses = senses
        self.budget = budget
        self.progress = progress
        self.job = Job(tuple(study.targets), read_root=str(Path(study.path).resolve().parent))
        self.memo: dict[str, Evaluated] = {}
        self.result: OptimiseResult | None = None

    def values_of(self, unit: np.ndarray) -> dict[str, Any]:
        return {v.node_id: v.from_unit(u) for v, u in zip(self.study.variables, unit, strict=True)}

    def __call__(self, units: np.ndarray) -> np.ndarray:
        assert self.result is not None
        points = [self.values_of(np.clip(row, 0.0, 1.0)) for row in np.atleast_2d(units)]
        keys = [values_key(p) for p in points]
        todo = {}
        for key, values in zip(keys, points, strict=True):
            if key not in self.memo and key not in todo:
                todo[key] = values
        batch = list(enumerate(todo.values()))
        order = list(todo)
        for index, data in self.executor.run(self.study.text, self.job, batch):
            outcome = Outcome.from_json(data)
            self.memo[order[index]] = Evaluated(outcome.values, self._objectives(outcome), outcome)
            self.result.solves += 1
        rows = []
        for key in keys:
            if self.progress is not None:
                self.progress.advance(cached=key not in todo)
            evaluated = self.memo[key]
            self.result.evaluated.append(evaluated)
            self.result.evaluations += 1
            rows.append([s * f if math.isfinite(f) else math.inf for s, f in
                         zip(self.senses, evaluated.objectives, strict=True)])
            self._keep_best(evaluated)
        scores = np.array(rows, dtype=float)
        self._generation(scores[:, 0] * self.senses[0])
        return scores

    def _objectives(self, outcome: Outcome) -> list[float]:
        values = []
        for target in self.study.targets:
            value = outcome.outputs.get(target.name)
            ok = isinstance(value, int | float) and not isinstance(value, bool) and not outcome.failed
            values.append(float(value) if ok and math.isfinite(value) else math.nan)
        return values

    def _keep_best(self, evaluated: Evaluated) -> None:
        result = self.result
        if not evaluated.feasible:
            return
        score = self.senses[0] * evaluated.objectives[0]
        if result.best is None or score < self.senses[0] * result.best.objectives[0]:
            result.best = evaluated

    def _generation(self, firsts: np.ndarray) -> None:
        finite = firsts[np.isfinite(firsts)]
        best = self.result.best.objectives[0] if self.result.best is not None else math.nan
        mean = float(finite.mean()) if finite.size else math.nan
        self.result.generations.append(Generation(len(self.result.generations), best, mean,
                                                  self.result.evaluations))


def optimise(
    study: Study,
    executor: Executor,
    senses: list[int],
    *,
    budget: int = DEFAULT_BUDGET,
    seed: int = 0,
    method: str = DEFAULT_METHOD,
    progress: Progress | None = None,
    on_generation: Callable[[Generation], None] | None = None,
    should_stop: Callable[[], bool] | None = None,
) -> OptimiseResult:
    """Search ``study``'s sliders for the best of its targets; ``senses`` +1 minimise, -1 maximise."""
    objective = Objective(study, executor, senses, budget, progress)
    name = "nsga2" if len(senses) > 1 else method
    objective.result = OptimiseResult({"cma": "cma-es", "de": "differential-evolution"}.get(name, name))
    stop = should_stop or (lambda: False)

    def generation_done() -> bool:
        if on_generation is not None and objective.result.generations:
            on_generation(objective.result.generations[-1])
        if stop():
            objective.result.stopped = True
            return True
        return False

    try:
        if len(senses) > 1:
            _nsga2(objective, budget, seed, generation_done)
        elif method == "de":
            _differential_evolution(objective, budget, seed, generation_done)
        else:
            _cma(objective, budget, seed, generation_done)
    except Stopped:  # stopped in the middle of a generation: keep what was evaluated
        objective.result.stopped = True
    result = objective.result
    if len(senses) > 1:
        result.front = pareto_front(list(objective.memo.values()), senses)
    return result


def _start(objective: Objective) -> np.ndarray:
    """The sliders' current values, in 0 … 1: the search starts from the design as it is."""
    start = []
    for variable in objective.study.variables:
        value = objective.study.graph.nodes[variable.node_id].node.settings.get("value")
        unit = variable.to_unit(value) if isinstance(value, int | float) else 0.5
        start.append(min(max(unit, 0.0), 1.0))
    return np.array(start)


def _cma(objective: Objective, budget: int, seed: int, generation_done: Callable[[], bool]) -> None:
    import cma

    dimensions = len(objective.study.variables)
    options = {
        "bounds": [0.0, 1.0], "seed": seed + 1,  # cma takes seed 0 as "from the clock"
        "verbose": -9, "tolx": 1e-9, "tolfun": 1e-14, "tolflatfitness": 10,
    }
    x0 = _start(objective)
    # cma wants two or more dimensions: one slider gets a dummy second one that changes nothing
    es = cma.CMAEvolutionStrategy(np.r_[x0, 0.5] if dimensions == 1 else x0, 0.3, options)
    while not es.stop():
        population = es.ask()
        if objective.result.evaluations + len(population) > budget:
            break
        points = np.array(population)[:, :dimensions]
        scores = objective(points)[:, 0]
        finite = scores[np.isfinite(scores)]
        worst = float(finite.max()) if finite.size else 0.0
        penalised = np.where(np.isfinite(scores), scores, worst + 1.0 + abs(worst))
        es.tell(population, penalised.tolist())
        if generation_done():
            break


def _differential_evolution(objective: Objective, budget: int, seed: int,
                            generation_done: Callable[[], bool]) -> None:
    from scipy.optimize import differential_evolution

    dimensions = len(objective.study.variables)
    multiplier = 10
    population = multiplier * dimensions
    maxiter = max(budget // population - 1, 0)
    stopped = False

    def batch(x: np.ndarray) -> np.ndarray:
        return objective(x.T)[:, 0]

    def callback(*_: Any) -> bool:
        nonlocal stopped
        stopped = generation_done()
        return stopped

    differential_evolution(
        batch, [(0.0, 1.0)] * dimensions, popsize=multiplier, maxiter=maxiter, seed=seed, polish=False,
        vectorized=True, updating="deferred", tol=1e-10, atol=0.0, callback=callback, init="latinhypercube",
    )


def _nsga2(objective: Objective, budget: int, seed: int, generation_done: Callable[[], bool]) -> None:
    from pymoo.algorithms.moo.nsga2 import NSGA2
    from pymoo.core.problem import Problem

    dimensions = len(objective.study.variables)
    count = len(objective.senses)

    class _Problem(Problem):
        def __init__(self) -> None:
            super().__init__(n_var=dimensions, n_obj=count, n_ieq_constr=1, xl=0.0, xu=1.0)

        def _evaluate(self, x: np.ndarray, out: dict[str, Any], *args: Any, **kwargs: Any) -> None:
            scores = objective(x)
            feasible = np.isfinite(scores).all(axis=1)
            out["F"] = np.where(np.isfinite(scores), scores, 1e300)
            out["G"] = np.where(feasible, -1.0, 1.0)[:, None]

    size = int(min(100, max(8, budget // 10)))
    algorithm = NSGA2(pop_size=size)
    algorithm.setup(_Problem(), termination=("n_evals", budget), seed=seed, verbose=False)
    while algorithm.has_next():
        if objective.result.evaluations + size > budget:
            break
        algorithm.next()
        if generation_done():
            break


def dominates(a: list[float], b: list[float]) -> bool:
    """``a`` is no worse than ``b`` in every objective and better in one (both minimised)."""
    return all(x <= y for x, y in zip(a, b, strict=True)) and any(x < y for x, y in zip(a, b, strict=True))


def pareto_front(evaluated: list[Evaluated], senses: list[int]) -> list[Evaluated]:
    """The feasible points no other point dominates, sorted by the first objective."""
    feasible = [e for e in evaluated if e.feasible]
    if not feasible:
        return []
    scores = np.array([[s * f for s, f in zip(senses, e.objectives, strict=True)] for e in feasible])
    keep = np.ones(len(feasible), dtype=bool)
    for i in range(len(feasible)):
        no_worse = (scores <= scores[i]).all(axis=1)
        better = (scores < scores[i]).any(axis=1)
        if (no_worse & better).any():
            keep[i] = False
    front = [e for e, k in zip(feasible, keep, strict=True) if k]
    return sorted(front, key=lambda e: senses[0] * e.objectives[0])
