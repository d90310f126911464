"""Plot: a line graph of numbers, as a PNG image (like the thesis's warp-angle graphs)."""

from __future__ import annotations

import hashlib
import math
import os
import tempfile
from pathlib import Path
from typing import Any

import numpy as np

from engine.node import LIST, In, Node, NodeWarning, Out
from engine.types import NUMBER, TEXT
from nodes.io.common import FileFailure, may_write, replacing, writable, write_target

PLOT_FOLDER = Path(tempfile.gettempdir()) / "torsal" / "plots"
"""Where plots go when no File is given: one file per distinct plot, rewritten in place."""


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


def target(file: str, key: bytes, node: Node | None = None) -> tuple[Path, bool]:
    """The PNG path to write and whether it was chosen by the node (no File given).

    A File is a file the graph writes, so it follows the write rules
    (:mod:`engine.writes`): inside the graph's folder, never a ``.graph``, and only once
    the user allows the graph to write (``node`` asks; without consent it warns and the
    image goes to the temporary folder, so it can still be shown). Without a File the
    image goes to :data:`PLOT_FOLDER`, named for ``key`` (the bytes that make the plot).
    """
    temporary = PLOT_FOLDER / f"plot-{hashlib.sha1(key).hexdigest()[:12]}.png"
    name = file.strip()
    if not name:
        return temporary, True
    if not Path(name).suffix:
        name += ".png"
    if Path(name).suffix.lower() != ".png":
        raise NodeWarning(f"File must be a .png image, not {Path(name).name!r}")
    if node is None:
        raise NodeWarning("File: a plot is written to a file only by a node of a graph")
    path = write_target(node, name, "File")
    return (path, False) if may_write(node, [path]) else (temporary, False)


def draw(path: Path, y: np.ndarray, title: str) -> None:
    """Draw the line graph of ``y`` against its index into the PNG at ``path``.

    Uses matplotlib's Agg canvas directly (no pyplot, no window, no global state),
    so it works headless and from a solver thread. The file is written next to the
    target and renamed over it, so a viewer never reads half an image.
    """
    figure, axes = new_figure()
    x = np.arange(len(y))
    axes.plot(x, y, color="#d55e00", linewidth=1.5, marker="o" if len(y) <= 60 else None, markersize=3)
    axes.set_title(title)
    axes.set_xlabel("Index")
    axes.set_ylabel("Value")
    axes.grid(True, alpha=0.3)
    save(figure, path)


def new_figure() -> tuple[Any, Any]:
    """A figure on matplotlib's Agg canvas (no pyplot, no window, no global state: safe
    headless and on the solver's worker thread) and its one axes."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    figure = Figure(figsize=(6.4, 4.0), dpi=100)
    FigureCanvasAgg(figure)
    return figure, figure.add_subplot()


def save(figure: Any, path: Path) -> None:
    """Write ``figure`` as a PNG at ``path``: next to it first, then renamed over it, so
    a viewer never reads half an image."""
    figure.tight_layout()
    if PLOT_FOLDER not in path.parents:  # the user's own file: atomic, keeping a .bak
        writable(path)
        replacing(path, lambda temporary: figure.savefig(temporary, format="png"))
        return
    path.parent.mkdir(parents=True, exist_ok=True)
    partial = path.with_name(f".{path.stem}.{os.getpid()}.partial.png")
    try:
        figure.savefig(partial, format="png")
        os.replace(partial, path)
    finally:
        partial.unlink(missing_ok=True)


class Plot(Node):
    """Draw numbers as a line graph, such as the warp angle of every panel along a surface.

    Each value is plotted against its position in the list (0, 1, 2 …); values
    that are not finite numbers leave gaps. The graph is written as a PNG image to
    File, or, when File is empty, to a folder for temporary files (the node says
    where). The app shows the image; Summary gives the smallest, largest and mean
    value in words.
    """

    type_id = "display.Plot"
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
            draw(path, y, heading)
        except OSError as exc:
            raise NodeWarning(f"Could not write the plot to {path}: {exc.strerror or exc}") from None
        except FileFailure as exc:
            raise NodeWarning(f"Could not write the plot to {path}: {exc}") from None
        if chosen:
            self.remark(f"No File given: the plot was written to {path}")
        return str(path), summary(y)
