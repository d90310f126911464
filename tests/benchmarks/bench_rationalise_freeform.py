"""developable.Rationalise on the freeform designs of ``tests/support/freeform_designs.py``
and the Kaohsiung roof, at 1, 2 and 5 cm (``make bench``).

Run alone with::

    .venv/bin/python -m pytest tests/benchmarks/bench_rationalise_freeform.py \\
        -o python_files='bench_*.py' -o norecursedirs='.*' -s

For every design and tolerance it prints the row of the table in the issue's note: strips,
the certified deviation and an independent one (the designs' own Newton on dense samples
of every strip), torsal, fan and crease rulings (Kind: the fan rulings across which the
sheet folds by more than 1e-7 rad are creases), the fan and creased shares of the area,
the solve's time and the isocurve baseline of ``bench_rationalise`` (evenly spaced
parameter lines, as many as it takes). It asserts what the issue asks that holds on every
design: within the tolerance by the independent measure, never more strips than the
baseline, a solve of at most 60 CPU-s on this 2-core machine, at most 10 % of the strips'
area in fans and every fan flat (no crease). The double bump (every line x = const crosses
an asymptotic direction at y = ±3, where f_yy changes sign and f_xy does not vanish, and
so does every line y = const near the bumps' inflection circles: no family of parameter
lines avoids it) is rationalised with strips that ring its bumps along lines of curvature
at 1, 2 and 5 cm, within the tolerance, covering the edge and ≤ 10 % in fans, each solve
within 60 CPU-s (52, 41 and 27 CPU-s at 1, 2 and 5 cm, load 4–10); it does not yet meet
the strip count at 2 and 5 cm (30 and 16 against the baseline's 26 and 14; see
docs/geometry.md, why), and its halves' triangles crease (at 5 cm 36 of its 430 rulings,
6e-4–0.12 rad). Where the rings are kept, their solves' CPU is also asserted against the
isocurve baseline's searches in the same run (:data:`RINGS_RATIO`).
"""

from __future__ import annotations

import time

import numpy as np
import pytest

from tests.benchmarks.bench_rationalise import even_strips
from tests.nodes.developable.test_rationalise import distance_to_surface, kaohsiung_roof
from tests.support import strip_readback
from tests.support.freeform_designs import DESIGNS
from torsal.nodes.geometry.developable.freeform import rationalise_freeform
from torsal.nodes.geometry.developable.kinds import fan_kinds
from torsal.nodes.geometry.developable.rationalise import creased_area, fan_area

TOLERANCES = (0.01, 0.02, 0.05)
#: The issue's bar for one solve on this machine, s.
SOLVE_LIMIT = 60.0
#: Where the ring layout is kept (the double bump), its three solves' CPU against the
#: isocurve baseline's three searches (``even_strips``, run beside them), at most: measured
#: 2.38 (120.5 against 50.7 CPU-s at load 4-10, trials judged by estimates before cuts);
#: 3.4 before that (166 against 49.5 CPU-s at load 6-12), about 6 before the march's search
#: and rings were made faster.
RINGS_RATIO = 4.0
#: The issue's bar for the strips' area in fans (flat triangles and end cones), a share.
FAN_LIMIT = 0.10


def _independent(name: str, surface, strips) -> float:
    u, v = np.meshgrid(np.linspace(0, 1, 201), np.linspace(0, 1, 17), indexing="ij")
    worst = 0.0
    for strip in strips:
        points = strip.surface.point_at(u.ravel(), v.ravel())
        d = DESIGNS[name].distance(points) if name in DESIGNS else distance_to_surface(surface, points)
        worst = max(worst, float(d.max()))
    return worst


CASES = [*DESIGNS, "kaohsiung"]

#: The tolerance whose strips are exported to a .3dm and read back (item 3 of the issue).
EXPORTED = 0.05


def _exported(strips, folder) -> dict[str, bool]:
    """The strips written to a .3dm and read back with rhino3dm (tests/support/strip_readback):
    item 3 of the issue on every strip (ruled faces degree 1 across, edges within 1e-6 of
    the size of the strips' rails, normals 1 % in from each end of 400 isocurves across
    every face within 1e-6 rad, fans flat to 1e-7 rad, faces joined within 1e-9 of the size)
    asserted; the node's torsal rulings' warp on the faces (the Valid bar, < 1e-7 rad) and
    the file's share of the one-surface form (the bar: 20 %) printed. Measured at 5 cm: item
    3 holds on every strip of every design; the warp is below 1e-7 on all but the double
    bump (3 of its 374 rulings, 2.3e-5 rad at most, where a cut strip's edge sweeps round a
    fan just past a ruling: since the export's triple knots at the cut pace's ramps, none of
    its 370, 6.3e-8 rad at most); the file is within 20 % but on Kaohsiung (20.3 %) and the
    double bump (44.5 %, now 47.4 %)."""
    surfaces = [s.surface for s in strips]
    kinds = [kind for s in strips for kind in np.where(s.result.fan, "fan", "torsal").tolist()]
    back = strip_readback.exported(surfaces, kinds, folder)
    share, warps, rows, worst = back.share, back.warps, back.rows, back.worst
    print(f"  exported: {100 * share:.1f} % of the one-surface form; warp at {len(warps)} torsal rulings "
          f"{max(warps.values(), default=0.0):.2g} rad ({sum(w >= 1e-7 for w in warps.values())} over 1e-7); "
          f"item 3: {worst}", flush=True)
    return {"exported faces ruled, degree 1 across": all(row["ruled"] == 1.0 for row in rows),
            "exported rails within 1e-6 of the size": worst["rails"] <= 1e-6,
            "exported normals agree to 1e-6 rad": worst["twist"] <= 1e-6,
            "exported fans flat": worst["fans"] <= 1e-7,
            "exported faces joined": worst["joins"] <= 1e-9}


@pytest.mark.timeout(2400)  # the double bump: three ring layouts and their baselines, ~10 min at load 9
@pytest.mark.parametrize("name", CASES)
def test_freeform_designs_within_tolerance_and_no_more_strips_than_isocurves(name, tmp_path):
    surface = DESIGNS[name].surface() if name in DESIGNS else kaohsiung_roof()
    unit = DESIGNS[name].unit if name in DESIGNS else 1.0
    rows: list[str] = []
    failed: list[str] = []
    rings_cpu: list[tuple[float, float]] = []  # the ring layout's solves and the baseline's searches
    for tolerance in TOLERANCES:
        tol = tolerance * unit
        start, cpu = time.perf_counter(), time.process_time()
        result = rationalise_freeform(surface, tol, 64, min_width=0.2 * unit)
        seconds, cpu = time.perf_counter() - start, time.process_time() - cpu
        base_cpu = time.process_time()
        baseline = even_strips(surface, tol, limit=128)
        base_cpu = time.process_time() - base_cpu
        if result.family == "rings":
            rings_cpu.append((cpu, base_cpu))
        fans = sum(int(s.result.fan.sum()) for s in result.strips)
        rulings = sum(len(s.result.fan) for s in result.strips)
        creases = sum(int(fan_kinds(s.surface.curve_a, s.surface.curve_b, s.surface.ruling_parameters,
                                    s.result.starts, s.result.ends, s.result.fan, 1e-7).crease.sum())
                      for s in result.strips)
        independent = _independent(name, surface, result.strips)
        rows.append(
            f"| {name} | {100 * tolerance:g} cm | {len(result.strips)} ({result.family}) | "
            f"{result.deviation / unit * 100:.3f} cm | {independent / unit * 100:.3f} cm | "
            f"{result.coverage / unit * 100:.3f} cm | {rulings - fans} / {fans - creases} / {creases} | "
            f"{fan_area(result.strips):.3f} | {creased_area(result.strips):.3f} | "
            f"{seconds:.1f} s ({cpu:.1f} CPU-s) | {baseline} ({base_cpu:.1f} CPU-s to find) |"
        )
        print(rows[-1], flush=True)
        checks = {"independent deviation within the tolerance": independent <= tol * 1.0001,
                  "the certified deviation bounds the independent one": independent <= result.deviation,
                  "certified within and covered": result.within and result.covered,
                  "no more strips than the baseline": len(result.strips) <= baseline,
                  f"solve within {SOLVE_LIMIT:g} CPU-s": cpu <= SOLVE_LIMIT,
                  f"fan area within {FAN_LIMIT:g} of the strips'": fan_area(result.strips) <= FAN_LIMIT,
                  "every fan flat (no crease)": creases == 0}
        if tolerance == EXPORTED:
            checks.update(_exported(result.strips, tmp_path))
        failed += [f"{100 * tolerance:g} cm: {what}" for what, ok in checks.items() if not ok]
    if rings_cpu:  # the rings' solves against the isocurve baseline's searches, same run
        ratio = sum(c for c, _ in rings_cpu) / max(sum(b for _, b in rings_cpu), 1e-9)
        print(f"  ring layout: {ratio:.2f} times the baseline's CPU", flush=True)
        if ratio > RINGS_RATIO:
            failed.append(f"ring layout {ratio:.2f} times the baseline's CPU (at most {RINGS_RATIO:g})")
    # every tolerance is solved and printed before the checks fail, so the table is whole
    assert not failed, failed
