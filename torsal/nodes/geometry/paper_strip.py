"""A digital paper strip, after Lorenz Lachauer: the kernel of PaperStrip.

The strip is a chain of planar quads, each folded against the previous one about
their shared ruling — exactly what paper does, so the result is developable by
construction. Each ruling i carries an orthonormal frame (r, c, n): r along the
ruling, c the strip's advancing direction (in the face, perpendicular to r) and
n = c × r the face normal. Segment i then

1. bends: c turns about the ruling r by the curvature angle κ_i (towards +n for
   κ_i > 0), giving the direction c′ in which the new face leaves the ruling;
2. tilts: the next ruling is r turned within the new face plane by θ_i = 90° − iso_i,
   r_{i+1} = cos θ_i · r + sin θ_i · c′, so the iso angle is the angle between the
   strip's advancing direction c′ and the new ruling (90°: parallel rulings);
3. advances: the ruling's midpoint moves by length/segments along c′.

In frame coordinates one segment is a fixed rotation Q(κ_i, θ_i); the frame of
ruling i is the product Q_0 ⋯ Q_{i−1}, computed for all rulings at once by a
log₂(segments)-step parallel prefix product, and the midpoints by a cumulative sum.

Unfolding is the same construction with every κ = 0 (a fold about a ruling is an
isometry of the face), so the development comes exact, not from a numerical
unrolling; :func:`~torsal.nodes.geometry.unroll.unroll_rulings` reproduces it.

The strip *is* its faces: between two fold lines the paper is the flat quad through
their end points, with straight edges. So the surface a node outputs is the loft with
polyline rails (``RuledSurface.from_rulings(..., degree=1)``), not a smooth loft,
whose curved edges would leave the faces' planes; cut along the development's
straight edges, a sheet folds into exactly these faces.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .array_types import FloatArray
from .counts import segment_count


def quad_planarity(starts: ArrayLike, ends: ArrayLike) -> FloatArray:
    """Planarity of each quad (A_i, A_{i+1}, B_{i+1}, B_i) of a strip, ``(n − 1,)``.

    The distance of the fourth vertex from the plane of the other three, divided by
    the quad's longer diagonal: 0 for a planar quad. Of the two vertex triples
    (A_i, A_{i+1}, B_i) and (A_{i+1}, B_{i+1}, B_i) the one with the larger triangle
    defines the plane (a quad with a collapsed edge still has a well-defined plane).
    """
    a = np.asarray(starts, dtype=float)
    b = np.asarray(ends, dtype=float)
    a0, a1, b0, b1 = a[:-1], a[1:], b[:-1], b[1:]
    n1 = np.cross(a1 - a0, b0 - a0)
    n2 = np.cross(b1 - a1, b0 - a1)
    use_first = np.linalg.norm(n1, axis=1) >= np.linalg.norm(n2, axis=1)
    normal = np.where(use_first[:, None], n1, n2)
    origin = np.where(use_first[:, None], a0, a1)
    other = np.where(use_first[:, None], b1, a0)
    length = np.linalg.norm(normal, axis=1)
    off = np.abs(np.einsum("ij,ij->i", other - origin, normal)) / np.where(length > 0, length, 1.0)
    size = np.maximum(np.linalg.norm(b1 - a0, axis=1), np.linalg.norm(b0 - a1, axis=1))
    return np.where(size > 0, off / np.where(size > 0, size, 1.0), 0.0)


def face_warp(starts: ArrayLike, ends: ArrayLike) -> FloatArray:
    """Warp angle (rad, in [0, π]) along each ruling of the strip of flat quads through
    the rulings: the turn of the tangent plane from the ruling's start to its end on the
    face after it (the last ruling: on the face before it). The face's plane at A_i is
    spanned by the ruling and the edge A_i → A_{i+1}, at B_i by the ruling and
    B_i → B_{i+1}; for a planar quad the two agree, so the warp is 0 to rounding."""
    a = np.asarray(starts, dtype=float)
    b = np.asarray(ends, dtype=float)
    face = np.minimum(np.arange(len(a)), len(a) - 2)  # the face each ruling is measured on
    ruling = b - a
    at_start = np.cross(a[face + 1] - a[face], ruling)
    at_end = np.cross(b[face + 1] - b[face], ruling)
    return np.arctan2(np.linalg.norm(np.cross(at_start, at_end), axis=1),
                      np.einsum("ij,ij->i", at_start, at_end))


@dataclass(frozen=True)
class Strip:
    """A paper strip: its rulings in 3D and, flat, in the XY plane.

    ``starts``/``ends`` (n, 3) are the rulings (n = segments + 1), each ``width``
    long; ``starts2d``/``ends2d`` (n, 2) the same strip unfolded (the first ruling
    from the origin up the +y axis, the strip running towards +x, as
    :func:`~torsal.nodes.geometry.unroll.unroll_rulings` lays it down). ``normals`` are the
    unit face normals per segment, ``planarity`` per segment (see
    :func:`quad_planarity`), and ``crossing`` flags segments whose two rulings meet
    inside the strip (the tilt is too steep for the segment length and width: the
    quad folds over itself).
    """

    starts: FloatArray
    ends: FloatArray
    starts2d: FloatArray
    ends2d: FloatArray
    normals: FloatArray
    planarity: FloatArray
    crossing: NDArray[np.bool_]

    @property
    def valid(self) -> bool:
        """True when no two neighbouring rulings cross inside the strip."""
        return not bool(self.crossing.any())


def _per_segment(values: ArrayLike, segments: int, default: float, name: str) -> FloatArray:
    """A per-segment list: the last value repeats when short, extra values are ignored."""
    v = np.atleast_1d(np.asarray(values, dtype=float)).ravel()
    if v.size == 0:
        v = np.array([default])
    if not np.all(np.isfinite(v)):
        raise ValueError(f"{name} must be finite numbers")
    return np.concatenate([v, np.full(max(0, segments - v.size), v[-1])])[:segments]


def _prefix_products(q: FloatArray) -> FloatArray:
    """``P_k = q_0 q_1 ⋯ q_k`` for a stack of matrices ``(m, 3, 3)``, by recursive
    doubling: log₂ m batched matrix products instead of m sequential ones."""
    p = q.copy()
    shift = 1
    while shift < len(p):
        p[shift:] = p[:-shift] @ p[shift:]
        shift *= 2
    return p


def _build(length: float, width: float, iso: FloatArray, kappa: FloatArray
           ) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Ruling starts, ends and face normals of a strip (see the module docstring)."""
    segments = len(iso)
    theta = 0.5 * np.pi - iso
    ct, st, ck, sk = np.cos(theta), np.sin(theta), np.cos(kappa), np.sin(kappa)
    zero = np.zeros(segments)
    # columns: the next ruling r', advancing direction c', normal n' in the current frame
    q = np.stack([
        np.column_stack([ct, st * ck, st * sk]),
        np.column_stack([-st, ct * ck, ct * sk]),
        np.column_stack([zero, -sk, ck]),
    ], axis=2)
    first = np.array([[0.0, 1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])  # r = +y, c = +x, n = +z
    frames = np.concatenate([first[None], first @ _prefix_products(q)])  # (n, 3, 3), columns r, c, n
    bend = np.column_stack([zero, ck, sk])  # c′ of segment i in frame i
    advance = np.einsum("ijk,ik->ij", frames[:-1], bend) * (length / segments)
    origin = np.array([0.0, 0.5 * width, 0.0])  # so that the first ruling starts at the origin
    middle = origin + np.vstack([np.zeros(3), np.cumsum(advance, axis=0)])
    ruling = frames[:, :, 0]
    starts, ends = middle - 0.5 * width * ruling, middle + 0.5 * width * ruling
    normals = np.einsum("ijk,ik->ij", frames[:-1], np.column_stack([zero, -sk, ck]))
    return starts, ends, normals


def paper_strip(
    length: float,
    width: float,
    iso_angles: ArrayLike,
    curvatures: ArrayLike,
    segments: int,
) -> Strip:
    """A paper strip of ``segments`` planar quads, ``length`` long (along its middle
    line) and ``width`` wide (every ruling's length).

    ``iso_angles`` (rad, per segment): the angle between the strip's advancing
    direction and the next ruling; π/2 keeps the rulings parallel (bent, a
    cylinder), less leans each ruling forward at its end point so the strip turns
    towards its start edge (bent, a cone or a tangent developable).
    ``curvatures`` (rad, per segment): the fold angle about the previous ruling;
    0 keeps the strip flat. A list shorter than ``segments`` repeats its last value
    (an empty one means π/2, resp. 0).

    Example:
        >>> strip = paper_strip(2 * np.pi, 1.0, [np.pi / 2], [2 * np.pi / 12], 12)
        >>> round(float(np.linalg.norm(strip.starts[-1] - strip.starts[0])), 12)  # closes
        0.0
    """
    segments = segment_count(segments)
    if not (length > 0 and width > 0):
        raise ValueError("length and width must be positive")
    iso = _per_segment(iso_angles, segments, 0.5 * np.pi, "iso angles")
    kappa = _per_segment(curvatures, segments, 0.0, "curvatures")
    starts, ends, normals = _build(length, width, iso, kappa)
    flat_starts, flat_ends, _ = _build(length, width, iso, np.zeros(segments))
    # neighbouring rulings meet Δ·|cot θ| from the middle line, inside the strip if < width/2
    step = length / segments
    theta = 0.5 * np.pi - iso
    crossing = step * np.abs(np.cos(theta)) < 0.5 * width * np.abs(np.sin(theta))
    return Strip(
        starts=starts, ends=ends,
        starts2d=flat_starts[:, :2], ends2d=flat_ends[:, :2],
        normals=normals, planarity=quad_planarity(starts, ends), crossing=crossing,
    )
