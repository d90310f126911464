"""Curves that Rationalise's strips run on say where they may not be smooth themselves.

A lifted parameter line of a NURBS design reports the design's knots along it (it is only
as smooth as the design there); a chain of trimmed pieces reports its joins and each
piece's own breakpoints inside the part it runs over — so a writer or a sampler asks the
curve, not the curve's container. Expected values are the knots put in.
"""

from __future__ import annotations

import numpy as np

from torsal.nodes.geometry.curves.nurbs import NurbsCurve
from torsal.nodes.geometry.developable.chain import Chain
from torsal.nodes.geometry.developable.offset import Lift, LiftedIsoCurve
from torsal.nodes.geometry.nurbs_surface import NurbsSurface


def test_a_lifted_parameter_line_reports_the_design_knots_along_it():
    grid = np.stack(np.meshgrid(np.linspace(0, 6, 6), np.linspace(0, 4, 5), indexing="ij"), axis=-1)
    points = np.concatenate([grid, np.sin(grid[..., :1])], axis=-1)
    knots_u = [0, 0, 0, 0, 0.3, 0.7, 1, 1, 1, 1]
    knots_v = [0, 0, 0, 0, 0.5, 1, 1, 1, 1]
    design = NurbsSurface(points, 3, 3, knots_u, knots_v)
    along_u = LiftedIsoCurve(design, "u", 0.4, Lift(None))
    along_v = LiftedIsoCurve(design, "v", 0.4, Lift(None))
    np.testing.assert_array_equal(along_u._breakpoints(), [0.0, 0.3, 0.7, 1.0])
    np.testing.assert_array_equal(along_v._breakpoints(), [0.0, 0.5, 1.0])


def test_a_chain_reports_its_joins_and_its_pieces_breaks_inside_what_it_runs_over():
    points = np.array([[0, 0, 0], [1, 1, 0], [2, 0, 0], [3, 1, 0], [4, 0, 0], [5, 1, 0.0]])
    first = NurbsCurve(points, 3, knots=[0, 0, 0, 0, 0.05, 0.5, 1, 1, 1, 1])  # breaks 0.05, 0.5
    line = NurbsCurve(np.array([[5, 1, 0], [5, 5, 0.0]]), 1)
    # the first piece run from its parameter 0.1 to 0.9 (0.05 is outside), the line whole
    chain = Chain([(first, 0.1, 0.9), (line, 0.0, 1.0)])
    join = 0.8 / 1.8  # the pieces' shares by their parameter spans, 0.8 and 1
    np.testing.assert_allclose(chain._breakpoints(), [0.0, (0.5 - 0.1) / 0.8 * join, join, 1.0],
                               rtol=0, atol=1e-15)
