"""Long kernels report fractional progress (Node.progress) and stop on the node's token:
SurfaceAnalysis's grids, SplineApproximation's optimisation, the development map's search.
(The area cubature's: tests/nodes/geometry/test_area_knot_grid.py.)"""

from __future__ import annotations

import numpy as np
import pytest

from tests.nodes.developable.test_spline_approximation import twisted_strip
from tests.nodes.geometry.test_development_locate import helix_tangent
from torsal.engine.node import Cancelled
from torsal.nodes.analysis.surface_analysis import SurfaceAnalysis, _curvature
from torsal.nodes.geometry.approximation import approximate, station_rulings
from torsal.nodes.geometry.parametric_surface import torus
from torsal.nodes.geometry.unroll import unroll_rulings
from torsal.nodes.geometry.watch import watched


def analyse(node: SurfaceAnalysis, density: int) -> tuple:
    return node.solve(torus(2.0, 0.5), density, density, 1.0, 0.01, 0.01)


def test_surface_analysis_progress_rises_to_one():
    node, heard = SurfaceAnalysis(), []
    node.on_progress = heard.append
    analyse(node, 20)
    assert len(heard) >= 3 and heard == sorted(heard) and heard[-1] == 1.0


def test_surface_analysis_stops_when_its_token_is_cancelled():
    node = SurfaceAnalysis()
    node.token.cancel()
    with pytest.raises(Cancelled):
        analyse(node, 20)


def test_chunked_curvature_equals_one_call():
    surface = torus(2.0, 0.5)
    u, v = (a.ravel() for a in np.meshgrid(np.linspace(0, 1, 100), np.linspace(0, 1, 100)))
    whole, chunked = surface.curvature(u, v), _curvature(surface, u, v, lambda: None)
    np.testing.assert_array_equal(chunked.k1, whole.k1)
    np.testing.assert_array_equal(chunked.direction2, whole.direction2)


def test_optimisation_progress_rises_to_one():
    surface, edge = twisted_strip()
    heard: list[float] = []
    approximate(station_rulings(surface, edge, 20), None, True, progress=heard.append)
    assert len(heard) >= 3 and heard == sorted(heard) and heard[-1] == 1.0


def test_development_map_search_reports_progress_and_stops():
    starts, ends = helix_tangent(200, 2)
    m = unroll_rulings(starts, ends).map
    points = np.repeat(m.vertices3d, 10, axis=0) + 0.01
    heard: list[float] = []
    with watched(None, heard.append):
        m.to_2d(points)
    assert heard and heard == sorted(heard) and heard[-1] == 1.0

    def stop() -> None:
        raise Cancelled

    with watched(stop), pytest.raises(Cancelled):
        m.to_2d(points)
