"""The area a closed planar curve encloses, for the Area node.

A failed measurement raises :class:`~torsal.engine.node.NodeWarning` with a sentence for the
designer. (Candidate for the kernel's :mod:`torsal.nodes.geometry.area` once a second caller
needs it.)
"""

from __future__ import annotations

import numpy as np

from torsal.engine.node import NodeWarning
from torsal.nodes.geometry.curve_base import Curve

PLANAR = 1e-9
"""A closed curve is planar when its points lie within this share of its size across its plane."""


def _loop_integrals(curve: Curve, origin: np.ndarray, order: int = 16) -> tuple[np.ndarray, np.ndarray]:
    """Vector area ½∮(C − O) × C' dt and Gauss samples, refined until the area settles.

    Panels start at the curve's smooth spans and halve until the vector area changes
    by less than 1e-14 of itself. Returns the area vector and the (points, C', weights)
    of the last rule, stacked as one ``(m, 7)`` array.
    """
    breaks = np.unique(np.clip(np.asarray(curve._breakpoints(), dtype=float), 0.0, 1.0))
    nodes, weights = np.polynomial.legendre.leggauss(order)
    previous = None
    for level in range(12):
        pieces = 2**level
        steps = np.arange(pieces) / pieces
        spans = breaks[:-1, None] + np.diff(breaks)[:, None] * steps
        edges = np.append(spans.ravel(), breaks[-1])
        low, high = edges[:-1], edges[1:]
        half = 0.5 * (high - low)[:, None]
        t = (0.5 * (low + high)[:, None] + half * nodes).ravel()
        w = (half * weights).ravel()
        c, d = curve.derivatives(t, 1)
        area = 0.5 * (np.cross(c - origin, d) * w[:, None]).sum(axis=0)
        if previous is not None and np.linalg.norm(area - previous) <= 1e-14 * np.linalg.norm(area):
            break
        previous = area
    return area, np.column_stack([c, d, w])


def enclosed(curve: Curve) -> tuple[float, np.ndarray]:
    """Area and centroid of the region a closed planar curve bounds.

    Green's theorem in the curve's plane: with O the start point and n the unit
    normal of the vector area, A = ½∮ n·((C − O) × C') dt and the centroid is
    O + ∮ (C − O)·n·((C − O) × C') dt / (3A), each thin triangle from O weighted at
    two thirds of the way out.
    """
    start, end = curve.point_at(0.0), curve.point_at(1.0)
    box = curve.bounding_box()
    size = float(np.linalg.norm(box[1] - box[0]))
    if size == 0:
        raise NodeWarning("The curve is a single point, so it encloses no area")
    if not (curve.closed or np.linalg.norm(end - start) <= 1e-12 * size):
        raise NodeWarning("The curve is open: only a closed planar curve encloses an area")
    vector_area, samples = _loop_integrals(curve, start)
    c, d, w = samples[:, :3] - start, samples[:, 3:6], samples[:, 6]
    area = float(np.linalg.norm(vector_area))
    if area <= 1e-14 * size * size:
        raise NodeWarning("The curve encloses no area: it runs back along itself")
    normal = vector_area / area
    corners = curve.point_at(np.asarray(curve._breakpoints(), dtype=float)) - start
    heights = np.concatenate([c @ normal, corners @ normal])
    spread = float(heights.max() - heights.min())
    if spread > PLANAR * size:
        raise NodeWarning(
            f"The curve is not planar (its points lie up to {spread:.3g} apart across its plane): "
            "only a closed planar curve encloses an area"
        )
    fan = np.cross(c, d) @ normal  # twice the area rate of the thin triangles from O
    centroid = start + (c * (fan * w)[:, None]).sum(axis=0) / (3.0 * area)
    return area, centroid
