"""Where a curve meets a plane (:func:`curve_plane_intersections`, behind the
IntersectCurvePlane node)."""

from __future__ import annotations

from typing import TYPE_CHECKING, NamedTuple

import numpy as np

from .array_types import FloatArray
from .closest import sample_parameters
from .roots import roots_in_samples
from .vectors import Plane

if TYPE_CHECKING:
    from .curve_base import Curve


class CurvePlaneHits(NamedTuple):
    """Where a curve meets a plane, in increasing t."""

    parameters: FloatArray  #: (k,)
    points: FloatArray  #: (k, 3)


def curve_plane_intersections(
    curve: Curve, plane: Plane, tolerance: float = 1e-10, samples_per_span: int = 32
) -> CurvePlaneHits:
    """All points where ``curve`` crosses or touches ``plane``.

    The signed distance ``g(t) = (C(t) − origin)·n`` is sampled on every smooth span
    (``samples_per_span``, and finer where the curve turns);
    each sign change is refined to rounding by a bracketed solver. Touching points
    (g has a zero minimum or maximum, no sign change) are found as roots of ``g'`` where
    ``|g| <= tolerance``. A stretch of curve lying in the plane gives its sampled points.
    Crossings closer together than a sampling interval can be missed.
    """
    per_span = sample_parameters(curve, per_span=samples_per_span, minimum=256)
    samples = np.union1d(per_span, curve._search_parameters)

    # measured from the curve's anchor: far from the origin the distances then round
    # relative to the curve's size, not to its coordinates
    normal = np.asarray(plane.z, dtype=float)
    height = float((np.asarray(curve.anchor, dtype=float) - np.asarray(plane.origin, dtype=float)) @ normal)

    def distance(t: FloatArray) -> FloatArray:
        local = curve.local_derivatives(np.ravel(t), 0)[0]
        return (local @ normal + height).reshape(np.shape(t))

    def rate(t: FloatArray) -> FloatArray:
        return (curve.derivatives(np.ravel(t), 1)[1] @ plane.z).reshape(np.shape(t))

    crossings = roots_in_samples(distance, samples)
    extremes = roots_in_samples(rate, samples)
    touching = extremes[np.abs(distance(extremes)) <= tolerance]
    lying = samples[np.abs(distance(samples)) <= tolerance]
    t = np.sort(np.concatenate([crossings, touching, lying]))
    if len(t):
        keep = np.concatenate([[True], np.diff(t) > 1e-10])
        t = t[keep]
        if curve.closed and len(t) > 1 and t[0] <= 1e-10 and t[-1] >= 1 - 1e-10:
            t = t[:-1]  # t = 0 and t = 1 are the same point of a closed curve
    return CurvePlaneHits(t, curve.point_at(t))
