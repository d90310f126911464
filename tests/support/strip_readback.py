"""Exported strips read back with rhino3dm (not with the exporter's code): the normals of
each face along its lines across, at the node's own rulings and anywhere on it.

A strip goes to a ``.3dm`` as faces, each a single-face brep carrying the user strings
``TorsalIndex`` (the strip), ``TorsalRulings`` ("first-last", 1-based) and ``TorsalFace``
("torsal", "cone" or "fan"). A ruled face's parameter along the strip is the strip's own u
scaled to the face's domain, so the face's isocurve at a ruling's u is that ruling (checked
here against the node's line before its normals are read).
"""

from __future__ import annotations

import numpy as np
import rhino3dm as rh


def _vector(p) -> np.ndarray:
    return np.array([p.X, p.Y, p.Z])


def _angle(x: np.ndarray, y: np.ndarray) -> float:
    return float(np.arctan2(np.linalg.norm(np.cross(x, y)), x @ y))


def read(path) -> list:
    """The objects of a ``.3dm`` file."""
    return list(rh.File3dm.Read(str(path)).Objects)


def faces_of(objects: list, index: int) -> list[tuple[object, str, int, int]]:
    """Strip ``index``'s faces in the file: (object, kind, first ruling, last ruling), 0-based."""
    out = []
    for obj in objects:
        if obj.Attributes.GetUserString("TorsalIndex") != str(index):
            continue
        first, last = (int(x) - 1 for x in obj.Attributes.GetUserString("TorsalRulings").split("-"))
        out.append((obj, obj.Attributes.GetUserString("TorsalFace"), first, last))
    return out


def across_twist(surface: rh.Surface, count: int, inset: float = 0.01) -> float:
    """The largest angle between the normals ``inset`` in from each end of an isoparametric
    line across the face (v from end to end), over ``count`` of them evenly in u."""
    du, dv = surface.Domain(0), surface.Domain(1)
    worst = 0.0
    for a in np.linspace(0.0, 1.0, count):
        u = du.T0 + (du.T1 - du.T0) * a
        n0 = _vector(surface.NormalAt(u, dv.T0 + inset * (dv.T1 - dv.T0)))
        n1 = _vector(surface.NormalAt(u, dv.T0 + (1.0 - inset) * (dv.T1 - dv.T0)))
        worst = max(worst, _angle(n0, n1))
    return worst


def ruling_warps(objects: list, strips: list, kinds: list[str]) -> tuple[dict[tuple[int, int], float], float]:
    """The warp of every one of the node's torsal rulings (``kinds``: Rationalise's Kind,
    strip after strip) as the exported faces have it, by (strip, ruling): the largest angle
    between a face's normals at the two ends of its isocurve at the ruling's u, over the
    ruled faces the ruling bounds or crosses; and the largest distance of those isocurves'
    ends from the node's ruling ends, relative to the strip's size."""
    warps: dict[tuple[int, int], float] = {}
    off, start = 0.0, 0
    for index, strip in enumerate(strips):
        lines = np.asarray(strip.ruling_lines, dtype=float)
        u = np.asarray(strip.ruling_parameters, dtype=float)
        kind = kinds[start:start + len(lines)]
        start += len(lines)
        size = float(np.ptp(lines.reshape(-1, 3), axis=0).max())
        for obj, face, first, last in faces_of(objects, index):
            if face == "fan":
                continue
            surface = obj.Geometry.Faces[0].UnderlyingSurface()
            du, dv = surface.Domain(0), surface.Domain(1)
            for j in range(first, last + 1):
                if kind[j] != "torsal":
                    continue
                at = du.T0 + (du.T1 - du.T0) * (u[j] - u[first]) / (u[last] - u[first])
                ends = np.array([_vector(surface.PointAt(at, v)) for v in (dv.T0, dv.T1)])
                off = max(off, float(np.linalg.norm(ends - lines[j], axis=1).max()) / size)
                normals = [_vector(surface.NormalAt(at, v)) for v in (dv.T0, dv.T1)]
                warps[index, j] = max(warps.get((index, j), 0.0), _angle(*normals))
    return warps, off


def torsal_rulings(strips: list, kinds: list[str]) -> set[tuple[int, int]]:
    """The (strip, ruling) of every ruling whose Kind is "torsal"."""
    out, start = set(), 0
    for index, strip in enumerate(strips):
        count = len(strip.ruling_lines)
        out |= {(index, j) for j in range(count) if kinds[start + j] == "torsal"}
        start += count
    return out
