"""The sliders a sweep or an optimisation varies, and the outputs it collects."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from torsal.app.headless import UsageError
from torsal.engine.graph import Graph

REDUCERS = ("mean", "sum", "min", "max", "count")


@dataclass(frozen=True)
class Variable:
    """One varied slider: its node id and the range ``low … high`` explored.

    ``integer`` sliders take whole numbers; a number slider's values are rounded to its
    ``decimals`` so that the value written in the table is the value the slider used.
    """

    node_id: str
    low: float
    high: float
    integer: bool = False
    decimals: int | None = None
    steps: int | None = None

    def snap(self, value: float) -> float | int:
        """``value`` kept within ``low … high`` and rounded as the slider rounds it."""
        value = min(max(float(value), self.low), self.high)
        if self.integer:
            return round(value)
        if self.decimals is not None:
            return round(value, self.decimals)
        return value

    def from_unit(self, u: float) -> float | int:
        """The value at ``u`` in 0 … 1 of the range, snapped."""
        return self.snap(self.low + (self.high - self.low) * float(u))

    def to_unit(self, value: float) -> float:
        span = self.high - self.low
        return 0.0 if span == 0 else (float(value) - self.low) / span

    @property
    def column(self) -> str:
        return f"in:{self.node_id}"


@dataclass(frozen=True)
class Target:
    """A collected output ``NODE.OUTPUT``, reduced to one value by ``:mean`` … when it holds several."""

    node_id: str
    port: str
    reducer: str | None = None

    @property
    def name(self) -> str:
        return f"{self.node_id}.{self.port}" + (f":{self.reducer}" if self.reducer else "")

    @property
    def column(self) -> str:
        return f"out:{self.name}"


def _number(text: str, flag: str, what: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise UsageError(f"{flag}: {what} must be a number, not {text!r}") from None
    if not math.isfinite(value):
        raise UsageError(f"{flag}: {what} must be a finite number, not {text!r}")
    return value


def parse_vary(text: str, graph: Graph, steps: bool) -> Variable:
    """``scale=0.5:0.9:5`` (``steps``) or ``scale=0.5:0.9``, checked against the slider's limits."""
    flag = f"--vary {text}"
    node_id, sep, spec = text.partition("=")
    node_id = node_id.strip()
    parts = spec.split(":")
    form = "ID=LO:HI:N" if steps else "ID=LO:HI"
    if not sep or not node_id or len(parts) != (3 if steps else 2):
        if not steps and len(parts) == 3:
            raise UsageError(f"{flag}: N steps are for --sampler grid; give {form}")
        raise UsageError(f"{flag}: give {form}")
    if node_id not in graph.nodes:
        raise UsageError(f"{flag}: there is no node with id {node_id!r}")
    settings = graph.nodes[node_id].node.settings
    current = settings.get("value")
    if "value" not in settings or isinstance(current, bool) or not isinstance(current, int | float):
        raise UsageError(f"{flag}: node {node_id!r} has no number value to vary (a slider has one)")
    low, high = _number(parts[0], flag, "LO"), _number(parts[1], flag, "HI")
    if low > high:
        raise UsageError(f"{flag}: LO ({low:g}) is greater than HI ({high:g})")
    limits = [settings.get(name) for name in ("min", "max")]
    if all(isinstance(v, int | float) and not isinstance(v, bool) for v in limits):
        lo_limit, hi_limit = float(limits[0]), float(limits[1])
        if low < lo_limit or high > hi_limit:
            raise UsageError(
                f"{flag}: {low:g}:{high:g} is outside the limits of slider {node_id!r}, "
                f"{lo_limit:g} to {hi_limit:g}"
            )
    type_id = graph.nodes[node_id].type_id
    integer = type_id == "params.IntegerSlider" or (isinstance(current, int) and "decimals" not in settings)
    decimals = settings.get("decimals")
    decimals = decimals if isinstance(decimals, int) and not isinstance(decimals, bool) else None
    count = None
    if steps:
        count_value = _number(parts[2], flag, "N")
        if not count_value.is_integer() or count_value < 1:
            raise UsageError(f"{flag}: N must be a whole number of steps, 1 or more, not {parts[2]!r}")
        count = int(count_value)
        distinct = _distinct_values(low, high, integer, decimals)
        if distinct is not None and count > distinct:
            raise UsageError(
                f"{flag}: slider {node_id!r} has only {distinct} distinct values from {low:g} to {high:g}: "
                f"give N up to {distinct}"
            )
        if count == 1 and low != high:
            raise UsageError(f"{flag}: one step cannot span {low:g} to {high:g}; give N ≥ 2 or LO = HI")
    if integer and (not low.is_integer() or not high.is_integer()):
        raise UsageError(f"{flag}: slider {node_id!r} is a whole-number slider: give whole LO and HI")
    return Variable(node_id, low, high, integer, None if integer else decimals, count)


def _distinct_values(low: float, high: float, integer: bool, decimals: int | None) -> int | None:
    if integer:
        return int(math.floor(high) - math.ceil(low)) + 1
    if decimals is not None and decimals <= 12:
        scale = 10.0**decimals
        return int(math.floor(high * scale + 1e-9) - math.ceil(low * scale - 1e-9)) + 1
    return None


def parse_target(text: str, graph: Graph, flag: str = "--collect") -> Target:
    """``strip.Valid`` or ``strip.Valid:mean``: the node and output must exist."""
    spec, _, reducer = text.partition(":")
    node_id, dot, port = spec.partition(".")
    if not dot or not node_id or not port:
        raise UsageError(f"{flag} {text}: give NODE.OUTPUT (or NODE.OUTPUT:{'|'.join(REDUCERS)})")
    if reducer and reducer not in REDUCERS:
        raise UsageError(f"{flag} {text}: {reducer!r} is not one of {', '.join(REDUCERS)}")
    if node_id not in graph.nodes:
        raise UsageError(f"{flag} {text}: there is no node with id {node_id!r}")
    outputs = [p.name for p in graph.nodes[node_id].node.output_ports()]
    if outputs and port not in outputs:
        raise UsageError(f"{flag} {text}: {node_id!r} has no output {port!r} (outputs: {', '.join(outputs)})")
    return Target(node_id, port, reducer or None)


def values_key(values: dict[str, Any]) -> str:
    """A stable text of varied values (for cache keys): floats by their exact repr."""
    return ";".join(f"{k}={values[k]!r}" for k in sorted(values))
