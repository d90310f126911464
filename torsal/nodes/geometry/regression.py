"""The curve of regression of a ruled strip: the kernel of CurveOfRegression.

On a developable surface (other than a plane, cylinder or cone) consecutive rulings
meet, in the limit, on a space curve that every ruling touches: the curve of
regression, the surface's sharp edge. Given a strip of discrete rulings:

1. For each pair of neighbouring rulings, the closest points of their two lines
   (one on each), for all pairs at once. With unit directions u_i, u_{i+1},
   w = A_{i+1} − A_i and n = u_i × u_{i+1}, the closest point on line i lies at
   s = ((w × u_{i+1})·n)/|n|² along u_i from A_i, and the one on line i + 1 at
   t = ((w × u_i)·n)/|n|² along u_{i+1} from A_{i+1}.
2. One point per ruling: every inner ruling takes the midpoint of its two closest
   points (the one towards the previous ruling and the one towards the next). Each
   point lies on its ruling; for a smooth ruled surface it tends to the striction
   point v = −⟨a′, e′⟩/|e′|² (e the unit ruling direction), and the midpoint makes
   the estimate second-order accurate. The first and last rulings have one closest
   point each; it is first-order (half a step off along the ruling), so it is moved
   back by half the split between the two closest points seen on the neighbouring
   ruling — a second-order end point, so that the end segments pass the same
   Deviation test as the rest (with two rulings only the raw points are used).
3. A segment between consecutive points is kept when its direction agrees with the
   rulings' within ``deviation`` (the angle between the chord's line and the mean of
   the two rulings' lines — a tangent must agree with its ruling; the mean makes the
   test second-order so that Deviation is not eaten by the discretisation). Runs of
   kept segments become separate polylines.

Special cases are told apart first: a planar strip and parallel rulings (a
cylinder) have no curve of regression; a cone has an apex instead (all closest
points coincide); a warped ruled surface (a hyperbolic paraboloid) has rulings that
never meet and gets no curve either.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .array_types import FloatArray
from .vec_ops import det, dot

#: Rulings within this angle (rad) count as parallel.
PARALLEL_ANGLE = 1e-9
#: Points within this share of the strip's size count as one point (a cone's apex).
APEX_TOLERANCE = 1e-7
#: A strip whose points lie within this share of its size from one plane is planar.
PLANAR_TOLERANCE = 1e-9


@dataclass(frozen=True)
class Regression:
    """The curve of regression of a strip, or why there is none.

    ``kind`` is ``"curve"`` (``curves`` holds it, split where invalid), ``"apex"`` (a
    cone: ``apex`` is the point), ``"parallel"`` (a cylinder), ``"planar"`` or
    ``"warped"`` (the rulings do not meet: not developable). ``message`` says it in
    words for the node. ``points`` has one row per ruling (NaN where a ruling is
    parallel to both neighbours); ``valid`` one flag per segment between them;
    ``deviations`` the angle (rad) of each segment against the rulings;
    ``gaps`` the distance between the lines of each pair of neighbouring rulings
    (zero for rulings that meet, so a measure of the warp).
    """

    points: FloatArray
    valid: NDArray[np.bool_]
    deviations: FloatArray
    gaps: FloatArray
    curves: list[FloatArray] = field(repr=False)
    kind: str
    message: str
    apex: FloatArray | None = None

    @property
    def has_curve(self) -> bool:
        """True when at least one piece of the curve of regression was found."""
        return self.kind == "curve"


def closest_points_of_lines(
    starts: FloatArray, directions: FloatArray
) -> tuple[FloatArray, FloatArray, NDArray[np.bool_]]:
    """Closest points of the lines of neighbouring rulings, all pairs at once.

    ``starts`` (n, 3) are points on the lines and ``directions`` (n, 3) unit
    directions. Returns ``(on_first, on_second, parallel)``: for pair i, the point on
    line i nearest to line i + 1, the point on line i + 1 nearest to line i (both
    ``(n − 1,)``: their distances along the directions from the starts, NaN for
    parallel pairs), and the parallel flags.
    """
    u0, u1 = directions[:-1], directions[1:]
    w = starts[1:] - starts[:-1]
    normal = np.cross(u0, u1)
    sin2 = dot(normal, normal)
    parallel = sin2 <= PARALLEL_ANGLE**2
    with np.errstate(divide="ignore", invalid="ignore"):
        s = np.where(parallel, np.nan, det(normal, w, u1) / sin2)
        t = np.where(parallel, np.nan, det(normal, w, u0) / sin2)
    return s, t, parallel


def curve_of_regression(starts: ArrayLike, ends: ArrayLike, deviation: float) -> Regression:
    """The curve of regression of the strip through rulings ``starts[i] → ends[i]``.

    ``deviation`` (rad) is how far a segment of the curve may turn away from the
    rulings it joins and still count as part of the curve (see the module docstring).

    Example:
        >>> import numpy as np
        >>> t = np.linspace(0.0, 1.0, 5)
        >>> base = np.column_stack([np.cos(t), np.sin(t), 0 * t])   # a cone, apex (0, 0, 2)
        >>> reg = curve_of_regression(base, base + 0.5 * ([0, 0, 2] - base), 0.01)
        >>> reg.kind, bool(np.allclose(reg.apex, [0, 0, 2], atol=1e-12))
        ('apex', True)
    """
    a = np.asarray(starts, dtype=float)
    b = np.asarray(ends, dtype=float)
    if a.ndim != 2 or a.shape[1] != 3 or a.shape != b.shape or len(a) < 2:
        raise ValueError("starts and ends must be (n, 3) arrays of at least two rulings")
    ruling = b - a
    length = np.linalg.norm(ruling, axis=1)
    if np.any(length == 0):
        raise ValueError("every ruling needs a length to have a direction")
    unit = ruling / length[:, None]
    cloud = np.vstack([a, b])
    size = float(np.linalg.norm(np.ptp(cloud, axis=0)))

    s, t, parallel = closest_points_of_lines(a, unit)
    gaps = np.linalg.norm(a[:-1] + s[:, None] * unit[:-1] - a[1:] - t[:, None] * unit[1:], axis=1)
    # on each ruling: where it comes closest to the previous (back) and next (ahead) one
    back, ahead = np.r_[np.nan, t], np.r_[s, np.nan]
    both = np.column_stack([back, ahead])
    count = np.isfinite(both).sum(axis=1)
    with np.errstate(invalid="ignore", divide="ignore"):
        where = np.where(count > 0, np.nansum(both, axis=1) / count, np.nan)
        half = 0.5 * (ahead - back)  # half the split on the inner rulings
    if len(a) > 2:
        where[0] -= np.nan_to_num(half[1])
        where[-1] += np.nan_to_num(half[-2])
    points = a + where[:, None] * unit

    # segment directions against the mean of the two rulings' lines
    chord = np.diff(points, axis=0)
    sign = np.where(dot(unit[:-1], unit[1:]) < 0, -1.0, 1.0)
    mean = unit[:-1] + sign[:, None] * unit[1:]
    deviations = np.arctan2(np.linalg.norm(np.cross(chord, mean), axis=1), np.abs(dot(chord, mean)))
    collapsed = np.linalg.norm(chord, axis=1) <= APEX_TOLERANCE * size  # the rulings meet in one point
    deviations = np.where(collapsed, 0.0, deviations)
    finite = np.all(np.isfinite(chord), axis=1)
    valid = finite & (deviations <= deviation)

    def result(kind: str, message: str, curves: list[FloatArray] | None = None,
               apex: FloatArray | None = None) -> Regression:
        return Regression(points, valid if kind == "curve" else np.zeros_like(valid),
                          np.where(finite, deviations, np.nan), gaps, curves or [], kind, message, apex)

    centred = cloud - cloud.mean(axis=0)
    thickness = np.linalg.svd(centred, compute_uv=False)[-1] / np.sqrt(len(cloud))
    if thickness <= PLANAR_TOLERANCE * size:
        return result("planar", "no curve of regression: the strip is planar")
    if parallel.all():
        return result("parallel", "no curve of regression: the rulings are parallel (a cylinder)")
    good = np.all(np.isfinite(points), axis=1)
    spread = np.linalg.norm(points[good] - points[good].mean(axis=0), axis=1).max()
    if good.all() and spread <= APEX_TOLERANCE * size:
        apex = points.mean(axis=0)
        text = ", ".join(f"{x:.6g}" for x in apex)
        return result("apex", f"a cone: every ruling passes through its apex ({text}); "
                      "a cone has an apex, not a curve of regression", apex=apex)
    if not valid.any():
        worst = float(np.nanmax(gaps)) if np.isfinite(gaps).any() else 0.0
        return result("warped", "no curve of regression: neighbouring rulings do not meet (up to "
                      f"{worst:.3g} apart), so the surface is not developable; a larger Deviation "
                      "accepts rougher curves")
    # runs of valid segments → polylines (a loop over runs, not points)
    edges = np.diff(np.r_[0, valid.astype(np.int8), 0])
    run_starts, run_ends = np.flatnonzero(edges == 1), np.flatnonzero(edges == -1)
    curves = [points[i:j + 1] for i, j in zip(run_starts, run_ends, strict=True)]
    bad = int((~valid).sum())
    message = "curve of regression" if bad == 0 else (
        f"curve of regression in {len(curves)} pieces: {bad} of {len(valid)} segments turn "
        f"more than Deviation away from the rulings")
    return result("curve", message, curves)
