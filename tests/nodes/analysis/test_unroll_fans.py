"""IsoMapping's promise on strips with fans: both flat edges as long as the 3D edges to
1e-7 of the strip's size.

A RulingDevelopable strip with fans sweeps long stretches of one curve from single
points of the other, so its edges run fast over a few of its parameter's segments;
evenly spaced samples left those stretches coarse (edges 1.8e-5 … 4.7e-5 of the size
short, measured before the change). The 3D lengths here are the curves' arc lengths
over the strip's parameters, integrated independently (composite Gauss–Legendre of
|C'|, 400 panels of 20 points), never from the unrolling.
"""

from __future__ import annotations

import numpy as np
import pytest

from tests.nodes.developable.test_ruling_kinds import nappes
from tests.support import curve_pairs
from tests.support.node_helpers import out, run, tree
from torsal.nodes.analysis.iso_mapping import IsoMapping
from torsal.nodes.geometry.curve_rail import ruled_between
from torsal.nodes.geometry.developable import ruling_developable


def arc_length(curve, t0: float, t1: float, panels: int = 400) -> float:
    x, w = np.polynomial.legendre.leggauss(20)
    edges = np.linspace(t0, t1, panels + 1)
    half, mid = 0.5 * np.diff(edges), 0.5 * (edges[1:] + edges[:-1])
    t = (half[:, None] * x + mid[:, None]).ravel()
    speed = np.linalg.norm(curve.derivatives(t, 1)[1], axis=1).reshape(panels, 20)
    return float((half * (speed * w).sum(axis=1)).sum())


PAIRS = {"chorded": curve_pairs.chorded_pair, "nappes": nappes, "folded cone": curve_pairs.folded_cone_pair}


@pytest.mark.parametrize("pair", list(PAIRS))
def test_flat_edges_of_a_strip_with_fans_are_as_long_as_its_3d_edges_to_1e_7(pair):
    a, b = PAIRS[pair]()
    strip = ruling_developable(a, b, 60, 0.01)
    assert (~strip.stations).sum() >= 5  # fans: rulings added through single points (22, 57, 5)
    surface = ruled_between(a, strip.s, b, strip.t, points=(strip.starts, strip.ends))
    result = run(IsoMapping(), Surface=tree({(0,): [surface]}), Segments=100, Placement=1)
    development = out(result, "Map")[(0,)][0]
    flat = [np.linalg.norm(np.diff(edge, axis=0), axis=1).sum()
            for edge in (development.starts2d, development.ends2d)]
    exact = [arc_length(a, strip.s[0], strip.s[-1]), arc_length(b, strip.t[0], strip.t[-1])]
    size = np.linalg.norm(np.ptp(np.vstack([strip.starts, strip.ends]), axis=0))
    errors = np.abs(np.subtract(flat, exact)) / size
    assert errors.max() < 1e-7  # measured 4.9e-8 (chorded), 3.8e-8 (nappes), 4.8e-8 (folded cone)
    # the rulings the user sees are still the 101 asked for, laid flat at their lengths
    lines = out(result, "Rulings")[(0,)]
    assert len(lines) == 101
    requested = surface.rulings(101)
    lengths = np.linalg.norm(requested[:, 1] - requested[:, 0], axis=1)
    np.testing.assert_allclose([line.length for line in lines], lengths, rtol=0, atol=1e-12 * size)
