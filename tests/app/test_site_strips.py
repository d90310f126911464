"""A strip between two curves, unrolled and summarised as ``torsal run --json`` does, at
site coordinates: the same outputs as at the origin, moved, and no stall.

Two pairs the examples do not hold (``tests/app/test_site_coordinates.py`` moves those):

- *rational*: random rational cubic NURBS (seeded) whose control points are moved: the
  kernel's curves move exactly on their data, so the strip must be the origin's, moved,
  to 1e-9 of the size plus the inputs' own rounding (as the examples' bound).
- *functions*: curves given as functions *of their world coordinates* (an expression
  with the site offset in it), differentiated by finite differences. Their derivatives
  are only known to the rounding of the points they are made of over the difference
  step (measured: 4.8e-8 of the derivative at 1e6 m, 2.3e-5 at 1e9 m), so the partners
  are only known to that: the bound here is that noise, measured, with a margin of 5.
  What must hold for them as for any curve is the time: before the integrals stopped at
  that noise, the strip's area took 84 s at 1e6 m (0.02 s at the origin), IsoMapping 83 s,
  a curve's length 50 s at 1e9 m (timed side by side in
  ``tests/benchmarks/bench_site_strips.py``; here a stall is caught by the timeout).
"""

from __future__ import annotations

import numpy as np
import pytest

from tests.support.node_helpers import out, run, tree
from torsal.nodes.analysis.iso_mapping import IsoMapping
from torsal.nodes.common.values import _curve_summary, _development_summary, _surface_summary
from torsal.nodes.developable.ruling_developable import RulingDevelopable
from torsal.nodes.geometry.curves import NurbsCurve, ParametricCurve

SITE = (1e6, 2e6, 300.0)
FAR = (1e9, 1e9, 1e9)

_RNG = np.random.default_rng(3)
_PA = np.cumsum(_RNG.uniform(0.5, 1.5, (7, 3)) * [1.0, 0.3, 0.3], axis=0)
_PB = _PA + np.array([0.0, 2.0, 0.5]) + _RNG.normal(0.0, 0.3, (7, 3))
_WA, _WB = _RNG.uniform(0.5, 2.0, 7), _RNG.uniform(0.5, 2.0, 7)


def pair(kind: str, offset) -> tuple:
    o = np.asarray(offset, dtype=float)
    if kind == "rational":
        return NurbsCurve(_PA + o, 3, weights=_WA), NurbsCurve(_PB + o, 3, weights=_WB)

    def a(u):
        return o[0] + 3 * np.cos(u), o[1] + 3 * np.sin(u), o[2] + 0.3 * np.sin(3 * u)

    def b(u):
        return o[0] + 5 * np.cos(u), o[1] + 5 * np.sin(u), o[2] + 2 + 0.5 * np.cos(2 * u)

    return ParametricCurve(a, (0.0, 2.5)), ParametricCurve(b, (0.0, 2.5))


def solved(kind: str, offset) -> dict:
    a, b = pair(kind, offset)
    strip = run(RulingDevelopable(), CurveA=tree({(0,): [a]}), CurveB=tree({(0,): [b]}), Segments=60)
    surface = out(strip, "Surface")[(0,)][0]
    iso = run(IsoMapping(), Surface=tree({(0,): [surface]}), Segments=100, Placement=1)
    rulings = out(strip, "Rulings")[(0,)]
    shift = np.asarray(offset, dtype=float)
    return {
        "ends": np.array([[r.start, r.end] for r in rulings]) - shift,
        "kind": out(strip, "Kind")[(0,)],
        "torsal": out(strip, "Torsal")[(0,)][0],
        "summary": _surface_summary(surface),
        "length": _curve_summary(a)["length"],
        "development": _development_summary(out(iso, "Map")[(0,)][0]),
        "flat": np.array([[line.start, line.end] for line in out(iso, "Rulings")[(0,)]]),
    }


_ORIGIN: dict[str, dict] = {}


def at_origin(kind: str) -> dict:
    if kind not in _ORIGIN:
        _ORIGIN[kind] = solved(kind, (0.0, 0.0, 0.0))
    return _ORIGIN[kind]


def bound(kind: str, offset, size: float) -> float:
    """1e-9 plus the inputs' rounding (as for the examples), or the functions' derivative
    noise (measured 2.3e-8 at 1e6 m and 1.5e-5 at 1e9 m, with a margin of 5)."""
    if kind == "functions":
        return 1.2e-7 if offset == SITE else 8e-5
    return 1e-9 + 32 * float(np.spacing(max(offset))) / size


@pytest.mark.timeout(60)
@pytest.mark.parametrize("offset", [SITE, FAR], ids=["1e6", "1e9"])
@pytest.mark.parametrize("kind", ["rational", "functions"])
def test_a_strip_at_site_coordinates_is_the_strip_at_the_origin_moved(kind, offset):
    origin, moved = at_origin(kind), solved(kind, offset)
    size = float(np.linalg.norm(np.ptp(origin["ends"].reshape(-1, 3), axis=0)))
    limit = bound(kind, offset, size)
    assert moved["kind"] == origin["kind"]
    assert moved["torsal"] == origin["torsal"]
    assert np.abs(moved["ends"] - origin["ends"]).max() <= limit * size
    assert abs(moved["summary"]["area"] / origin["summary"]["area"] - 1) <= limit
    lows = np.array(moved["summary"]["bbox"][0]) - np.asarray(offset)
    np.testing.assert_allclose(lows, origin["summary"]["bbox"][0], rtol=0, atol=limit * size)
    assert abs(moved["length"] - origin["length"]) <= limit * size
    for figure in ("area_3d", "area_2d"):
        assert abs(moved["development"][figure] / origin["development"][figure] - 1) <= limit
    assert np.abs(moved["flat"] - origin["flat"]).max() <= limit * size
