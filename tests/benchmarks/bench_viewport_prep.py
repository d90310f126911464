"""The viewport's preparation of a Kaohsiung re-solve's preview (``make bench``).

Run alone with::

    .venv/bin/python -m pytest tests/benchmarks/bench_viewport_prep.py -s

While the 'Inward scale' slider is dragged, the solve worker prepares every re-solved
node's preview (points, triangles, normals, line cells) for the viewport: 28 strips,
their rulings and edge curves. Timed against the evaluations no preview can skip,
measured in the same run: each strip's derivatives on its 33 × 2 grid and again at its
degenerate points (where the normals are re-taken a step inwards), and each curve's 97
samples. What is left is making and merging the arrays.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from tests.benchmarks.timing import ratio_to_baseline
from torsal.app.gui.viewport.preview import prepare_solved
from torsal.app.headless import run_file
from torsal.nodes.common.preview import CURVE_SAMPLES, SURFACE_GRID
from torsal.nodes.geometry.curvature import DEGENERATE_RATIO
from torsal.nodes.geometry.surface_base import DEGENERATE_NUDGE, uv_grid
from torsal.nodes.geometry.vec_ops import cross, dot

EXAMPLE = Path(__file__).resolve().parents[2] / "torsal" / "resources" / "examples" / (
    "kaohsiung-stadium.graph"
)
#: Measured 1.53–1.59× (5.3–7.7 ms against 3.3–4.8 ms, load 1.5; the code before issue 16's
#: preview work: 3.4–3.6×, 11.5 ms).
BAR = 2.0


def test_kaohsiung_preview_preparation_within_2x_the_evaluations_it_cannot_skip():
    run = run_file(EXAMPLE)
    run.graph.set_setting("scale", "value", 0.70)
    report = run.solver.solve()
    results = run.solver.results
    strips = results["strip"].outputs["Surface"].all_items()
    outputs = (("edge_curves", "Curve"), ("inner", "Geometry"))
    curves = [curve for node, port in outputs for curve in results[node].outputs[port].all_items()]
    u, v = uv_grid(SURFACE_GRID, 2)
    nudged_u = u + np.where(u < 0.5, DEGENERATE_NUDGE, -DEGENERATE_NUDGE)
    nudged_v = v + np.where(v < 0.5, DEGENERATE_NUDGE, -DEGENERATE_NUDGE)
    samples = np.linspace(0.0, 1.0, CURVE_SAMPLES)

    def evaluations() -> None:
        for strip in strips:
            _, su, sv = strip.derivatives(u, v, 1)
            normal = cross(su, sv)
            bad = ~(np.sqrt(dot(normal, normal)) > DEGENERATE_RATIO * (dot(su, su) + dot(sv, sv)))
            if bad.any():
                strip.derivatives(nudged_u[bad], nudged_v[bad], 1)
        for curve in curves:
            curve.point_at(samples)

    def preparation() -> None:
        prepare_solved(run.graph, results, report.solved)

    ratio = ratio_to_baseline(
        f"Preview of a Kaohsiung re-solve ({len(strips)} strips, {len(curves)} curves)", preparation,
        "the strips' grid derivatives and the curves' samples", evaluations, 15,
    )
    assert set(prepare_solved(run.graph, results, report.solved)) >= {"strip", "edge_curves", "inner"}
    assert ratio <= BAR
