"""analysis.WarpChart: the warp of every ruling along a strip, as a line chart."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from torsal.engine.node import LIST, In, Node, NodeWarning, Out
from torsal.engine.types import INTEGER, NUMBER, TEXT, describe
from torsal.nodes.common.charts import target, write_chart
from torsal.nodes.common.checks import angle
from torsal.nodes.common.values import LINE
from torsal.nodes.geometry.array_types import FloatArray
from torsal.nodes.geometry.curves.line import Line


def _warps(values: list[Any]) -> FloatArray:
    out = np.full(len(values), math.nan)
    for i, v in enumerate(values):
        if v is None:
            continue
        try:
            out[i] = float(v)
        except (TypeError, ValueError):
            raise NodeWarning(f"WarpAngles item {i} is {describe(v)}, not a number") from None
    return out


def positions(rulings: list[Line]) -> FloatArray:
    """The distance along the strip of each ruling: from the first ruling's midpoint,
    through the midpoints of those between."""
    starts = np.array([np.asarray(r.start, dtype=float) for r in rulings]).reshape(-1, 3)
    ends = np.array([np.asarray(r.end, dtype=float) for r in rulings]).reshape(-1, 3)
    steps = np.linalg.norm(np.diff(0.5 * (ends - starts), axis=0) + np.diff(starts, axis=0), axis=1)
    return np.concatenate([[0.0], np.cumsum(steps)])


class WarpChart(Node):
    """Draw the warp of every ruling along a strip, to see where it stops being developable.

    Wire a developable node's WarpAngles (radians, one per ruling, as every strip
    node gives them) and, optionally, its Rulings: then the chart runs along the
    strip in model units (Positions: the distance from the first ruling's midpoint
    through the others'), else ruling by ruling. A dashed line marks Tolerance;
    Over counts the rulings whose warp is
    above it — those a flat sheet cannot follow there. A NaN warp (no tangent plane
    at that ruling) leaves a gap and is counted in Summary, never drawn as 0.

    The chart is a PNG image written to File, or to a temporary folder when File is
    empty; the inspector shows it.
    """

    type_id = "analysis.WarpChart"
    nickname, aliases = "Warp", ("warp graph", "twist chart")
    inputs = (
        In("WarpAngles", NUMBER, "W", "The warp angle of each ruling, rad, in order along the strip.",
           access=LIST),
        In("Rulings", LINE, "R", "Optional: the rulings themselves, same order, for distances along the "
           "strip.", access=LIST, optional=True),
        In("Tolerance", NUMBER, "Tol", "The warp (rad) a sheet may take along one ruling.", default=0.01),
        In("Title", TEXT, "T", "The chart's title.", default="Warp along the strip"),
        In("File", TEXT, "F", "Path of the .png to write; empty for a temporary file.", default=""),
    )
    outputs = (
        Out("Image", TEXT, "I", "Path of the PNG image written."),
        Out("Over", INTEGER, "O", "How many rulings warp by more than Tolerance."),
        Out("Positions", NUMBER, "P", "Where each ruling is along the strip, in model units (with "
            "Rulings; else its index).", access=LIST),
        Out("Summary", TEXT, "S", "Largest and mean warp, and how many rulings are over Tolerance."),
    )

    def solve(self, warp_angles: list[Any], rulings: list[Any] | None, tolerance: Any, title: Any,
              file: Any) -> tuple[Any, ...]:
        if not warp_angles:
            raise NodeWarning("WarpAngles is empty: there is nothing to chart")
        warp = _warps(warp_angles)
        tol = angle("Tolerance", tolerance, "0.01")
        lines = [r for r in (rulings or []) if r is not None]
        if lines and not all(isinstance(r, Line) for r in lines):
            bad = next(r for r in lines if not isinstance(r, Line))
            raise NodeWarning(f"Rulings holds {describe(bad)}: give the strip's rulings (lines)")
        if lines and len(lines) != len(warp):
            raise NodeWarning(f"Rulings has {len(lines)} lines but WarpAngles {len(warp)} values: wire the "
                              "same node's Rulings and WarpAngles")
        x = positions(lines) if lines else np.arange(len(warp), dtype=float)
        defined = np.isfinite(warp)
        if not defined.any():
            raise NodeWarning("None of the WarpAngles is a number: there is nothing to chart")
        if np.abs(warp[defined]).max() > 1e300:  # the axis' margins and ticks would overflow
            raise NodeWarning("WarpAngles reach beyond 1e+300: too large to draw an axis for (warps are "
                              "angles in radians, 0 to π)")
        if np.abs(x).max() > 1e300:
            raise NodeWarning("The Rulings lie beyond 1e+300 along the strip: too far to draw an axis for")
        over = int(np.count_nonzero(warp[defined] > tol))
        summary = (f"max {warp[defined].max():.6g} rad, mean {warp[defined].mean():.6g} rad over "
                   f"{int(defined.sum())} rulings; {over} over the tolerance {tol:g} rad")
        undefined = len(warp) - int(defined.sum())
        if undefined:
            summary += f" ({undefined} undefined, left out)"
        heading = "" if title is None else str(title)
        path, chosen = target("" if file is None else str(file),
                              heading.encode() + warp.tobytes() + x.tobytes() + repr(tol).encode(), self)
        try:
            write_chart(path, {"kind": "warp", "x": x.tolist(), "warp": warp.tolist(), "tolerance": tol,
                               "title": heading, "along": bool(lines)})
        except OSError as exc:
            raise NodeWarning(f"Could not write the chart to {path}: {exc.strerror or exc}") from None
        if chosen:
            self.remark(f"No File given: the chart was written to {path}")
        return str(path), over, x.tolist(), summary
