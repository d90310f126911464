"""The charts nodes draw as PNG images (Plot, WarpChart, CurvatureHistogram): a figure on
matplotlib's Agg canvas, where its image goes and how it is written.

An image goes to the File a node is given, under the write rules of
:mod:`torsal.nodes.common.files`, or, with no File, to a temporary folder named for what the
chart shows; either way it is written beside its place and renamed over it, so a viewer
never reads half an image.
"""

from __future__ import annotations

import hashlib
import os
import tempfile
from pathlib import Path
from typing import Any

from torsal.engine.node import Node, NodeWarning
from torsal.nodes.common.files import may_write, replacing, writable, write_target

PLOT_FOLDER = Path(tempfile.gettempdir()) / "torsal" / "plots"
"""Where plots go when no File is given: one file per distinct plot, rewritten in place."""


def target(file: str, key: bytes, node: Node | None = None) -> tuple[Path, bool]:
    """The PNG path to write and whether it was chosen by the node (no File given).

    A File is a file the graph writes, so it follows the write rules
    (:mod:`torsal.engine.writes`): inside the graph's folder, never a ``.graph``, and only once
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
