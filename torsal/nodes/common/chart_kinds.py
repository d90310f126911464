"""The kinds of chart the nodes draw, each from a *recipe*: a small dict of plain data.

A recipe is what a chart shows (its numbers, title and labels), not its pixels, so the
same chart can be drawn at any size: the node draws it at 640 × 400 into its PNG, and
the app draws it again at the size of the panel that shows it (the recipe travels in
the PNG, see :mod:`torsal.nodes.common.charts`). Each kind declares its fields; a recipe
read back from a file is checked against them (:func:`checked`) before anything is drawn.

- ``line`` (display.Plot): ``y`` against its index.
- ``warp`` (analysis.WarpChart): the warp angle of each ruling against ``x``, the tolerance
  dashed and the rulings over it marked.
- ``histogram`` (analysis.CurvatureHistogram): ``counts`` between bin ``edges``.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np

#: The most numbers a recipe's list may hold (a longer one is refused when read back).
MAX_VALUES = 1_000_000
#: The longest text a recipe may hold (titles, names).
MAX_TEXT = 1_000


def _literal(text: str) -> str:
    """``text`` shown as typed: a ``$`` is a dollar sign, not the start of matplotlib's maths."""
    return text.replace("$", r"\$")


def _line(axes: Any, r: dict[str, Any]) -> None:
    y = np.asarray(r["y"], dtype=float)
    x = np.arange(len(y))
    axes.plot(x, y, color="#d55e00", linewidth=1.5, marker="o" if len(y) <= 60 else None, markersize=3)
    axes.set_title(_literal(r["title"]))
    axes.set_xlabel("Index")
    axes.set_ylabel("Value")
    axes.grid(True, alpha=0.3)


def _warp(axes: Any, r: dict[str, Any]) -> None:
    x, warp, tolerance = np.asarray(r["x"], dtype=float), np.asarray(r["warp"], dtype=float), r["tolerance"]
    axes.plot(x, warp, color="#0072b2", linewidth=1.5, marker="o" if len(warp) <= 60 else None, markersize=3,
              label="warp angle")
    over = np.isfinite(warp) & (warp > tolerance)
    if over.any():
        axes.plot(x[over], warp[over], linestyle="none", marker="o", markersize=5, color="#d55e00",
                  label=f"over tolerance ({int(over.sum())})")
    axes.axhline(tolerance, color="#d55e00", linestyle="--", linewidth=1.0,
                 label=f"tolerance {tolerance:g} rad")
    axes.set_title(_literal(r["title"]))
    axes.set_xlabel("Distance along the strip" if r["along"] else "Ruling")
    axes.set_ylabel("Warp angle, rad")
    axes.set_ylim(bottom=0.0)
    axes.grid(True, alpha=0.3)
    axes.legend(loc="best")


def _histogram(axes: Any, r: dict[str, Any]) -> None:
    edges, counts = np.asarray(r["edges"], dtype=float), r["counts"]
    tolerance, name = r["tolerance"], r["name"]
    axes.bar(edges[:-1], counts, width=np.diff(edges), align="edge", color="#cc79a7", edgecolor="#5d2a4c",
             linewidth=0.6)
    if tolerance is not None and edges[0] <= tolerance <= edges[-1]:
        axes.axvline(tolerance, color="#0072b2", linestyle="--", linewidth=1.2,
                     label=f"tolerance {tolerance:g}")
        axes.legend(loc="upper right")
    axes.set_title(_literal(r["title"]))
    axes.set_xlabel(f"{name}, 1/unit" if name != "gaussian" else "gaussian, 1/unit²")
    axes.set_ylabel("Grid points")
    axes.grid(True, axis="y", alpha=0.3)


#: Each kind: its drawing function and its fields with their types ("numbers": a list of
#: numbers (NaN allowed), "count": a list of whole numbers, "number": a finite number,
#: "number?": one or None, "text", "flag").
KINDS: dict[str, tuple[Callable[[Any, dict[str, Any]], None], dict[str, str]]] = {
    "line": (_line, {"y": "numbers", "title": "text"}),
    "warp": (_warp, {"x": "numbers", "warp": "numbers", "tolerance": "number", "title": "text",
                     "along": "flag"}),
    "histogram": (_histogram, {"edges": "numbers", "counts": "counts", "tolerance": "number?",
                               "title": "text", "name": "text"}),
}


def draw(axes: Any, recipe: dict[str, Any]) -> None:
    """Draw ``recipe`` on matplotlib ``axes``."""
    KINDS[recipe["kind"]][0](axes, recipe)


def _field(kind: str, value: Any) -> bool:
    if kind in ("numbers", "counts"):
        if not isinstance(value, list) or len(value) > MAX_VALUES:
            return False
        if kind == "counts":
            return all(isinstance(v, int) and not isinstance(v, bool) and v >= 0 for v in value)
        return all(isinstance(v, int | float) and not isinstance(v, bool) for v in value)
    if kind == "number?" and value is None:
        return True
    if kind in ("number", "number?"):
        return isinstance(value, int | float) and not isinstance(value, bool) and math.isfinite(value)
    if kind == "text":
        return isinstance(value, str) and len(value) <= MAX_TEXT
    return isinstance(value, bool)  # "flag"


def checked(recipe: Any) -> dict[str, Any] | None:
    """``recipe`` if it is one of :data:`KINDS` with every field of the right type (and
    nothing else), else None: a recipe read from a file is data, checked before use."""
    if not isinstance(recipe, dict) or recipe.get("kind") not in KINDS:
        return None
    fields = KINDS[recipe["kind"]][1]
    if set(recipe) != {"kind", *fields}:
        return None
    if not all(_field(kind, recipe[name]) for name, kind in fields.items()):
        return None
    return recipe if _SHAPES[recipe["kind"]](recipe) else None


#: What each kind's lists must agree on (a line needs a value, bins one edge more than counts).
_SHAPES: dict[str, Callable[[dict[str, Any]], bool]] = {
    "line": lambda r: len(r["y"]) >= 1,
    "warp": lambda r: 1 <= len(r["x"]) == len(r["warp"]),
    "histogram": lambda r: len(r["edges"]) == len(r["counts"]) + 1 >= 2,
}
