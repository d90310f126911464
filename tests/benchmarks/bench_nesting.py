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
example itself, run as shipped (Nesting = TrueShape): usage ≥ 72 %.
"""

from __future__ import annotations

import itertools
import json
import os
import resource
import subprocess
import sys
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
#: The issue's bar (31): true-shape nesting within this many times sparrow's own time to pack
#: the same parts at the same density in one strip of the sheet's height.
TIME_RATIO = 1.5
#: Longest a baseline strip packing is given to reach the density (s).
BASELINE_CAP = 300.0

#: The baseline: spyrrow in one call, free rotation (or the layout's turns), 10 mm
#: separation, a strip of the sheet's height, two threads; prints the seconds from the
#: start of the solve to its first packing at least as dense as asked (null: not by the cap).
BASELINE = """
import json, sys, threading, time, spyrrow, shapely
job = json.loads(sys.stdin.read())
area = sum(shapely.Polygon(s).area for s in job["shapes"])
items = [spyrrow.Item(str(i), [tuple(p) for p in s], demand=1, allowed_orientations=None)
         for i, s in enumerate(job["shapes"])]
instance = spyrrow.StripPackingInstance("baseline", job["height"], items)
config = spyrrow.StripPackingConfig(early_termination=False, total_computation_time=None,
    exploration_time=int(job["cap"]), compression_time=0, min_items_separation=job["spacing"],
    seed=0, num_workers=2)
progress = spyrrow.ProgressQueue()
solver = threading.Thread(target=lambda: instance.solve(config, progress=progress), daemon=True)
start = time.perf_counter()
solver.start()
while True:
    alive = solver.is_alive()
    for kind, solution in progress.drain():
        if kind in (spyrrow.ReportType.ExplFeas, spyrrow.ReportType.CmprFeas, spyrrow.ReportType.Final) \\
                and area / (solution.width * job["height"]) >= job["density"]:
            reached = area / (solution.width * job["height"])
            print(json.dumps([time.perf_counter() - start, reached]), flush=True)
            import os; os._exit(0)
    if not alive:
        print(json.dumps([None, 0.0]), flush=True)
        break
    time.sleep(0.01)
"""


def sparrow_seconds(files: list[Path], density: float, height: float = 1250.0,
                    spacing: float = 10.0) -> tuple[float, float]:
    """Seconds spyrrow takes, in one call, to pack the parts of ``files`` (their CUT contours,
    centred) into a strip ``height`` tall at ``density`` or more (inf when not within
    :data:`BASELINE_CAP`), from before its process starts, and its CPU seconds. The strip's
    density counts its length to the far separation, as the stock usage counts the last sheet
    to its parts' reach plus the margin."""
    shapes = []
    for file in files:
        for e in ezdxf.readfile(file).modelspace().query('LWPOLYLINE[layer=="CUT"]'):
            ring = np.array([(x, y) for x, y, *_ in e.get_points()])
            shapes.append(np.round(ring - ring.mean(axis=0), 3).tolist())
    job = {"shapes": shapes, "height": height, "spacing": spacing + 0.02, "density": density,
           "cap": BASELINE_CAP}
    # timed as ours is: from before its process starts (ours starts sparrow's worker processes and
    # imports spyrrow in them on its clock too) to the packing; the process ends at once after it
    before, started = _children_cpu(), time.perf_counter()
    done = subprocess.run([sys.executable, "-c", BASELINE], input=json.dumps(job), capture_output=True,
                          text=True, timeout=BASELINE_CAP + 60, check=True)
    seconds, cpu = time.perf_counter() - started, _children_cpu() - before
    reached, _ = json.loads(done.stdout.strip().splitlines()[-1])
    return (float("inf"), cpu) if reached is None else (seconds, cpu)


def _children_cpu() -> float:
    """CPU seconds of this process's ended (and waited for) child processes so far."""
    used = resource.getrusage(resource.RUSAGE_CHILDREN)
    return used.ru_utime + used.ru_stime


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


def _lay_out(items, units, nesting, folder: Path, budget: float, found=None):  # type: ignore[no-untyped-def]
    from torsal.nodes.geometry import nesting as engine

    engine.PACKED.clear()  # packings cached by an earlier test of the same parts would be no search at all
    cpu = time.process_time() + _children_cpu()
    started = time.perf_counter()
    seen: list[tuple[float, float]] = []  # (seconds, stock usage) of each layout found on the way
    layout = cutfiles.lay_out(items, width=2500.0, height=1250.0, gap=10.0, units=units, nesting=nesting,
                              budget=budget, seed=0, text_height=0.0,
                              found=lambda on_the_way: seen.append((time.perf_counter() - started,
                                                                    on_the_way.stock_usage)))
    seconds = time.perf_counter() - started
    if found is not None:  # when the final layout was first shown (the search may go on without bettering it)
        found.append(next((t for t, usage in seen if usage >= layout.stock_usage), seconds))
        # and the CPU seconds of the whole nesting, sparrow's worker processes included (to its end:
        # more than to when the final layout was shown)
        found.append(time.process_time() + _children_cpu() - cpu)
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


#: Many parts long beside the sheet: the sheets are filled one at a time, and the first set of
#: random strips, chosen at 72 % of a sheet, pays for a packing that cannot fit before the target
#: follows the parts. One run at load 7-9: 68.1 % shown at 253.7 s (103.5 CPU-s) against sparrow's
#: 41.0 s (20.8 CPU-s) to the same density, ratio 6.19 (CPU 4.98); earlier 3.77 at load 11-17
#: (297.4 s against 78.9 s) and 36 before the target followed the parts. Profiled per packing
#: (budget 30, seed 0, load 9-11): sheet 1's set of 13 at 72 % fails after 252 steps, 29 CPU-s;
#: the set of 12 at the density it reached fits in 4.2; sheet 2's 17 (10.8 CPU-s, two threads)
#: beside the last sheet's 21 (33 CPU-s, one thread), which the final layout waits for.
SHEET_BY_SHEET = pytest.mark.xfail(strict=True, reason="issue 31 item 1 not reached for many parts long "
                                   "beside the sheet: see nesting.py and docs/cut-sheets.md")


#: Three runs at load 8-11 (both sides timed from before their processes start): the Kaohsiung
#: strips 72.5 %, ratio 0.45 / 0.56 / 0.48 (CPU 0.88 / 0.99 / 0.83): the set of 13 fits its sheet
#: in about 7 CPU-s (seed 0, two threads) beside the last sheet's 5 on one thread (5 CPU-s);
#: the panels 84.5 %, ratio 1.17 / 0.99 / 0.92 (CPU 1.18 / 0.84 / 1.08): sparrow's first packing
#: cut into sheets, as the baseline's first packing is already that dense.
@pytest.mark.parametrize("name", ["kaohsiung", "panels", pytest.param("random strips", marks=SHEET_BY_SHEET)])
def test_true_shape_nesting_takes_at_most_one_and_a_half_times_sparrows_own_strip_packing(name, tmp_path):
    """The issue's bar: time to the layout against spyrrow's time, in one call, to pack the same
    parts at the same density in one strip of the sheet's height (measured here, in this run,
    from the parts as the DXF files hold them). Both are times to a layout: the baseline's to
    sparrow's first packing that dense, ours to when the final layout was first shown (an
    anytime search shows each better layout as it finds it, and may search on without
    bettering it)."""
    items, units = {"kaohsiung": kaohsiung, "panels": panels, "random strips": random_strips}[name]()
    found: list[float] = []
    usage, sheets, seconds = _lay_out(items, units, cutfiles.TRUE_SHAPE, tmp_path, BUDGET[name], found)
    files = sorted(tmp_path.glob(f"{cutfiles.TRUE_SHAPE}*.dxf"))
    baseline, baseline_cpu = sparrow_seconds(files, usage)
    ratio = found[0] / baseline
    ROWS.append(f"{name:14s} true shape {usage:6.1%} on {sheets} sheets, shown at {found[0]:6.1f} s (ended "
                f"at {seconds:6.1f} s, {found[1]:6.1f} CPU-s) | sparrow alone to {usage:.1%} in one strip: "
                f"{baseline:6.1f} s ({baseline_cpu:6.1f} CPU-s) | ratio {ratio:.2f} (bar {TIME_RATIO}), CPU "
                f"{found[1] / baseline_cpu:.2f} | load {os.getloadavg()[0]:.1f}")
    print("\n" + "\n".join(ROWS))
    assert ratio <= TIME_RATIO
    if name == "kaohsiung":  # the bar holds at the usage a shop expects
        assert usage >= 0.72


def test_kaohsiung_cut_sheets_nested_true_shape_use_at_least_72_percent_with_seams_on_both_parts(tmp_path,
                                                                                                   capsys):
    """The issue's bar on the example itself: ``torsal run kaohsiung-cut-sheets.graph --export
    cut.Layout=roof.dxf --json`` as a user types it (the example ships Nesting = TrueShape with
    its own Seed and TimeBudget). Usage measured from the DXF files ``--json`` says were
    written."""
    import json

    from torsal.app.cli import main

    started = time.perf_counter()
    assert main(["run", str(EXAMPLES / "kaohsiung-cut-sheets.graph"),
                 "--export", f"cut.Layout={tmp_path / 'roof.dxf'}", "--json"]) == 0
    seconds = time.perf_counter() - started
    data = json.loads(capsys.readouterr().out)
    files = [Path(p) for p in data["exported"]]
    assert files and all(f.exists() for f in files)
    (layout,) = data["nodes"]["cut"]["outputs"]["Layout"]["{0}"]
    assert layout["nesting"] == cutfiles.TRUE_SHAPE
    usage, sheets = _usage_from_files(files, 2500.0, 1250.0)
    with capsys.disabled():
        print(f"\nkaohsiung-cut-sheets as shipped: {sheets} sheets, usage {usage:.1%} "
              f"(from the DXF files), run {seconds:.1f} s")
    assert usage >= 0.72  # and no two parts overlap (_usage_from_files checks with shapely)
    # every seam engraved on both its parts: the node says when an ID fits on neither side
    messages = " ".join(m["text"] for m in data["nodes"]["cut"].get("messages", []))
    assert "does not fit" not in messages and "seams" in messages
