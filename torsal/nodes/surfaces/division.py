"""Dividing a surface: a grid of points over its (u, v) square, as Grasshopper's Divide Surface."""

from __future__ import annotations

from typing import Any

import numpy as np

from torsal.engine.datatree import DataTree
from torsal.engine.node import TREE, In, Node, NodeWarning, Out
from torsal.engine.types import INTEGER, POINT, VECTOR
from torsal.nodes.common.checks import count
from torsal.nodes.common.convert import points, vectors
from torsal.nodes.common.geometry_checks import parametric_surface
from torsal.nodes.common.values import SURFACE
from torsal.nodes.limits import MAX_DIVISIONS


class DivideSurface(Node):
    """A grid of points on a surface: U + 1 rows of V + 1 points, evenly spaced in (u, v).

    Row i holds the points at u = i / U, from v = 0 to v = 1, in branch {…;i} (a surface
    in a branch of several gets {…;k;i}, k its place in the branch). Points are even in
    the surface's parameters, not in distance on it: a surface parameterised unevenly
    (a loft through uneven curves) gives an uneven grid. Normals and the (u, v) of each
    point (x is u, y is v) come in the same tree.
    """

    type_id = "surfaces.DivideSurface"
    nickname, aliases = "SDivide", ("Divide Surface", "surface grid", "points on surface", "grid points")
    inputs = (
        In("Surface", SURFACE, "S", "The surfaces to divide.", access=TREE),
        In("U", INTEGER, "U", "Divisions along u (rows of points minus one).", default=10),
        In("V", INTEGER, "V", "Divisions along v (points in a row minus one).", default=10),
    )
    outputs = (
        Out("Points", POINT, "P", "The grid, one branch per row of constant u.", access=TREE),
        Out("Normals", VECTOR, "N", "The unit normal at each point.", access=TREE, preview=False),
        Out("Parameters", POINT, "uv", "The (u, v) of each point, as x and y.", access=TREE, preview=False),
    )

    def solve(self, surfaces: DataTree, u_count: Any, v_count: Any) -> tuple[DataTree, DataTree, DataTree]:
        nu = count("U", u_count, least=1, limit=MAX_DIVISIONS)
        nv = count("V", v_count, least=1, limit=MAX_DIVISIONS)
        if (nu + 1) * (nv + 1) * max(surfaces.item_count, 1) > MAX_DIVISIONS:
            raise NodeWarning(f"U and V ask for {(nu + 1) * (nv + 1):,} points a surface; at most "
                              f"{MAX_DIVISIONS:,} in all: give fewer divisions")
        u, v = np.meshgrid(np.linspace(0.0, 1.0, nu + 1), np.linspace(0.0, 1.0, nv + 1), indexing="ij")
        u, v = u.ravel(), v.ravel()
        uv = points(np.stack([u, v, np.zeros_like(u)], axis=1))
        several = any(len(branch) > 1 for branch in surfaces.raw_branches)
        trees = DataTree(), DataTree(), DataTree()
        for path, branch in surfaces.items():
            for k, value in enumerate(branch):
                if value is None:
                    self.warn("Surface has an empty (null) item: it is skipped")
                    continue
                try:
                    surface = parametric_surface("Surface", value)
                except NodeWarning as refused:  # this surface is skipped, the others divided
                    self.warn(str(refused))
                    continue
                grid = points(surface.point_at(u, v))
                normal = vectors(surface.normal_at(u, v))
                prefix = (*path, k) if several else path
                for row in range(nu + 1):
                    rows = slice(row * (nv + 1), (row + 1) * (nv + 1))
                    for tree, values in zip(trees, (grid, normal, uv), strict=True):
                        tree.extend((*prefix, row), values[rows])
        return trees

