"""The double bump drawn in millimetres in Rhino (tests/fixtures/double-bump-mm.3dm, written by
tests/support/double_bump_3dm.py) comes in as the closed-form design: in millimetres as
drawn, or converted to metres. Expected values: the closed form of
tests/support/freeform_designs.py and rhino3dm's own reading of the file. (Rationalise on
it, against the closed form in metres: tests/benchmarks/bench_ring_layout.py.)"""

from __future__ import annotations

import numpy as np
import rhino3dm as rh

from tests.support import double_bump_3dm
from tests.support.freeform_designs import DESIGNS, MM
from tests.support.node_helpers import run, texts
from torsal.nodes.io.rhino import Import3dm

DESIGN = DESIGNS["bumps"]


def _net(path):
    (obj,) = rh.File3dm.Read(str(path)).Objects
    s = obj.Geometry
    points = [[s.Points[(i, j)].X, s.Points[(i, j)].Y, s.Points[(i, j)].Z]
              for i in range(s.Points.CountU) for j in range(s.Points.CountV)]
    return np.array(points), np.array(list(s.KnotsU)), np.array(list(s.KnotsV))


def test_the_fixture_is_what_its_script_writes(tmp_path):
    model = rh.File3dm.Read(str(double_bump_3dm.FIXTURE))
    assert model.Settings.ModelUnitSystem == rh.UnitSystem.Millimeters
    for ours, again in zip(_net(double_bump_3dm.FIXTURE), _net(double_bump_3dm.build(tmp_path / "again.3dm")),
                           strict=True):
        np.testing.assert_array_equal(ours, again)


def _imported(units: str):
    result = run(Import3dm(), Path=str(double_bump_3dm.FIXTURE), Units=units)
    (surface,) = result.outputs["Surfaces"].all_items()
    return result, surface


def _off_the_closed_form(surface, unit: float) -> float:
    """Largest height difference from the closed form at 4,000 random points of the surface
    (the surface's x and y read off its points, in metres)."""
    rng = np.random.default_rng(7)
    points = surface.point_at(rng.random(4000), rng.random(4000)) / unit
    return float(np.abs(points[:, 2] - DESIGN.height(points[:, 0], points[:, 1])).max())


def test_in_millimetres_it_is_the_closed_form_times_1000():
    result, surface = _imported("mm")
    assert result.outputs["FileUnits"].all_items() == ["mm"]
    assert not any("Converted" in t for t in texts(result))
    corners = surface.point_at(np.array([0.0, 1.0, 0.0, 1.0]), np.array([0.0, 0.0, 1.0, 1.0]))
    np.testing.assert_allclose(corners[:, :2], MM * np.array([[-9, -6], [9, -6], [-9, 6], [9, 6]]),
                               atol=1e-9 * MM)
    assert _off_the_closed_form(surface, MM) <= double_bump_3dm.FIT  # measured 2.6e-5 m


def test_converted_to_metres_it_is_the_closed_form():
    result, surface = _imported("m")
    assert any("Converted from mm to m" in t for t in texts(result))
    u, v = np.meshgrid(np.linspace(0, 1, 9), np.linspace(0, 1, 7), indexing="ij")
    points = surface.point_at(u.ravel(), v.ravel())
    # x and y are the surface's parameters scaled: as the closed form's, so its strips can be compared
    np.testing.assert_allclose(points[:, 0], -9 + 18 * u.ravel(), atol=1e-9)
    np.testing.assert_allclose(points[:, 1], -6 + 12 * v.ravel(), atol=1e-9)
    assert _off_the_closed_form(surface, 1.0) <= double_bump_3dm.FIT
