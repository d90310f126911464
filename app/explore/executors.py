"""Where variants are solved: in this process, local worker processes, or a dask cluster.

Every executor takes a batch of ``(index, values)`` and yields ``(index, outcome)`` as
variants finish, in any order; the caller puts them back in order. Local workers are a
``distributed.LocalCluster`` of single-threaded processes (BLAS limited to one thread by
dask's worker environment), so a worker that dies is restarted and its variant retried
by dask, exactly as on a remote cluster.
"""

from __future__ import annotations

import logging
import os
from collections.abc import Iterable, Iterator
from typing import Any

from app.explore.evaluate import Job, Stopped, solve_variant
from app.headless import UsageError
from engine.node import CancelToken

#: how often dask re-runs a variant whose worker died or which raised
RETRIES = 3
#: the status of a variant that failed on every try: not cached, a re-run tries again
WORKER_FAILED = "error: the worker failed"
_BLAS_THREADS = ("OMP_NUM_THREADS", "MKL_NUM_THREADS", "OPENBLAS_NUM_THREADS")


def default_workers() -> int:
    """The machine's cores available to this process."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except AttributeError:  # not on Linux
        return max(1, os.cpu_count() or 1)


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
    next node: :meth:`run` then raises :class:`~app.explore.evaluate.Stopped`.
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
        futures = {}
        for index, values in batch:
            future = self.client.submit(solve_variant, graph, values, job, index, retries=RETRIES, pure=False)
            futures[future] = (index, values)
        for future in as_completed(list(futures), loop=self.client.loop):
            index, values = futures[future]
            try:
                outcome = future.result()
            except Exception as exc:  # the variant failed even after dask's retries
                outcome = {"values": dict(values),
                           "outputs": {t.name: None for t in job.targets},
                           "status": f"{WORKER_FAILED}: {type(exc).__name__}: {exc}"}
            yield index, outcome

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
