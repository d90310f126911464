"""analysis.CurvatureHistogram: how a surface's curvature is spread, as a bar chart."""

from __future__ import annotations

from typing import Any

import numpy as np

from torsal.engine.node import LIST, In, Node, NodeWarning, Out
from torsal.engine.types import GENERIC, INTEGER, NUMBER, TEXT
from torsal.nodes.common.charts import target, write_chart
from torsal.nodes.common.checks import finite, whole
from torsal.nodes.common.geometry_checks import surface_or_mesh
from torsal.nodes.geometry.array_types import FloatArray
from torsal.nodes.geometry.curvature import SurfaceCurvature
from torsal.nodes.geometry.mesh_surface import MeshSurface
from torsal.nodes.geometry.surface_base import Surface
from torsal.nodes.limits import MAX_DENSITY

#: What can be counted, and how it is computed from the principal curvatures.
MEASURES: dict[str, str] = {
    "min|k|": "min(|k1|, |k2|): 0 where the surface is single-curved (developable)",
    "max|k|": "max(|k1|, |k2|): how tightly the sheet is bent",
    "k1": "the larger principal curvature",
    "k2": "the smaller principal curvature",
    "gaussian": "Gaussian curvature k1·k2 (0 on a developable)",
    "mean": "mean curvature (k1 + k2)/2",
}
#: The most bars a histogram may have.
MAX_BINS = 1000
#: Values beyond this cannot be given an axis (its margins and ticks would overflow).
LARGEST = 1e300
#: Values spread over less than this share of their size (or of 1/diameter) count as one value.
CONSTANT = 1e-9


def measure(c: SurfaceCurvature, name: str) -> FloatArray:
    """The chosen measure (a key of :data:`MEASURES`) at every point."""
    k1, k2 = np.asarray(c.k1, dtype=float), np.asarray(c.k2, dtype=float)
    if name == "min|k|":
        return np.minimum(np.abs(k1), np.abs(k2))
    if name == "max|k|":
        return np.maximum(np.abs(k1), np.abs(k2))
    if name == "k1":
        return k1
    if name == "k2":
        return k2
    if name == "gaussian":
        return np.asarray(c.gaussian, dtype=float)
    return np.asarray(c.mean, dtype=float)


def grid(n: int, closed: bool) -> FloatArray:
    """n parameters over [0, 1]: both ends, or once round a closed direction."""
    return np.arange(n) / n if closed else np.linspace(0.0, 1.0, n)


def curvature_samples(target_: Surface | MeshSurface, nu: int, nv: int) -> tuple[SurfaceCurvature, float]:
    """Curvature on the nu × nv parameter grid of a surface (every vertex of a mesh), and
    the surface's diameter."""
    if isinstance(target_, MeshSurface):
        c = target_.curvature()
        vertices = np.asarray(target_.points, dtype=float)
    else:
        uu, vv = np.meshgrid(grid(nu, target_.closed_u), grid(nv, target_.closed_v), indexing="ij")
        c = target_.curvature(uu.ravel(), vv.ravel())
        vertices = np.asarray(target_.derivatives(uu.ravel(), vv.ravel(), 0)[0], dtype=float)
        vertices = vertices[np.isfinite(vertices).all(axis=1)]
    size = float(np.linalg.norm(np.ptp(vertices, axis=0))) if len(vertices) else 0.0
    return c, size


def bin_edges(values: FloatArray, bins: int, size: float) -> FloatArray:
    """``bins + 1`` even edges from the smallest to the largest value; values that are all
    the same (to rounding) get a range ±5 % around them with the value in the middle of
    bar ``bins // 2``, so rounding cannot split them between two bars."""
    low, high = float(values.min()), float(values.max())
    scale = max(abs(low), abs(high), 1.0 / size if size > 0 else 1.0)
    if high - low <= CONSTANT * scale:
        width = 0.1 * scale / bins
        low = 0.5 * (low + high) - (bins // 2 + 0.5) * width
        return low + width * np.arange(bins + 1)
    return np.linspace(low, high, bins + 1)


def histogram(values: FloatArray, edges: FloatArray) -> list[int]:
    """How many values fall in each bar ``[edges[i], edges[i+1])`` (the last bar closed)."""
    index = np.searchsorted(edges, values, side="right") - 1
    index = np.clip(index, 0, len(edges) - 2)  # the largest value belongs to the last bar
    return np.bincount(index, minlength=len(edges) - 1).astype(int).tolist()


class CurvatureHistogram(Node):
    """Draw how a surface's curvature is spread: a bar chart of how many grid points
    have each curvature.

    The curvature is measured on a UDensity × VDensity grid over the surface (every
    vertex of a mesh). Measure chooses what is counted: min|k| (the default) is 0
    where the surface is single-curved, so a developable surface puts every point
    in the first bar, and a bump of points away from 0 shows where it is
    double-curved; max|k| shows how tightly the sheet must be bent (compare it with
    the material's smallest bending radius); k1, k2, gaussian and mean are also
    offered. Tolerance (optional, 1/m) draws a line and counts the points below it.

    Curvature is in 1/model unit. Points where the surface has no curvature (a pole,
    an apex) are left out and counted in Summary. The chart is a PNG image written
    to File, or to a temporary folder when File is empty; the inspector shows it.
    """

    type_id = "analysis.CurvatureHistogram"
    nickname, aliases = "CrvHist", ("curvature graph", "histogram")
    inputs = (
        In("Surface", GENERIC, "S", "The surface, mesh or mesh surface to measure."),
        In("Measure", TEXT, "M",
           "What to count: " + "; ".join(f"{k} — {v}" for k, v in MEASURES.items()) + ".", default="min|k|"),
        In("UDensity", INTEGER, "U", "Grid points across u (2 or more).", default=24,
           min=2, max=MAX_DENSITY),
        In("VDensity", INTEGER, "V", "Grid points across v (2 or more).", default=24,
           min=2, max=MAX_DENSITY),
        In("Bins", INTEGER, "B", "How many bars.", default=20, min=1, max=MAX_BINS),
        In("Tolerance", NUMBER, "Tol", "Optional curvature (1/m) to mark with a line; Summary counts the "
           "points whose value is below it.", optional=True),
        In("Title", TEXT, "T", "The chart's title (empty: the measure's name).", default=""),
        In("File", TEXT, "F", "Path of the .png to write; empty for a temporary file.", default=""),
    )
    outputs = (
        Out("Image", TEXT, "I", "Path of the PNG image written."),
        Out("Counts", INTEGER, "C", "How many points fall in each bar, from the smallest values up.",
            access=LIST),
        Out("Edges", NUMBER, "E", "The bars' edges (one more than the bars).", access=LIST),
        Out("Values", NUMBER, "Va", "The measured value at every grid point, u-major (NaN where undefined).",
            access=LIST, preview=False),
        Out("Summary", TEXT, "Su", "Smallest, largest and mean value, and the count below Tolerance."),
    )

    def solve(self, surface: Any, measure_name: Any, u_density: Any, v_density: Any, bins: Any,
              tolerance: Any, title: Any, file: Any) -> tuple[Any, ...]:
        target_ = surface_or_mesh("Surface", surface, "curvature to count")
        name = str(measure_name or "min|k|").strip()
        if name not in MEASURES:
            raise NodeWarning(f"Measure must be one of {', '.join(MEASURES)}, not {name!r}")
        nu, nv = whole("UDensity", u_density), whole("VDensity", v_density)  # bounded on the ports
        n_bins = whole("Bins", bins)
        tol = None if tolerance is None else finite("Tolerance", tolerance)
        curvature, size = curvature_samples(target_, nu, nv)
        values = measure(curvature, name)
        finite_values = values[np.isfinite(values)]
        if len(finite_values) == 0:
            raise NodeWarning("The surface has no curvature at any grid point (it is degenerate): "
                              "there is nothing to count")
        if np.abs(finite_values).max() > LARGEST:
            raise NodeWarning(f"The curvature reaches {np.abs(finite_values).max():.3g}: too large to draw "
                              "an axis for (the surface is degenerate somewhere)")
        edges = bin_edges(finite_values, n_bins, size)
        counts = histogram(finite_values, edges)
        summary = (f"{name}: min {finite_values.min():.6g}, max {finite_values.max():.6g}, "
                   f"mean {finite_values.mean():.6g} over {len(finite_values)} points")
        missing = len(values) - len(finite_values)
        if missing:
            summary += f" ({missing} without curvature, left out)"
            self.warn(f"{missing} of {len(values)} grid points have no curvature (a pole or apex): "
                      "they are left out of the chart")
        if tol is not None:
            below = int(np.count_nonzero(finite_values < tol))
            summary += f"; {below} of {len(finite_values)} below {tol:g}"
        heading = str(title).strip() if title else f"Curvature: {name}"
        key = heading.encode() + name.encode() + edges.tobytes() + np.asarray(counts).tobytes()
        path, chosen = target("" if file is None else str(file), key + repr(tol).encode(), self)
        try:
            write_chart(path, {"kind": "histogram", "edges": edges.tolist(),
                               "counts": [int(c) for c in counts], "tolerance": tol, "title": heading,
                               "name": name})
        except OSError as exc:
            raise NodeWarning(f"Could not write the chart to {path}: {exc.strerror or exc}") from None
        if chosen:
            self.remark(f"No File given: the chart was written to {path}")
        return str(path), counts, edges.tolist(), values.tolist(), summary
