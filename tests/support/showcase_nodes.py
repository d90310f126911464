"""Test-only node types that make geometry, so the viewport tests do not depend on which
geometry nodes the library has today: a helix (curve), a hyperbolic paraboloid (ruled
surface plus its rulings), a mesh coloured by height (scalars), and a slow node."""

from __future__ import annotations

import math
import time

import numpy as np
import trimesh

from torsal.engine.node import LIST, In, Node, Out
from torsal.engine.registry import Registry
from torsal.engine.types import NUMBER
from torsal.nodes.catalogue import default_registry
from torsal.nodes.common.values import CURVE, LINE, MESH, SURFACE
from torsal.nodes.geometry.curves.line import Line
from torsal.nodes.geometry.curves.parametric import ParametricCurve
from torsal.nodes.geometry.parametric_surface import ParametricSurface


class Helix(Node):
    """A helix of radius 1 rising 0.3 per turn."""

    type_id = "showcase.Helix"
    inputs = (In("Turns", NUMBER, "T", "Number of turns.", default=2.0),)
    outputs = (Out("Curve", CURVE, "C", "The helix."),)

    def solve(self, turns: float) -> ParametricCurve:
        return ParametricCurve(
            lambda u: (np.cos(u), np.sin(u), 0.3 * u / (2 * math.pi)), (0.0, 2 * math.pi * max(turns, 0.1))
        )


class Hypar(Node):
    """z = x·y / Size over a square: a doubly ruled surface, with one family of rulings."""

    type_id = "showcase.Hypar"
    inputs = (In("Size", NUMBER, "S", "Half the side of the square.", default=2.0),)
    outputs = (
        Out("Surface", SURFACE, "S", "The hypar."),
        Out("Rulings", LINE, "R", "Rulings x = constant.", access=LIST),
    )

    def solve(self, size: float) -> tuple[ParametricSurface, list[Line]]:
        s = max(size, 0.1)
        surface = ParametricSurface(lambda u, v: (u + 4.0, v, u * v / s), (-s, s), (-s, s))
        rulings = [Line((x + 4.0, -s, -x), (x + 4.0, s, x)) for x in np.linspace(-s, s, 9)]
        return surface, rulings


class Bumps(Node):
    """A wavy square mesh whose vertices carry their height as scalars."""

    type_id = "showcase.Bumps"
    inputs = (In("Height", NUMBER, "H", "Wave height.", default=0.5),)
    outputs = (Out("Mesh", MESH, "M", "The coloured mesh."),)

    def solve(self, height: float) -> trimesh.Trimesh:
        n = 24
        x, y = np.meshgrid(np.linspace(-2, 2, n), np.linspace(-2, 2, n), indexing="ij")
        z = height * np.sin(2 * x) * np.cos(2 * y)
        vertices = np.column_stack([x.ravel(), y.ravel() - 5.0, z.ravel()])
        i, j = np.meshgrid(np.arange(n - 1), np.arange(n - 1), indexing="ij")
        a = (i * n + j).ravel()
        faces = np.concatenate(
            [np.column_stack([a, a + n, a + n + 1]), np.column_stack([a, a + n + 1, a + 1])]
        )
        mesh = trimesh.Trimesh(vertices, faces, process=False)
        mesh.metadata["scalars"] = z.ravel()
        mesh.metadata["scalar_name"] = "height"
        return mesh


class Slow(Node):
    """Busy for Seconds (pure Python, holding the GIL), checking for cancellation and
    saying how far it is."""

    type_id = "showcase.Slow"
    inputs = (In("Seconds", NUMBER, "S", "How long to work.", default=10.0),)
    outputs = (Out("Value", NUMBER, "V", "The seconds worked."),)

    def solve(self, seconds: float) -> float:
        start = time.perf_counter()
        total = 0
        while (elapsed := time.perf_counter() - start) < seconds:
            for k in range(2000):
                total += k * k
            self.check_cancelled()
            self.progress(elapsed / seconds)
        return time.perf_counter() - start


SHOWCASE = (Helix, Hypar, Bumps, Slow)


def showcase_registry() -> Registry:
    registry = default_registry(plugins=False)
    for cls in SHOWCASE:
        registry.register(cls)
    return registry
