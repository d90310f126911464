"""The same sweep on a dask.distributed LocalCluster (two processes on loopback), and a dead worker."""

from __future__ import annotations

import os
import signal
from pathlib import Path

import pytest

from tests.support.explore_graphs import formula_graph
from torsal.app.explore.executors import DaskExecutor, InlineExecutor
from torsal.app.explore.samplers import grid
from torsal.app.explore.study import open_study
from torsal.app.explore.sweep import RESULTS, run_sweep

KAOHSIUNG = Path(__file__).resolve().parents[3] / "torsal" / "resources" / "examples" / (
    "kaohsiung-stadium.graph"
)
pytestmark = pytest.mark.timeout(180)


def test_a_sweep_on_the_cluster_writes_the_same_table_as_one_in_this_process(cluster, tmp_path):
    path = formula_graph(tmp_path / "wave.graph", {"x": (0, 3, 1), "y": (0, 3, 1)},
                         {"f": "sin(x) * cos(2*y)"})
    study = open_study(path, ["x=0:3:4", "y=0:3:5"], ["f.Result"], steps=True)
    run_sweep(study, grid(study.variables), InlineExecutor(), tmp_path / "here")
    with DaskExecutor(scheduler=cluster.scheduler_address) as executor:
        result = run_sweep(study, grid(study.variables), executor, tmp_path / "there")
    assert result.solved == 20
    assert (tmp_path / "there" / RESULTS).read_text() == (tmp_path / "here" / RESULTS).read_text()


def test_killing_a_worker_mid_sweep_loses_no_row(cluster, tmp_path):
    study = open_study(KAOHSIUNG, ["scale=0.6:0.8:6"], ["strips.Result", "strip.Valid:mean"], steps=True)
    variants = grid(study.variables)
    killed = []
    with DaskExecutor(scheduler=cluster.scheduler_address) as executor:
        workers = list(executor.client.scheduler_info()["workers"])

        def kill_one(index, outcome):
            if not killed:  # the first variant is back: the other worker is busy with one
                busy = [a for a, tasks in executor.client.processing().items() if tasks] or workers
                nanny = next(n for n in cluster.workers.values() if n.worker_address == busy[0])
                os.kill(nanny.process.process.pid, signal.SIGKILL)
                killed.append(busy[0])

        result = run_sweep(study, variants, executor, tmp_path / "out", on_outcome=kill_one)
    assert killed
    assert [o.values for o in result.outcomes] == variants
    here = run_sweep(study, variants, InlineExecutor())
    assert [o.outputs for o in result.outcomes] == [o.outputs for o in here.outcomes]
    assert [o.status for o in result.outcomes] == [o.status for o in here.outcomes]


def test_an_optimisation_on_the_cluster_makes_the_same_evaluations_as_one_in_this_process(cluster, tmp_path):
    from torsal.app.explore.optimise import optimise

    path = formula_graph(tmp_path / "bowl.graph", {"x": (-5, 5, 4), "y": (-5, 5, -3)},
                         {"f": "(x - 1.3)**2 + 2*(y + 0.7)**2"})
    study = open_study(path, ["x=-5:5", "y=-5:5"], ["f.Result"], steps=False)
    here = optimise(study, InlineExecutor(), [1], budget=60, seed=4)
    with DaskExecutor(scheduler=cluster.scheduler_address) as executor:
        there = optimise(study, executor, [1], budget=60, seed=4)
    assert [e.values for e in there.evaluated] == [e.values for e in here.evaluated]
    assert there.best.objectives == here.best.objectives


def test_local_workers_run_one_thread_each_with_blas_limited_to_one_thread():
    with DaskExecutor(workers=1) as executor:
        threads = executor.client.nthreads()
        environ = executor.client.run(lambda: {k: os.environ.get(k) for k in ("OMP_NUM_THREADS",
                                                                               "OPENBLAS_NUM_THREADS")})
    assert list(threads.values()) == [1]
    assert list(environ.values()) == [{"OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1"}]


def test_local_workers_run_without_the_sampling_profiler_or_work_stealing():
    import dask

    with DaskExecutor(workers=1) as executor:
        profiling = executor.client.run(lambda: dask.config.get("distributed.worker.profile.enabled"))
        stealing = executor.client.run_on_scheduler(
            lambda dask_scheduler: "stealing" in dask_scheduler.extensions)
    assert list(profiling.values()) == [False]
    assert stealing is False
