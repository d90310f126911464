"""The charts nodes draw as PNG images (Plot, WarpChart, CurvatureHistogram): a figure on
matplotlib's Agg canvas, where its image goes and how it is written.

An image goes to the File a node is given, under the write rules of
:mod:`torsal.nodes.common.files`, or, with no File, to the user's private scratch folder
(:func:`plot_folder`: the user cache folder, mode 0700 — never a shared ``/tmp`` path),
named for what the chart shows; either way it goes through the one write path
(:mod:`torsal.engine.write_path`), so a viewer never reads half an image and no link is
ever followed.
"""

from __future__ import annotations

import hashlib
import io
from pathlib import Path
from typing import Any

from torsal.engine.node import Node, NodeWarning
from torsal.engine.write_path import scratch_folder, write_file
from torsal.nodes.common.files import may_write, replacing, writable, write_target


def plot_folder() -> Path:
    """Where plots go when no File is given (one file per distinct plot): ``plots`` in
    this user's private scratch folder."""
    return scratch_folder() / "plots"


def target(file: str, key: bytes, node: Node | None = None) -> tuple[Path, bool]:
    """The PNG path to write and whether it was chosen by the node (no File given).

    A File is a file the graph writes, so it follows the write rules
    (:mod:`torsal.engine.writes`): inside the graph's folder, never a ``.graph``, and only once
    the user allows the graph to write (``node`` asks; without consent it warns and the
    image goes to the temporary folder, so it can still be shown). Without a File the
    image goes to :func:`plot_folder`, named for ``key`` (the bytes that make the plot).
    """
    temporary = plot_folder() / f"plot-{hashlib.sha1(key).hexdigest()[:12]}.png"
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
    """Write ``figure`` as a PNG at ``path`` through the one write path, so a viewer never
    reads half an image: the user's own file keeps its original as ``.bak``; a plot in
    the scratch folder is simply replaced."""
    figure.tight_layout()
    image = io.BytesIO()
    figure.savefig(image, format="png")
    scratch = plot_folder()
    if scratch not in path.parents:  # the user's own file: atomic, keeping a .bak
        writable(path)
        replacing(path, image.getvalue())
        return
    write_file(path, image.getvalue(), base=scratch.parent, backup=False)
