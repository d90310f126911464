"""Write ``torsal/resources/examples/canopy.3dm``: the example design a Rhino user would bring.

A canopy 12 × 8 m, one untrimmed bicubic NURBS surface drawn in millimetres (as many
architects model), rising from 3 m at its long edges to 4.2 m along its middle and
sagging 0.3 m between its ends — curved both ways, gently. Made with rhino3dm alone, with
fixed object and layer ids and a bare file name, so two runs differ only in the time stamp
openNURBS writes into the file's properties.
``rationalise-canopy.graph`` reads it (``tools/build_examples.py``).

Run ``.venv/bin/python -m tools.build_design_3dm``.
"""

from __future__ import annotations

import os
import uuid
from pathlib import Path

import numpy as np
import rhino3dm as rh

OUT = Path(__file__).resolve().parent.parent / "torsal" / "resources" / "examples"
NAME = "canopy.3dm"


def canopy_points(nu: int = 7, nv: int = 6) -> np.ndarray:
    """The control net, in millimetres: x along the 12 m, y across the 8 m."""
    x = np.linspace(0.0, 12000.0, nu)
    y = np.linspace(0.0, 8000.0, nv)
    grid_x, grid_y = np.meshgrid(x, y, indexing="ij")
    across = 1.0 - ((grid_y - 4000.0) / 4000.0) ** 2  # 0 at the long edges, 1 in the middle
    along = ((grid_x - 6000.0) / 6000.0) ** 2  # 0 in the middle, 1 at the ends
    z = 3000.0 + 1200.0 * across - 300.0 * (1.0 - along) * across
    return np.stack([grid_x, grid_y, z], axis=-1)


def build(folder: Path = OUT) -> Path:
    points = canopy_points()
    nu, nv = points.shape[:2]
    surface = rh.NurbsSurface.Create(3, False, 4, 4, nu, nv)
    for i in range(nu):
        for j in range(nv):
            surface.Points[(i, j)] = rh.Point4d(*points[i, j].tolist(), 1.0)
    for knots, count in ((surface.KnotsU, nu), (surface.KnotsV, nv)):
        inner = count - 3
        values = [0.0, 0.0, *np.linspace(0.0, 1.0, inner + 1).tolist(), 1.0, 1.0]
        for k in range(len(knots)):
            knots[k] = float(values[k])
    return write_design(surface, folder / NAME, "Canopy")


def write_design(surface: rh.NurbsSurface, path: Path, name: str) -> Path:
    """Write ``surface`` alone to ``path`` as a design drawn in millimetres: on a layer
    "Design", named ``name``, with fixed object and layer ids (two runs differ only in
    openNURBS's time stamp)."""
    model = rh.File3dm()
    model.Settings.ModelUnitSystem = rh.UnitSystem.Millimeters
    layer = rh.Layer()
    layer.Name, layer.Id, layer.Color = "Design", uuid.UUID(int=1), (90, 140, 200, 255)
    index = model.Layers.Add(layer)
    attributes = rh.ObjectAttributes()
    attributes.Id, attributes.LayerIndex, attributes.Name = uuid.UUID(int=2), index, name
    model.Objects.AddSurface(surface, attributes)
    here = os.getcwd()
    os.chdir(path.parent)  # rhino3dm stores the path it is given
    try:
        if not model.Write(path.name, 7):
            raise RuntimeError(f"rhino3dm could not write {path}")
    finally:
        os.chdir(here)
    return path


if __name__ == "__main__":
    print(f"wrote {build()}")
