"""RulingDevelopable's WarpAngles and Valid hold for the Surface it outputs, not only for
the solver's own numbers: the angle between the Surface's normals at the two ends of each
ruling (its tangent plane turning along the ruling), computed here from the Surface's
partial derivatives alone, is the WarpAngles output."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from tests.support import curve_pairs
from tests.support.node_helpers import run, tree
from torsal.app.headless import run_file
from torsal.nodes.developable.ruling_developable import RulingDevelopable

EXAMPLES = Path(__file__).resolve().parents[3] / "torsal" / "resources" / "examples"


def surface_warp(surface, u: np.ndarray) -> np.ndarray:
    """Angle between the normal vectors Su × Sv at v = 0 and v = 1 along the isocurves u."""
    ends = []
    for v in (0.0, 1.0):
        _, su, sv = surface.derivatives(u, np.full_like(u, v), 1)
        ends.append(np.cross(su, sv))
    n0, n1 = ends
    return np.arctan2(np.linalg.norm(np.cross(n0, n1), axis=1), np.einsum("ij,ij->i", n0, n1))


def check(result, minimum: int) -> None:
    surfaces = result.output("Surface").all_items()
    warps = [np.array(branch, dtype=float) for branch in result.output("WarpAngles").branches]
    valid = [np.array(branch, dtype=bool) for branch in result.output("Valid").branches]
    tolerance = 0.01
    checked = 0
    for surface, warp, ok in zip(surfaces, warps, valid, strict=True):
        u = surface.ruling_parameters
        measured = surface_warp(surface, u)
        defined = np.isfinite(measured) & np.isfinite(warp)
        # where a rail stands still (a fan's apex, a tip) the surface has no normal there
        _, su0, _ = surface.derivatives(u, np.zeros_like(u), 1)
        _, su1, _ = surface.derivatives(u, np.ones_like(u), 1)
        moving = (np.linalg.norm(su0, axis=1) > 1e-9) & (np.linalg.norm(su1, axis=1) > 1e-9)
        both = defined & moving
        assert np.abs(measured[both] - warp[both]).max() <= 1e-9
        assert (ok[both] == (measured[both] <= tolerance)).all()
        checked += int(both.sum())
    assert checked >= minimum


def test_the_kaohsiung_strips_own_tangent_planes_give_the_reported_warp():
    check(run_file(EXAMPLES / "kaohsiung-stadium.graph").solver.result("strip"), 250)  # 268 of 413


@pytest.mark.parametrize("name", sorted(curve_pairs.PAIRS))
def test_strips_cut_from_known_developables_have_the_reported_warp_on_their_surface(name):
    pair = curve_pairs.PAIRS[name]()
    curves = {"CurveA": tree({(0,): [pair.a]}), "CurveB": tree({(0,): [pair.b]})}
    result = run(RulingDevelopable(), **curves, Segments=40)
    check(result, 30)
