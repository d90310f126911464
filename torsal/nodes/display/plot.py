"""Plot: a line graph of numbers, as a PNG image (like the thesis's warp-angle graphs)."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from torsal.engine.node import LIST, In, Node, NodeWarning, Out
from torsal.engine.types import NUMBER, TEXT
from torsal.nodes.common.charts import target, write_chart
from torsal.nodes.common.files import FileFailure


def _values(values: list[Any]) -> np.ndarray:
    return np.array([math.nan if v is None else float(v) for v in values], dtype=float)


def summary(y: np.ndarray) -> str:
    """``min …, max …, mean …`` of the finite values, saying how many were left out."""
    finite = y[np.isfinite(y)]
    text = (
        f"min {finite.min():.6g}, max {finite.max():.6g}, mean {finite.mean():.6g} "
        f"over {len(finite)} value{'s' if len(finite) != 1 else ''}"
    )
    missing = len(y) - len(finite)
    if missing:
        text += f" ({missing} not finite, left out)"
    return text


class Plot(Node):
    """Draw numbers as a line graph, such as the warp angle of every panel along a surface.

    Each value is plotted against its position in the list (0, 1, 2 …); values
    that are not finite numbers leave gaps. The graph is written as a PNG image to
    File, or, when File is empty, to a folder for temporary files (the node says
    where). The app shows the image; Summary gives the smallest, largest and mean
    value in words.
    """

    type_id = "display.Plot"
    nickname, aliases = "Plot", ("Quick Graph", "graph", "chart")
    inputs = (
        In("Values", NUMBER, "V", "The numbers to plot, in order.", access=LIST),
        In("Title", TEXT, "T", "The graph's title.", default=""),
        In("File", TEXT, "F", "The .png to write, relative to the graph's folder (written only when you "
           "allow the graph to write files); empty for a temporary file.", default=""),
    )
    outputs = (
        Out("Image", TEXT, "I", "Path of the PNG image written."),
        Out("Summary", TEXT, "S", "The minimum, maximum and mean of the values."),
    )

    def solve(self, values: list[Any], title: Any, file: Any) -> tuple[str, str]:
        if not values:
            raise NodeWarning("Values is empty: there is nothing to plot")
        y = _values(values)
        if not np.isfinite(y).any():
            raise NodeWarning("None of the Values is a finite number: there is nothing to plot")
        if np.abs(y[np.isfinite(y)]).max() > 1e300:  # the axis' margins and ticks would overflow
            raise NodeWarning("Values reach beyond 1e+300: too large to draw an axis for")
        heading = "" if title is None else str(title)
        path, chosen = target("" if file is None else str(file), heading.encode() + y.tobytes(), self)
        try:
            write_chart(path, {"kind": "line", "y": y.tolist(), "title": heading})
        except OSError as exc:
            raise NodeWarning(f"Could not write the plot to {path}: {exc.strerror or exc}") from None
        except FileFailure as exc:
            raise NodeWarning(f"Could not write the plot to {path}: {exc}") from None
        if chosen:
            self.remark(f"No File given: the plot was written to {path}")
        return str(path), summary(y)
