"""True-shape nesting (sparrow) against shelf packing, side by side (``make bench``).

Run alone with::

    .venv/bin/python -m pytest tests/benchmarks/bench_nesting.py \\
        -o python_files='bench_*.py' -o norecursedirs='.*' -s

Three part sets, on 2500 × 1250 mm sheets, 10 mm gap and margin:

* the Kaohsiung strips (kaohsiung-cut-sheets.graph, 1:50), 18 long curved strips;
* the development-and-panels panels (110 running-bond panels, 1:1);
* 50 random developable strips: developed conical strips (annular sectors) of random
  radius, width and angle.

For each: sheets used, material usage (parts' area over the sheets' area, the last sheet
counted only up to where its parts reach, measured from the DXF files written), and the
time. Bars: true-shape nesting never needs more sheets, and its usage is at least
:data:`USAGE_RATIO` times the shelf packing's on each set; and the issue's bar on the
example itself, run as shipped but for ``--set cut.Nesting=TrueShape``: usage ≥ 70 %.
"""

from __future__ import annotations

import itertools
import time
from pathlib import Path

import ezdxf
import numpy as np
import pytest
import shapely

from torsal.nodes.geometry.curves import Polyline
from torsal.nodes.io.formats import cutfiles

EXAMPLES = Path(__file__).resolve().parents[2] / "torsal" / "resources" / "examples"
#: Seconds of true-shape nesting per part set (the Kaohsiung strips: the example graph's TimeBudget).
BUDGET = {"kaohsiung": 45.0, "panels": 20.0, "random strips": 30.0}
#: True-shape usage over shelf usage, at least, per set (the panels are mostly rectangles,
#: which shelf packing already packs well).
USAGE_RATIO = {"kaohsiung": 1.3, "panels": 1.0, "random strips": 1.1}
ROWS: list[str] = []


def _example_items(name: str, node: str, port: str) -> tuple[list, str]:
    from torsal.app.headless import run_file

    run = run_file(EXAMPLES / name)
    items = run.solver.result(node).outputs[port].all_items() if node in run.solver.results else []
    if not items:
        pytest.skip(f"{name} gives no {node}.{port} here ({run.solver.result(node).messages})")
    return items, run.graph.units


def kaohsiung():  # type: ignore[no-untyped-def]
    return _example_items("kaohsiung-cut-sheets.graph", "model", "Geometry")


def panels():  # type: ignore[no-untyped-def]
    return _example_items("development-and-panels.graph", "patching", "PanelsFlat")


def random_strips(count: int = 50, seed: int = 3):  # type: ignore[no-untyped-def]
    """Developed conical strips: the annular sector between radii r and r + w over angle a."""
    rng = np.random.default_rng(seed)
    strips = []
    for k in range(count):
        r, w = rng.uniform(0.3, 2.0), rng.uniform(0.05, 0.25)
        a = min(rng.uniform(0.3, 1.2) / r * 1.0, 2.0)  # arc length along the inner edge 0.3-1.2 m
        t = np.linspace(0.0, a, 40)
        inner = np.column_stack([r * np.cos(t), r * np.sin(t)])
        outer = np.column_stack([(r + w) * np.cos(t), (r + w) * np.sin(t)])[::-1]
        ring = np.vstack([inner, outer]) + np.array([5.0 * k, 0.0])
        strips.append(Polyline(np.column_stack([ring, np.zeros(len(ring))]), closed=True))
    return strips, "m"


def _usage_from_files(files: list[Path], width: float, height: float) -> tuple[float, int]:
    """Parts' area over the stock, the last sheet counted up to where its parts reach, read
    from the DXF files; also checks no two parts overlap and every outline is simple."""
    area, reach = 0.0, 0.0
    for index, file in enumerate(files):
        polygons = [shapely.Polygon([(x, y) for x, y, *_ in e.get_points()])
                    for e in ezdxf.readfile(file).modelspace().query('LWPOLYLINE[layer=="CUT"]')]
        assert all(p.is_valid and p.exterior.is_simple for p in polygons)
        assert not any(a.intersects(b) for a, b in itertools.combinations(polygons, 2))
        area += sum(p.area for p in polygons)
        if index == len(files) - 1:
            reach = max(p.bounds[2] for p in polygons)
    stock = (len(files) - 1) * width * height + reach * height
    return area / stock, len(files)


def _lay_out(items, units, nesting, folder: Path, budget: float):  # type: ignore[no-untyped-def]
    started = time.perf_counter()
    layout = cutfiles.lay_out(items, width=2500.0, height=1250.0, gap=10.0, units=units, nesting=nesting,
                              budget=budget, seed=0, text_height=0.0)
    seconds = time.perf_counter() - started
    files = cutfiles.write_cut_files(layout, folder / f"{nesting}.dxf")
    usage, sheets = _usage_from_files(files, 2500.0, 1250.0)
    return usage, sheets, seconds


@pytest.mark.parametrize("name", ["kaohsiung", "panels", "random strips"])
def test_true_shape_nesting_uses_no_more_sheets_and_more_of_them_than_shelf_packing(name, tmp_path):
    items, units = {"kaohsiung": kaohsiung, "panels": panels, "random strips": random_strips}[name]()
    shelf = _lay_out(items, units, cutfiles.SHELF, tmp_path, 1.0)
    true = _lay_out(items, units, cutfiles.TRUE_SHAPE, tmp_path, BUDGET[name])
    ROWS.append(f"{name:14s} {len(items):4d} parts | shelf: {shelf[1]} sheets, usage {shelf[0]:6.1%}, "
                f"{shelf[2]:6.2f} s | true shape: {true[1]} sheets, usage {true[0]:6.1%}, {true[2]:6.2f} s "
                f"(budget {BUDGET[name]:g} s) | usage ratio {true[0] / shelf[0]:.2f}")
    print("\n" + "\n".join(ROWS))
    assert true[1] <= shelf[1]
    assert true[0] >= USAGE_RATIO[name] * shelf[0]


def test_kaohsiung_cut_sheets_nested_true_shape_use_at_least_70_percent_of_the_stock(tmp_path, capsys):
    """The issue's bar on the example itself: ``torsal run kaohsiung-cut-sheets.graph --set
    cut.Nesting=TrueShape`` as a user types it, with the graph's own Seed and TimeBudget
    (the example ships with Nesting = Shelf, which ignores both: TrueShape at the budget
    that reaches the bar takes a minute or more, too slow to open the example in the app
    or to solve it in the test suite). Usage measured from the DXF files ``--json`` says
    were written."""
    import json

    from torsal.app.cli import main

    started = time.perf_counter()
    assert main(["run", str(EXAMPLES / "kaohsiung-cut-sheets.graph"), "--set", "cut.Nesting=TrueShape",
                 "--export", f"cut.Layout={tmp_path / 'roof.dxf'}", "--json"]) == 0
    seconds = time.perf_counter() - started
    data = json.loads(capsys.readouterr().out)
    files = [Path(p) for p in data["exported"]]
    assert files and all(f.exists() for f in files)
    (layout,) = data["nodes"]["cut"]["outputs"]["Layout"]["{0}"]
    assert layout["nesting"] == cutfiles.TRUE_SHAPE
    usage, sheets = _usage_from_files(files, 2500.0, 1250.0)
    with capsys.disabled():
        print(f"\nkaohsiung-cut-sheets, Nesting = TrueShape: {sheets} sheets, usage {usage:.1%} "
              f"(from the DXF files), run {seconds:.1f} s")
    assert usage >= 0.70
