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
import json
from pathlib import Path
from typing import Any

from torsal.engine.node import Node, NodeWarning
from torsal.engine.write_path import scratch_folder, write_file
from torsal.nodes.common.chart_kinds import checked, draw
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


#: The size a node draws its chart at, in pixels (at :data:`DPI`), for its PNG file.
FILE_SIZE = (640, 400)
DPI = 100
#: The PNG text chunk that carries a chart's recipe (JSON, ASCII), so the app can draw the
#: chart again at the size of the panel showing it. The pixels are the same without it.
RECIPE_KEY = "torsal-chart"
#: A recipe longer than this (a chart of very many values) is not carried: the app then
#: scales the PNG instead.
MAX_RECIPE_BYTES = 2_000_000


def new_figure(width: int = FILE_SIZE[0], height: int = FILE_SIZE[1], dpi: float = DPI) -> tuple[Any, Any]:
    """A figure of ``width`` × ``height`` pixels on matplotlib's Agg canvas (no pyplot, no
    window, no global state: safe headless and on the solver's worker thread) and its axes."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    figure = Figure(figsize=(width / dpi, height / dpi), dpi=dpi)
    FigureCanvasAgg(figure)
    return figure, figure.add_subplot()


def render(recipe: dict[str, Any], width: int = FILE_SIZE[0], height: int = FILE_SIZE[1],
           dpi: float = DPI) -> Any:
    """The figure of ``recipe`` (see :mod:`torsal.nodes.common.chart_kinds`) at ``width`` ×
    ``height`` pixels, laid out for that size: titles and labels keep their size in points
    (``dpi`` pixels an inch; a high-DPI screen draws at more pixels for the same layout)."""
    figure, axes = new_figure(width, height, dpi)
    draw(axes, recipe)
    figure.tight_layout()
    return figure


def write_chart(path: Path, recipe: dict[str, Any]) -> None:
    """Draw ``recipe`` at :data:`FILE_SIZE` and write it as the PNG at ``path`` (see :func:`save`),
    the recipe in its text chunk :data:`RECIPE_KEY`."""
    text = json.dumps(recipe, ensure_ascii=True, separators=(",", ":"))
    save(render(recipe), path, text if len(text) <= MAX_RECIPE_BYTES else None)


def read_recipe(text: str) -> dict[str, Any] | None:
    """The recipe in a PNG's :data:`RECIPE_KEY` text, checked (None when there is none or
    it is not a well-formed recipe: the text comes from a file, so it is only data)."""
    if not text or len(text) > MAX_RECIPE_BYTES:
        return None
    try:
        recipe = json.loads(text)
    except ValueError:
        return None
    return checked(recipe)


def save(figure: Any, path: Path, recipe: str | None = None) -> None:
    """Write ``figure`` as a PNG at ``path`` through the one write path, so a viewer never
    reads half an image: the user's own file keeps its original as ``.bak``; a plot in
    the scratch folder is simply replaced. ``recipe`` goes in its text chunk."""
    image = io.BytesIO()
    figure.savefig(image, format="png", metadata={RECIPE_KEY: recipe} if recipe else None)
    scratch = plot_folder()
    if scratch not in path.parents:  # the user's own file: atomic, keeping a .bak
        writable(path)
        replacing(path, image.getvalue())
        return
    write_file(path, image.getvalue(), base=scratch.parent, backup=False)
