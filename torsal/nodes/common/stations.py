"""Where along a strip something happens: the per-station diagnostics strip nodes word.

A strip-making node samples its rulings at stations t in [0, 1]; when some stations
are degenerate (a ruling along the curve's tangent, a curve through the Apex) the node
says how many and where the first is.
"""

from __future__ import annotations

import numpy as np

#: Below this share of a shape's size a distance counts as zero.
COINCIDENT = 1e-12


def first_where(mask: np.ndarray, parameters: np.ndarray) -> str:
    """'k of n stations (first at t = …)' for a boolean mask over stations."""
    k = int(np.count_nonzero(mask))
    return f"{k} of {mask.size} stations (first at t = {float(parameters[np.argmax(mask)]):.4g})"


def along_tangent(directions: np.ndarray, tangents: np.ndarray, tolerance: float = 1e-9) -> np.ndarray:
    """Where a ruling direction is parallel to the curve's tangent: the strip has no width there."""
    d = directions / np.maximum(np.linalg.norm(directions, axis=1), 1e-300)[:, None]
    t = tangents / np.maximum(np.linalg.norm(tangents, axis=1), 1e-300)[:, None]
    moving = np.linalg.norm(tangents, axis=1) > 0
    return moving & (np.linalg.norm(np.cross(d, t), axis=1) <= tolerance)
