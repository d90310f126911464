"""Solving one variant: the function every worker runs, in-process or on a dask worker.

A variant is the graph's text plus the values of its varied sliders; the result is a
plain dict (picklable, JSON-able): the collected values and a status. A variant whose
graph has a node in error is a result like any other, with the node's message.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import lru_cache
from pathlib import Path
from typing import Any

from torsal.app.explore.variables import Target
from torsal.app.plugins import missing_types
from torsal.engine.graphfile import GraphFileError, loads
from torsal.engine.node import CancelToken
from torsal.engine.registry import Registry
from torsal.engine.solver import ERROR, WARNING, Solver
from torsal.engine.write_path import make_folders
from torsal.engine.writes import WriteAccess

OK_STATUS = "ok"


@dataclass(frozen=True)
class Job:
    """What a worker needs besides the graph: the targets and the write policy."""

    targets: tuple[Target, ...]
    allow_writes: bool = False
    write_root: str | None = None  # variant N writes into write_root/NNNNN when allowed
    image_root: str | None = None  # variant N is drawn into image_root/NNNNN.png (--images)
    read_root: str | None = None  # the graph's folder: files its nodes read are found from here


@dataclass
class Outcome:
    """One solved variant: its collected values (None where there is no number) and status."""

    values: dict[str, Any]
    outputs: dict[str, Any] = field(default_factory=dict)
    status: str = OK_STATUS
    image: str | None = None  #: the picture's file name, when asked for and there was geometry

    def to_json(self) -> dict[str, Any]:
        data = {"values": self.values, "outputs": self.outputs, "status": self.status}
        if self.image is not None:
            data["image"] = self.image
        return data

    @classmethod
    def from_json(cls, data: dict[str, Any]) -> Outcome:
        image = data.get("image")
        return cls(dict(data["values"]), dict(data["outputs"]), str(data["status"]),
                   None if image is None else str(image))

    @property
    def failed(self) -> bool:
        return self.status.startswith("error")


@lru_cache(maxsize=1)
def _registry() -> Registry:
    from torsal.nodes.catalogue import default_registry

    return default_registry()


def reduce_items(items: list[Any], reducer: str | None) -> tuple[Any, str | None]:
    """One table value from an output's items, or ``(None, why)`` when there is none."""
    if reducer == "count":
        return len(items), None
    if not items:
        return None, "is empty"
    numbers = []
    for item in items:
        if isinstance(item, bool):
            numbers.append(1.0 if item else 0.0)
        elif isinstance(item, int | float):
            numbers.append(float(item))
        elif reducer is None and len(items) == 1 and isinstance(item, str):
            return item, None
        else:
            return None, f"holds a {type(item).__name__}, not a number"
    if reducer is None:
        if len(numbers) != 1:
            return None, f"holds {len(numbers)} items: add :mean, :sum, :min, :max or :count"
        value = items[0] if isinstance(items[0], int) and not isinstance(items[0], bool) else numbers[0]
    else:
        value = {"mean": lambda v: math.fsum(v) / len(v), "sum": math.fsum, "min": min, "max": max}[reducer](
            numbers
        )
    if isinstance(value, float) and not math.isfinite(value):
        return None, f"is {value!r}, not a finite number"
    return value, None


class Stopped(Exception):
    """The user stopped the exploration while a variant was being solved."""


def solve_variant(graph_text: str, values: dict[str, Any], job: Job, index: int = 0,
                  token: CancelToken | None = None) -> dict[str, Any]:
    """Solve ``graph_text`` with ``values`` set on its sliders; the outcome as a JSON-able dict.

    A cancelled ``token`` stops the solve at the next node and raises :class:`Stopped`.
    """
    return _solve(graph_text, values, job, index, token).to_json()


def _solve(graph_text: str, values: dict[str, Any], job: Job, index: int, token: CancelToken | None
           ) -> Outcome:
    try:
        graph = loads(graph_text, _registry())
    except GraphFileError as exc:
        return Outcome(values, {t.name: None for t in job.targets}, f"error: the graph cannot be read: {exc}")
    missing = missing_types(graph)
    if missing:  # a worker without a plug-in the sender has: raised, so dask tries another worker
        raise LookupError("this worker cannot solve the graph: " + "; ".join(m.sentence() for m in missing))
    for node_id, value in values.items():
        graph.set_setting(node_id, "value", value)
    access = WriteAccess()
    if job.allow_writes and job.write_root is not None:
        root = Path(job.write_root)  # DIR/variants, DIR resolved once by the command
        parts = (root.name, f"{index:05d}")
        try:
            identity = make_folders(root.parent, parts)
        except OSError as exc:
            return Outcome(values, {t.name: None for t in job.targets},
                           f"error: cannot make the variant's folder: {exc.strerror or exc}")
        access = WriteAccess.held(root / parts[1], identity, allowed=True)
    elif job.write_root is not None:  # no consent: the paths are still checked, then the node warns
        access = WriteAccess(Path(job.write_root) / f"{index:05d}", allowed=False)
    # files the graph reads are found from its own folder, wherever variants write
    access.read_folder = Path(job.read_root) if job.read_root is not None else None
    solver = Solver(graph, access)
    if solver.solve(token).cancelled:
        raise Stopped
    notes: list[str] = []
    errors: list[str] = []
    warnings = 0
    for node_id, record in graph.nodes.items():
        result = solver.result(node_id)
        if result.state == ERROR:
            text = next((m.text for m in result.messages), "in error")
            errors.append(f"{record.title} [{node_id}]: {text}")
        elif result.state == WARNING:
            warnings += 1
    outputs: dict[str, Any] = {}
    for target in job.targets:
        result = solver.result(target.node_id)
        if result.state == ERROR:  # no value, not 0 or an empty list's count
            outputs[target.name] = None
            continue
        tree = result.outputs.get(target.port)
        items = tree.all_items() if tree is not None else []
        value, why = reduce_items(items, target.reducer)
        outputs[target.name] = value
        if why:
            notes.append(f"{target.name} {why}")
    if errors:
        status = "error: " + "; ".join(errors + notes)
    elif notes:
        status = "no value: " + "; ".join(notes)
    else:
        plural = "s" if warnings > 1 else ""
        status = OK_STATUS if not warnings else f"ok (warnings in {warnings} node{plural})"
    image = None
    if job.image_root is not None:
        from torsal.app.explore.images import previewed_values, render

        name = f"{index:05d}.png"
        try:
            if render(previewed_values(graph, solver), Path(job.image_root) / name):
                image = name
        except OSError as exc:  # a link planted in DIR/images, a full disk: no picture, said so
            status += f"; no picture: {exc.strerror or exc}"
    return Outcome(values, outputs, status, image)
