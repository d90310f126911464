"""Write ``tests/fixtures/double-bump-mm.3dm``: the double bump with a valley as a Rhino user
would bring it — one untrimmed bicubic NURBS surface, drawn in millimetres.

The closed form is the ``bumps`` design of :mod:`tests.support.freeform_designs`
(z = 2·exp(−((x ∓ 4.5)² + y²)/18) summed, over 18 × 12 m), here in millimetres. Its
heights are interpolated by scipy (``RectBivariateSpline``, cubic, through a grid of
:data:`GRID` points, spacing 0.375 m) and the spline written as the surface: control
points at the Greville abscissae of its knots in x and y (so x and y are the surface's
own parameters, exactly: a B-spline reproduces a linear function from its Greville
points), the spline's coefficients as heights. Interpolated thus, the surface lies within
about 3e-5 m of the closed form (:data:`FIT`, measured by a test). Written with rhino3dm
alone, as the canopy example's design is (``tools/build_design_3dm.py``).

Run ``.venv/bin/python -m tests.support.double_bump_3dm`` to write it again.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import rhino3dm as rh
from scipy.interpolate import RectBivariateSpline

from tests.support.freeform_designs import DESIGNS, MM
from tools.build_design_3dm import write_design

FIXTURE = Path(__file__).resolve().parent.parent / "fixtures" / "double-bump-mm.3dm"
#: Interpolation points along x and y (18 m and 12 m at 0.375 m).
GRID = (49, 33)
#: How far the written surface may lie from the closed form, in metres.
FIT = 1e-4


def spline() -> RectBivariateSpline:
    """The bumps' heights (m) interpolated over the grid, x and y in metres."""
    design = DESIGNS["bumps"]
    x, y = np.linspace(*design.x, GRID[0]), np.linspace(*design.y, GRID[1])
    gx, gy = np.meshgrid(x, y, indexing="ij")
    return RectBivariateSpline(x, y, design.height(gx, gy), kx=3, ky=3, s=0)


def _greville(knots: np.ndarray, count: int) -> np.ndarray:
    return np.array([knots[i + 1:i + 4].mean() for i in range(count)])


def surface() -> rh.NurbsSurface:
    """The spline as a rhino3dm NURBS surface, in millimetres."""
    fitted = spline()
    tx, ty, c = fitted.tck
    nx, ny = len(tx) - 4, len(ty) - 4
    heights = np.asarray(c).reshape(nx, ny)
    gx, gy = _greville(tx, nx), _greville(ty, ny)
    out = rh.NurbsSurface.Create(3, False, 4, 4, nx, ny)
    for i in range(nx):
        for j in range(ny):
            out.Points[(i, j)] = rh.Point4d(MM * gx[i], MM * gy[j], MM * heights[i, j], 1.0)
    for knots, full in ((out.KnotsU, tx), (out.KnotsV, ty)):  # Rhino's vector: no end knot of each side
        for k in range(len(knots)):
            knots[k] = float(MM * full[k + 1])
    return out


def build(path: Path = FIXTURE) -> Path:
    """Write the file at ``path`` (units: millimetres) and return it."""
    return write_design(surface(), path, "Double bump")


if __name__ == "__main__":
    print(f"wrote {build()}")
