"""Where variants are solved: in this process, local worker processes, or a dask cluster.

Every executor takes a batch of ``(index, values)`` and yields ``(index, outcome)`` as
variants finish, in any order; the caller puts them back in order. Local workers are a
``distributed.LocalCluster`` of single-threaded processes (BLAS limited to one thread by
dask's worker environment), so a worker that dies is restarted and its variant retried
by dask, exactly as on a remote cluster.

Variants travel to the workers in chunks of a few (:func:`chunk_size`): each dask task has
a fixed cost in the scheduler and the client, paid by the same cores the workers solve
on, and a chunk pays it once for several variants while leaving enough chunks per worker
that the last ones finish close together.
"""

from __future__ import annotations

import logging
import os
from collections.abc import Iterable, Iterator
from typing import Any

from torsal.app.explore.evaluate import Job, Stopped, solve_variant
from torsal.app.headless import UsageError
from torsal.engine.node import CancelToken

#: how often dask re-runs a variant whose worker died or which raised
RETRIES = 3
#: chunks per worker a batch is cut into at least: more balance the end, fewer cost less
CHUNKS_PER_WORKER = 6
#: the most variants in one chunk (a dead worker's chunk is solved again whole)
MAX_CHUNK = 8
#: the status of a variant that failed on every try: not cached, a re-run tries again
WORKER_FAILED = "error: the worker failed"
_BLAS_THREADS = ("OMP_NUM_THREADS", "MKL_NUM_THREADS", "OPENBLAS_NUM_THREADS")
#: dask settings for the local cluster. The workers' statistical profiler samples every
#: thread each 10 ms (measured: a tenth of a variant's time) and work stealing balances
#: tasks the chunks already balance; on a machine whose every core solves, both cost solves.
_LOCAL_CLUSTER_CONFIG = {
    "distributed.worker.profile.enabled": False,
    "distributed.scheduler.work-stealing": False,
}


def default_workers() -> int:
    """The machine's cores available to this process."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except AttributeError:  # not on Linux
        return max(1, os.cpu_count() or 1)


def chunk_size(variants: int, workers: int) -> int:
    """How many variants one task carries, for ``variants`` spread over ``workers``."""
    return max(1, min(MAX_CHUNK, variants // max(1, workers * CHUNKS_PER_WORKER)))


def solve_chunk(graph_text: str, chunk: list[tuple[int, dict[str, Any]]], job: Job
                ) -> list[tuple[int, dict[str, Any]]]:
    """Solve a chunk of variants one after the other (the task a dask worker runs)."""
    return [(index, solve_variant(graph_text, values, job, index)) for index, values in chunk]


class Executor:
    """Solves batches of variants of one graph."""

    def run(self, graph_text: str, job: Job, batch: Iterable[tuple[int, dict[str, Any]]]
            ) -> Iterator[tuple[int, dict[str, Any]]]:
        raise NotImplementedError

    def close(self) -> None:
        """Release workers and connections."""

    def __enter__(self) -> Executor:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()


class InlineExecutor(Executor):
    """Solves variants one after the other in this process (tests, the app's own thread).

    Cancelling ``token`` (from another thread) stops the variant being solved at its
    next node: :meth:`run` then raises :class:`~torsal.app.explore.evaluate.Stopped`.
    """

    def __init__(self, token: CancelToken | None = None) -> None:
        self.solves = 0
        self.token = token or CancelToken()

    def run(self, graph_text, job, batch):
        for index, values in batch:
            if self.token.cancelled:
                raise Stopped
            self.solves += 1
            yield index, solve_variant(graph_text, values, job, index, self.token)


class DaskExecutor(Executor):
    """Sends variants to a dask.distributed scheduler; the graph travels once, as text."""

    def __init__(self, scheduler: str | None = None, workers: int | None = None) -> None:
        try:
            from distributed import Client, LocalCluster
        except ImportError as exc:  # pragma: no cover - dask[distributed] is a dependency
            message = f"dask.distributed is not installed ({exc}): pip install 'dask[distributed]'"
            raise UsageError(message) from None
        self._cluster = None
        self._graph_futures: dict[int, Any] = {}
        if scheduler is not None:
            try:
                self.client = Client(scheduler, timeout=10, set_as_default=False)
            except (OSError, TimeoutError, ValueError) as exc:
                raise UsageError(f"--scheduler {scheduler}: cannot reach a dask scheduler there ({exc})"
                                 ) from None
        else:
            count = workers or default_workers()
            for name in _BLAS_THREADS:  # also dask's default for its workers: set it whatever the config
                os.environ.setdefault(name, "1")
            import dask

            with dask.config.set(_LOCAL_CLUSTER_CONFIG):
                self._cluster = LocalCluster(
                    n_workers=count, threads_per_worker=1, processes=True, host="127.0.0.1",
                    dashboard_address="127.0.0.1:0", silence_logs=logging.CRITICAL,
                )
            self.client = Client(self._cluster, set_as_default=False)

    @property
    def scheduler_address(self) -> str:
        return self.client.scheduler.address

    def run(self, graph_text, job, batch):
        from distributed import as_completed

        key = hash(graph_text)
        if key not in self._graph_futures:
            self._graph_futures[key] = self.client.scatter(graph_text, broadcast=True, hash=True)
        graph = self._graph_futures[key]
        batch = list(batch)
        size = chunk_size(len(batch), self.worker_count())
        futures = {}
        for start in range(0, len(batch), size):
            chunk = batch[start:start + size]
            future = self.client.submit(solve_chunk, graph, chunk, job, retries=RETRIES, pure=False)
            futures[future] = chunk
        for future in as_completed(list(futures), loop=self.client.loop):
            chunk = futures[future]
            try:
                yield from future.result()
            except Exception as exc:  # the chunk failed even after dask's retries
                status = f"{WORKER_FAILED}: {type(exc).__name__}: {exc}"
                for index, values in chunk:
                    yield index, {"values": dict(values),
                                  "outputs": {t.name: None for t in job.targets}, "status": status}

    def worker_count(self) -> int:
        """The workers the scheduler has now (at least one, as a chunking hint)."""
        try:
            return max(1, len(self.client.scheduler_info().get("workers", {})))
        except (OSError, TimeoutError, KeyError):
            return 1

    def close(self) -> None:
        self.client.close()
        if self._cluster is not None:
            self._cluster.close()


class LazyExecutor(Executor):
    """Starts (or connects to) the workers at the first batch that has something to solve.

    A sweep found whole in the cache starts no cluster at all, and a local cluster gets
    no more processes than the first batch has variants (without ``--workers``).
    """

    def __init__(self, workers: int | None, scheduler: str | None) -> None:
        self.workers = workers
        self.scheduler = scheduler
        self.inner: DaskExecutor | None = None

    def run(self, graph_text, job, batch):
        batch = list(batch)
        if not batch:
            return iter(())
        if self.inner is None:
            workers = self.workers or min(default_workers(), len(batch))
            self.inner = DaskExecutor(scheduler=self.scheduler, workers=workers)
        return self.inner.run(graph_text, job, batch)

    def close(self) -> None:
        if self.inner is not None:
            self.inner.close()


def make_executor(workers: int | None, scheduler: str | None) -> Executor:
    """``--workers N`` (local processes) or ``--scheduler ADDRESS`` (a running cluster)."""
    if workers is not None and workers < 1:
        raise UsageError(f"--workers {workers}: give 1 or more worker processes")
    return LazyExecutor(workers, scheduler)
