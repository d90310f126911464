"""Solving untrusted graphs under guard: worker processes with a memory cap and a stall alarm.

The input-cap sweep (tests/nodes/test_input_caps.py) and the ``.graph`` fuzzer
(tools/fuzz_graphs.py, tests/app/test_fuzz_examples.py) solve thousands of hostile graphs.
A case that tries to allocate 20 GiB or loops for ever must be caught, named and
reported, not take the machine (shared with other work) down with it. So every case runs
in a worker process of a :class:`GuardedPool`:

- the worker's address space is capped (``RLIMIT_AS``: what it had at start plus
  ``memory_bytes``), so a huge allocation fails at once with a ``MemoryError``, which the
  solver turns into an error message that :func:`solve_guarded` reports as unexpected;
- each case has an alarm (``SIGALRM`` after ``seconds``) that stops a Python-level loop
  with :class:`Stalled`, and a hard watchdog (``faulthandler``) that ends a worker stuck
  in C code; a case whose worker dies is run again alone and reported as a stall;
- each case's peak resident memory is measured (Linux's ``VmHWM``, reset per case
  through ``/proc/self/clear_refs``), and its wall time.

:func:`solve_guarded` solves one graph and says which nodes failed with an exception the
node did not mean (the solver's ``_describe_exception`` path), with its traceback.
"""

from __future__ import annotations

import faulthandler
import os
import re
import resource
import signal
import time
import traceback
from collections.abc import Callable, Iterable
from concurrent.futures import FIRST_COMPLETED, Future, ProcessPoolExecutor, wait
from concurrent.futures.process import BrokenProcessPool
from dataclasses import dataclass, field
from multiprocessing import get_context
from typing import Any

#: A solver message made from an exception the node did not raise on purpose looks like
#: ``ZeroDivisionError: division by zero (in solve, line 12)``.
EXCEPTION_MESSAGE = re.compile(
    r"^[A-Za-z_][\w.]*(Error|Exception|Exit|Interrupt)?: .*\(in [\w<>.]+, line \d+\)$", re.DOTALL
)

#: Extra seconds the hard watchdog gives a case after its alarm before ending the worker.
HARD_GRACE = 10.0


class Stalled(BaseException):
    """Raised in a worker when a case runs past its alarm (a BaseException, so that a
    node's ``except Exception`` and the solver's catch-all let it through)."""


@dataclass
class CaseResult:
    """What one guarded case did: its wall time, peak memory and anything unexpected.

    ``unexpected`` holds one line per exception a node did not mean (type, message, and
    the innermost frames of its traceback); ``stalled`` is set when the case ran past its
    time; ``info`` is whatever the case function chose to return besides.
    """

    seconds: float = 0.0
    peak_bytes: int = 0
    unexpected: list[str] = field(default_factory=list)
    stalled: bool = False
    info: Any = None


# --------------------------------------------------------------------------- in the worker

_EXCEPTIONS: list[str] = []


def _peak_rss() -> int:
    """Peak resident memory of this process since the last reset, in bytes."""
    try:
        with open("/proc/self/status") as status:
            found = re.search(r"VmHWM:\s+(\d+)\s*kB", status.read())
        if found:
            return int(found.group(1)) * 1024
    except OSError:
        pass
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024


def _current_rss() -> int:
    try:
        with open("/proc/self/status") as status:
            found = re.search(r"VmRSS:\s+(\d+)\s*kB", status.read())
        if found:
            return int(found.group(1)) * 1024
    except OSError:
        pass
    return 0


def _reset_peak() -> None:
    try:
        with open("/proc/self/clear_refs", "w") as refs:
            refs.write("5")
    except OSError:
        pass


def _virtual_size() -> int:
    try:
        with open("/proc/self/status") as status:
            found = re.search(r"VmSize:\s+(\d+)\s*kB", status.read())
        if found:
            return int(found.group(1)) * 1024
    except OSError:
        pass
    return 0


def _on_alarm(signum: int, frame: Any) -> None:
    raise Stalled("the case ran past its time")


def _one_line(exc: BaseException) -> str:
    """``Type: message [file:line function <- ...]``, the innermost three frames."""
    frames = traceback.extract_tb(exc.__traceback__)[-3:]
    where = " <- ".join(f"{os.path.basename(f.filename)}:{f.lineno} {f.name}" for f in reversed(frames))
    return f"{type(exc).__name__}: {str(exc)[:300]} [{where}]"


def _record_exception(original: Callable[[Exception], str]) -> Callable[[Exception], str]:
    def describe(exc: Exception) -> str:
        _EXCEPTIONS.append(_one_line(exc))
        return original(exc)

    return describe


def init_worker(memory_bytes: int, cwd: str | None, preload: tuple[str, ...]) -> None:
    """Set up a worker: one BLAS thread, modules preloaded, address space capped, the
    solver's exception path recorded, and (for file-writing nodes) a scratch folder."""
    for name in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
        os.environ[name] = "1"
    import importlib

    for module in preload:
        importlib.import_module(module)
    import torsal.engine.solver

    if not getattr(torsal.engine.solver._describe_exception, "_guarded", False):
        torsal.engine.solver._describe_exception = _record_exception(torsal.engine.solver._describe_exception)
        torsal.engine.solver._describe_exception._guarded = True  # type: ignore[attr-defined]
    if cwd:
        os.chdir(cwd)
    if memory_bytes > 0:
        limit = _virtual_size() + memory_bytes
        _, hard = resource.getrlimit(resource.RLIMIT_AS)
        if hard != resource.RLIM_INFINITY:
            limit = min(limit, hard)
        resource.setrlimit(resource.RLIMIT_AS, (limit, hard))
    signal.signal(signal.SIGALRM, _on_alarm)


def run_guarded(function: Callable[[Any], Any], argument: Any, seconds: float) -> CaseResult:
    """Run ``function(argument)`` in this worker with an alarm, measuring time and memory."""
    _EXCEPTIONS.clear()
    result = CaseResult()
    _reset_peak()
    base = _current_rss()
    faulthandler.dump_traceback_later(seconds + HARD_GRACE, exit=True)
    started = time.perf_counter()
    try:
        try:  # the alarm is one-shot: once it has fired (anywhere in here) it cannot fire again
            signal.setitimer(signal.ITIMER_REAL, seconds)
            result.info = function(argument)
        finally:
            signal.setitimer(signal.ITIMER_REAL, 0)
    except Stalled:
        result.stalled = True
    except Exception as exc:  # the harness itself must report, not die
        result.unexpected.append(f"harness: {type(exc).__name__}: {str(exc)[:300]}\n{traceback.format_exc()}")
    finally:
        faulthandler.cancel_dump_traceback_later()
    result.seconds = time.perf_counter() - started
    result.peak_bytes = max(0, _peak_rss() - base)
    result.unexpected.extend(_EXCEPTIONS)
    _EXCEPTIONS.clear()
    return result


# --------------------------------------------------------------------------- in the parent


class GuardedPool:
    """Run a function over many cases in capped worker processes (see the module text).

    ``function`` must be importable by name (a module-level function). Results come
    back as ``(case, CaseResult)`` in completion order; a case whose worker died (hard
    stall, crash) is run again alone and, if it kills its worker again, reported as
    stalled.
    """

    def __init__(self, workers: int = 2, memory_bytes: int = 1 << 30, seconds: float = 20.0,
                 cwd: str | None = None, preload: Iterable[str] = ("torsal.nodes.catalogue",)) -> None:
        self.workers = max(1, workers)
        self.memory_bytes = memory_bytes
        self.seconds = seconds
        self.cwd = cwd
        self.preload = tuple(preload)

    def _executor(self, workers: int) -> ProcessPoolExecutor:
        context = get_context("forkserver")
        # the server imports these once (not the caller's __main__); workers fork from it
        context.set_forkserver_preload(list(self.preload))
        return ProcessPoolExecutor(
            max_workers=workers,
            mp_context=context,
            initializer=init_worker,
            initargs=(self.memory_bytes, self.cwd, self.preload),
        )

    def run(self, function: Callable[[Any], Any], cases: Iterable[Any]) -> Iterable[tuple[Any, CaseResult]]:
        suspects: list[Any] = []
        queue = list(cases)
        executor = self._executor(self.workers)
        try:
            running: dict[Future, Any] = {}
            while queue or running:
                while queue and len(running) < 4 * self.workers:
                    case = queue.pop()
                    running[executor.submit(run_guarded, function, case, self.seconds)] = case
                done, _ = wait(running, return_when=FIRST_COMPLETED)
                broken = False
                for future in done:
                    case = running.pop(future)
                    try:
                        yield case, future.result()
                    except BrokenProcessPool:
                        suspects.append(case)
                        broken = True
                if broken:
                    suspects.extend(running.values())
                    running.clear()
                    executor.shutdown(wait=False, cancel_futures=True)
                    executor = self._executor(self.workers)
        finally:
            executor.shutdown(wait=True, cancel_futures=True)
        for case in suspects:  # alone, so a dead worker names its case
            alone = self._executor(1)
            try:
                yield case, alone.submit(run_guarded, function, case, self.seconds).result()
            except BrokenProcessPool:
                yield case, CaseResult(seconds=self.seconds + HARD_GRACE, stalled=True,
                                       unexpected=["the worker died (stuck in C code past its watchdog, "
                                                   "or killed)"])
            finally:
                alone.shutdown(wait=True)


def node_modules() -> tuple[str, ...]:
    """The modules of every installed node type, for a pool to import once before forking
    its workers (so a case's time is its own, not the first import of its palette's)."""
    from torsal.nodes.catalogue import default_registry

    return tuple(sorted({cls.__module__ for cls in default_registry(plugins=False)}))


def solve_guarded(graph: Any, summarize: bool = False) -> dict[str, Any]:
    """Solve ``graph`` with the engine's solver; per node: state and messages.

    Exceptions a node did not mean are collected by the worker (see :func:`init_worker`)
    and land in :attr:`CaseResult.unexpected`; a message in the exception format without
    that record (a node formatting one itself) is listed too. With ``summarize``, every
    output is also described as ``torsal run --json`` describes it (lengths, areas), and
    an exception there is reported the same way.
    """
    import json

    from torsal.engine.solver import Solver
    from torsal.engine.types import summarize_value

    # as the app solves: a node with a background search (TrueShape nesting, which the
    # kaohsiung-cut-sheets example ships) answers at once and its search is not run here
    solver = Solver(graph, anytime=True)
    report = solver.solve()
    states = {}
    for node_id in graph.nodes:
        result = solver.result(node_id)
        texts = [m.text for m in result.messages]
        states[node_id] = (result.state, texts)
        for text in texts:
            if EXCEPTION_MESSAGE.match(text) and not _EXCEPTIONS:
                _EXCEPTIONS.append(f"exception-shaped message from {node_id}: {text[:300]}")
        if summarize:
            try:
                json.dumps({port: [summarize_value(v) for v in tree.all_items()]
                            for port, tree in result.outputs.items()})
            except Exception as exc:
                _EXCEPTIONS.append(f"summary of {node_id}: {_one_line(exc)}")
    return {"cancelled": report.cancelled, "nodes": states}
