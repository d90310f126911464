"""A strip's fans as Rhino faces (:mod:`.threedm_strips`): flat triangles between rulings that
share an end, exactly through the rulings' ends.

- :func:`fan_run`: consecutive fan triangles as one face of degree 1 both ways, each span
  one flat triangle;
- :func:`fan_triangle`: a lone triangle (or a run rhino3dm will not make a face) as a
  trimmed plane through its three corners.
"""

from __future__ import annotations

import numpy as np
import rhino3dm as rh

from torsal.nodes.geometry.nurbs_surface import NurbsSurface
from torsal.nodes.io.formats.threedm_native import rhino_surface

#: Two ruling ends closer than this (relative to the size) are one point: a fan.
SAME_POINT = 1e-12


def fan_run(lines: np.ndarray) -> rh.Brep | None:
    """Consecutive fan triangles (each pair of rulings sharing an end) as one face of degree 1
    both ways through the rulings: each span between two rulings is one flat triangle (the
    rail that shares the end stands still there). None when rhino3dm will not make it a face
    (every triangle through one point: an edge collapsed to it)."""
    count = len(lines)
    knots = np.concatenate([[0.0], np.linspace(0.0, 1.0, count), [1.0]])

    try:
        surface = NurbsSurface(np.asarray(lines, dtype=float), 1, 1, knots, [0.0, 0.0, 1.0, 1.0])
        brep = rh.Brep.CreateFromSurface(rhino_surface(surface))
    except ValueError:
        return None
    return brep if brep is not None and brep.IsValid else None


def fan_triangle(first: np.ndarray, second: np.ndarray, size: float) -> rh.Brep | None:
    corners = [first[0], first[1], second[1] if np.abs(first[0] - second[0]).max() <= SAME_POINT * size
               else second[0]]
    a, b, c = (np.asarray(p, dtype=float) for p in corners)
    if np.linalg.norm(np.cross(b - a, c - a)) <= 1e-12 * size * size:
        return None
    points = [rh.Point3d(*map(float, p)) for p in (a, b, c, a)]
    plane = rh.Plane(points[0], points[1], points[2])
    return rh.Brep.CreateTrimmedPlane(plane, rh.PolylineCurve(points))
