"""analysis.CurvatureHistogram and analysis.WarpChart against closed forms."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from tests.support.node_helpers import allowed, out, run, texts, tree
from torsal.nodes.analysis.curvature_histogram import CurvatureHistogram
from torsal.nodes.analysis.warp_chart import WarpChart
from torsal.nodes.geometry.curves.line import Line
from torsal.nodes.surfaces.primitives import Cylinder

PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"
RADIUS = 2.0
NU, NV = 12, 5


def cylinder():
    (surface,) = out(run(Cylinder(), Radius=RADIUS, Height=3.0), "Cylinder")[(0,)]
    return tree({(0,): [surface]})


def histogram(tmp_path: Path, **inputs):
    return run(CurvatureHistogram(), Surface=cylinder(), UDensity=NU, VDensity=NV,
               File="histogram.png", writes=allowed(tmp_path), **inputs)


def only_bar(counts: list[int]) -> int:
    (index,) = np.flatnonzero(counts)
    return int(index)


def test_cylinder_puts_every_point_in_the_bar_of_one_over_its_radius(tmp_path):
    result = histogram(tmp_path, Measure="max|k|", Bins=10)
    counts, edges = out(result, "Counts")[(0,)], out(result, "Edges")[(0,)]
    assert result.state == "ok"
    assert len(counts) == 10 and len(edges) == 11
    bar = only_bar(counts)
    assert counts[bar] == NU * NV
    assert edges[bar] < 1 / RADIUS < edges[bar + 1]


def test_cylinder_is_single_curved_everywhere_so_min_k_is_all_in_the_zero_bar(tmp_path):
    result = histogram(tmp_path, Bins=8, Tolerance=0.01)
    counts, edges = out(result, "Counts")[(0,)], out(result, "Edges")[(0,)]
    bar = only_bar(counts)
    assert counts[bar] == NU * NV
    assert edges[bar] < 0 < edges[bar + 1]
    assert out(result, "Summary")[(0,)][0].endswith(f"; {NU * NV} of {NU * NV} below 0.01")


def test_cylinder_has_zero_gaussian_curvature_at_every_grid_point(tmp_path):
    result = histogram(tmp_path, Measure="gaussian", Bins=5)
    counts, edges = out(result, "Counts")[(0,)], out(result, "Edges")[(0,)]
    bar = only_bar(counts)
    assert counts[bar] == NU * NV
    assert edges[bar] < 0 < edges[bar + 1]


def test_histogram_writes_a_png(tmp_path):
    result = histogram(tmp_path)
    (path,) = out(result, "Image")[(0,)]
    assert Path(path).read_bytes()[:8] == PNG_SIGNATURE


def test_histogram_names_an_unknown_measure(tmp_path):
    result = histogram(tmp_path, Measure="twist")
    assert result.state == "warning"
    assert texts(result)[0].startswith("Measure must be one of min|k|, max|k|")


# -- warp along a hyperbolic paraboloid z = x·y -------------------------------------
# Rulings at x = t from (t, −L, −tL) to (t, L, tL); the normal (−y, −t, 1) turns along
# one by 2·atan(L / √(1 + t²)).
HALF = 1.0
T = np.linspace(0.0, 2.0, 9)


def hypar_rulings() -> list[Line]:
    return [Line((t, -HALF, -t * HALF), (t, HALF, t * HALF)) for t in T]


def hypar_warp() -> list[float]:
    return [2 * math.atan(HALF / math.sqrt(1 + t * t)) for t in T]


def test_warp_chart_counts_the_hypar_rulings_over_the_tolerance(tmp_path):
    tolerance = 1.2
    # 2·atan(L/√(1+t²)) > tol  ⇔  t < √((L / tan(tol/2))² − 1)
    limit = math.sqrt((HALF / math.tan(tolerance / 2)) ** 2 - 1)
    expected = int(np.count_nonzero(limit > T))
    result = run(WarpChart(), WarpAngles=hypar_warp(), Rulings=hypar_rulings(), Tolerance=tolerance,
                 File="warp.png", writes=allowed(tmp_path))
    assert result.state == "ok"
    assert expected == 5
    assert out(result, "Over") == {(0,): [expected]}


def test_warp_chart_places_the_hypar_rulings_along_the_strip(tmp_path):
    # the rulings' midpoints are (t, 0, 0): each is t − t0 along the strip
    result = run(WarpChart(), WarpAngles=hypar_warp(), Rulings=hypar_rulings(), File="w.png",
                 writes=allowed(tmp_path))
    assert np.allclose(out(result, "Positions")[(0,)], T - T[0], rtol=0, atol=1e-15)


def test_warp_chart_leaves_an_undefined_warp_out_and_says_so(tmp_path):
    warp = hypar_warp()
    warp[3] = float("nan")
    result = run(WarpChart(), WarpAngles=warp, Tolerance=0.5, File="w.png", writes=allowed(tmp_path))
    assert out(result, "Over") == {(0,): [8]}
    assert out(result, "Summary")[(0,)][0].endswith("(1 undefined, left out)")


def test_warp_chart_says_when_rulings_and_warps_do_not_pair_up(tmp_path):
    result = run(WarpChart(), WarpAngles=hypar_warp()[:4], Rulings=hypar_rulings(),
                 File="w.png", writes=allowed(tmp_path))
    assert result.state == "warning"
    assert texts(result) == ["Rulings has 9 lines but WarpAngles 4 values: wire the same node's Rulings and "
                             "WarpAngles"]
