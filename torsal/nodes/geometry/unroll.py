"""Unrolling ruled strips into the plane: the kernel of IsoMapping.

A strip of n rulings (A_i → B_i) is a chain of n − 1 quads. Each quad is split into
two triangles along its shorter diagonal and the triangles are laid flat one after
another, every triangle congruent to its 3D original and all of them oriented the
same way (the 2D image of the normal (A_{i+1} − A_i) × (B_i − A_i) points to +z).
So every edge — rulings, both rails, diagonals — keeps its 3D length to rounding.
For a developable input the quads are (nearly) planar and the unfolding is an
isometry; for a warped ruled surface (a hyperbolic paraboloid) the rulings and rails
still keep their lengths but the area does not, and :attr:`Development.area_error`
says by how much.

How the recurrence is vectorised. Give ruling i its own 2D frame: A_i at the origin,
B_i at (0, |B_i − A_i|), the strip continuing towards +x. In that frame the next
ruling's end points follow from the quad's own two triangles — local 3D geometry
only, computed for all quads at once. Frame i + 1 then sits in frame i at the
rigid motion z ↦ A'_{i+1} + r_i·z (complex numbers: r_i is the unit rotation taking
+y onto the placed ruling). Composing rigid motions is a cumulative product of the
rotations and a cumulative sum of the rotated offsets — two O(n) numpy scans, no
Python loop. Lengths stay exact because each edge is the image of a local vector
under one unit rotation (renormalised after the product).

Smooth input. Unrolling n chords of a smooth developable is accurate to
O(1/n²): a full cylinder cut into 100 strips unrolls 1.6e-4 narrower than 2πr,
because every strip is as wide as its chord. :func:`unroll_surface` therefore
samples ``subdivisions`` rulings per segment from the smooth surface (error / 64 at
the default 8) and takes the 3D area from the surface itself.

The map that carries points and polylines between a development and its strip
(:class:`~.development_map.DevelopmentMap`) is in :mod:`.development_map`.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike, NDArray

from torsal.nodes.geometry.array_types import FloatArray, IntArray
from torsal.nodes.geometry.vec_ops import bounds as coordinate_bounds
from torsal.nodes.geometry.vec_ops import cross, extent, linalg_norm
from torsal.nodes.geometry.vec_ops import dot as _dot

from .area import gauss_legendre_01
from .counts import segment_count
from .development_map import DevelopmentMap, is_simple, merge_repeats, rotate_about
from .edge_sampling import Samples, edge_parameters, edge_subdivisions
from .local_frame import LocalFrame
from .watch import watch_check

if TYPE_CHECKING:
    from .surface_base import Surface


#: Diagonals within this relative margin count as equally long; the first one
#: (A_{i+1} to B_i) is then taken, so symmetric strips triangulate uniformly.
DIAGONAL_TIE = 1e-12

#: Edges shorter than this share of the strip's size count as collapsed (a cone's apex
#: edge): their length error is measured against the strip's size, not their own length.
EDGE_COLLAPSED = 1e-9

#: Gauss–Legendre points per direction for the area of a bilinear quad.
QUAD_ORDER = 8


def _as_rulings(starts: ArrayLike, ends: ArrayLike) -> tuple[FloatArray, FloatArray]:
    a = np.asarray(starts, dtype=float)
    b = np.asarray(ends, dtype=float)
    if a.ndim != 2 or a.shape[1] != 3 or a.shape != b.shape:
        raise ValueError("starts and ends must be (n, 3) arrays of the same shape")
    if len(a) < 2:
        raise ValueError("a strip needs at least two rulings")
    if not (np.all(np.isfinite(a)) and np.all(np.isfinite(b))):
        raise ValueError("ruling end points must be finite")
    return a, b


def bilinear_quad_areas(starts: ArrayLike, ends: ArrayLike, order: int = QUAD_ORDER) -> FloatArray:
    """Area of each ruled quad S(a, b) = lerp(lerp(A_i, A_{i+1}, a), lerp(B_i, B_{i+1}, a), b).

    This is the straight-line loft between consecutive rulings (a piece of a hyperbolic
    paraboloid, or a plane for a planar quad), integrated with an ``order``² Gauss rule:
    exact for planar convex quads (|S_a × S_b| is then bilinear) and ~1e-12 relative
    for warped ones.
    """
    a, b = _as_rulings(starts, ends)
    x, w = gauss_legendre_01(order)
    da, db = np.diff(a, axis=0), np.diff(b, axis=0)  # rail steps
    ra, rb = b[:-1] - a[:-1], b[1:] - a[1:]  # rulings i and i + 1
    # S_a = (1 − b)·dA + b·dB and S_b = (1 − a)·r_i + a·r_{i+1}, so S_a × S_b is bilinear
    # in (a, b) with the four corner values below: evaluate it at the Gauss nodes.
    corners = np.stack([cross(da, ra), cross(da, rb), cross(db, ra), cross(db, rb)], 1)
    aa, bb = np.meshgrid(x, x, indexing="ij")
    aa, bb = aa.ravel(), bb.ravel()
    basis = np.column_stack([(1 - bb) * (1 - aa), (1 - bb) * aa, bb * (1 - aa), bb * aa])
    normal = basis @ corners  # (quads, nodes, 3)
    return np.sqrt(np.square(normal).sum(axis=2)) @ np.outer(w, w).ravel()


# --------------------------------------------------------------------------- development


@dataclass(frozen=True)
class Development:
    """A ruled strip unrolled into the XY plane, with its accuracy figures.

    ``starts2d``/``ends2d`` are the images of the rulings. ``area_3d`` is the area of
    the 3D surface (the bilinear loft of the rulings, or the smooth surface's area
    when one was given), ``area_2d`` the area of the development. ``area_error`` is
    (area_2d − area_3d) / area_3d, signed. ``max_edge_length_error`` is the largest
    relative change of any triangle edge (rulings, rails and diagonals; a collapsed
    edge, like those at a cone's apex, relative to the strip's size); it is at
    rounding level by construction. ``hinge_angles`` (rad, one per quad) is the fold
    between each quad's two triangles: zero for a planar quad, so it shows where a
    strip is not developable. ``stride`` marks every stride-th ruling as one the user
    asked for (see :func:`unroll_surface`), unless ``requested`` lists them (a strip
    sampled more finely in some segments than in others). ``map`` triangulates every
    unrolled ruling, or only every few of them where the edges needed far more rulings
    than a panel layout does (:func:`unroll_surface`: a full cone's rim): its vertices
    are then a subset of these, laid where the fine unrolling put them, and
    :attr:`outline` is its outline. ``edge_shortfall`` is how much shorter than the
    3D edges the flat ones are estimated to be, relative to the strip's size (the
    chords' Richardson estimate, :mod:`.edge_sampling`; NaN where none was made);
    ``edge_capped`` says the sampling stopped at its cap of rulings short of the
    tolerance asked for, where that estimate may be low.
    """

    starts2d: FloatArray
    ends2d: FloatArray
    starts3d: FloatArray
    ends3d: FloatArray
    area_3d: float
    area_2d: float
    area_error: float
    max_edge_length_error: float
    hinge_angles: FloatArray
    map: DevelopmentMap = field(repr=False)
    stride: int = 1
    requested: IntArray | None = field(default=None, repr=False)
    edge_shortfall: float = float("nan")
    edge_capped: bool = False

    @property
    def rulings2d(self) -> tuple[FloatArray, FloatArray]:
        """Starts and ends of the requested rulings (every ``stride``-th one, or ``requested``)."""
        if self.requested is not None:
            return self.starts2d[self.requested], self.ends2d[self.requested]
        return self.starts2d[:: self.stride], self.ends2d[:: self.stride]

    @property
    def requested_rulings(self) -> IntArray:
        """The indices of the requested rulings among all those unrolled."""
        if self.requested is not None:
            return self.requested
        return np.arange(0, len(self.starts2d), self.stride)

    @property
    def outline(self) -> FloatArray:
        """The boundary polygon ``(m, 2)``: the starts forwards, then the ends backwards
        (m ≤ 2n: a run of points within :data:`.development_map.REPEATED` of the size of each other, as at
        a fan's apex, is one vertex, so a simple development has a valid outline)."""
        vertices, n = self.map.vertices2d, self.map.n  # the map's rulings (see :attr:`map`)
        return merge_repeats(np.vstack([vertices[:n], vertices[n:][::-1]]))

    @property
    def bounds(self) -> FloatArray:
        """Bounding rectangle ``[xmin, ymin, xmax, ymax]`` of the development."""
        pts = np.vstack([self.starts2d, self.ends2d])
        return np.concatenate(coordinate_bounds(pts))

    @property
    def overlaps(self) -> bool:
        """True when the development overlaps itself in the plane (a tangent developable
        of more than a full turn): it cannot be cut from one sheet, and plane → surface
        mapping is ambiguous where it overlaps."""
        return not is_simple(self.outline)

    @property
    def centroid(self) -> FloatArray:
        """Area centroid of the development ``(2,)``."""
        tri = self.map.vertices2d[self.map.triangles]
        areas = 0.5 * self.map._area2
        return (tri.mean(axis=1) * areas[:, None]).sum(axis=0) / areas.sum()

    def moved(self, offset: ArrayLike) -> Development:
        """The development of the same strip moved by ``offset`` in 3D: the flat side and
        every figure stay the same."""
        shift = np.asarray(offset, dtype=float).reshape(3)
        return replace(self, starts3d=self.starts3d + shift, ends3d=self.ends3d + shift,
                       map=self.map.moved(shift))

    def rotated(self, angle_deg: float, pivot: ArrayLike | None = None) -> Development:
        """The development turned counter-clockwise by ``angle_deg`` about ``pivot``
        (default: its area centroid). The 3D side and every figure stay the same."""
        centre = self.centroid if pivot is None else np.asarray(pivot, dtype=float)
        angle = np.deg2rad(angle_deg)
        return replace(
            self,
            starts2d=rotate_about(self.starts2d, angle, centre),
            ends2d=rotate_about(self.ends2d, angle, centre),
            map=self.map.rotated(angle, centre),
        )


def _place(x2: NDArray, y2: NDArray, along: FloatArray, height: FloatArray) -> NDArray:
    """2D points (complex) ``along`` the edge x→y from x and ``height`` to its left."""
    edge = y2 - x2
    return x2 + edge / np.abs(edge) * (along + 1j * height)


def _local(x3: FloatArray, y3: FloatArray, p3: FloatArray) -> tuple[FloatArray, FloatArray]:
    """Coordinates of p over the edge x→y of triangle (x, y, p): the projection along
    the edge and the (unsigned) distance from its line."""
    edge, w = y3 - x3, p3 - x3
    length = linalg_norm(edge)
    return _dot(w, edge) / length, linalg_norm(cross(edge, w)) / length


def unroll_rulings(
    starts: ArrayLike, ends: ArrayLike, area_3d: float | None = None
) -> Development:
    """Unroll the ruled strip through n rulings ``starts[i] → ends[i]`` into the plane.

    Ruling 0 is laid from the origin up the +y axis and the strip continues towards
    +x (the side of ruling 1). Every quad is cut along its shorter diagonal and both
    triangles are laid down congruent to their 3D originals (see the module
    docstring for the vectorised recurrence). ``area_3d`` overrides the 3D area the
    development is compared with (pass the smooth surface's area); by default it is
    the area of the bilinear loft of the rulings (:func:`bilinear_quad_areas`).

    Example:
        >>> import numpy as np
        >>> phi = np.linspace(0, np.pi, 5)   # half a cylinder of radius 1, height 2
        >>> base = np.column_stack([np.cos(phi), np.sin(phi), 0 * phi])
        >>> dev = unroll_rulings(base, base + [0, 0, 2])
        >>> np.round(dev.ends2d[-1], 6).tolist()   # 4 chords of length 2 sin(π/8)
        [3.061467, 2.0]
    """
    a, b = _as_rulings(starts, ends)
    n = len(a)
    ruling = b - a
    length = linalg_norm(ruling)
    size = float(extent(np.vstack([a, b])).max())
    zero = length <= 1e-12 * size
    tip_start, tip_end = bool(zero[0]) and n > 2, bool(zero[-1]) and n > 2
    inner = zero.copy()
    inner[0] &= not tip_start
    inner[-1] &= not tip_end
    if np.any(inner):
        bad = np.flatnonzero(inner)
        raise ValueError(f"ruling {int(bad[0])} has zero length: a strip cannot be unrolled "
                         f"through a point ({len(bad)} such rulings)")
    if tip_start or tip_end:  # the strip tapers to a point: unroll the rest, then its tips
        return _with_tips(a, b, tip_start, tip_end, area_3d)
    starts2d, ends2d, first = _unrolled(a, b, length)
    _look()
    return _development(a, b, starts2d, ends2d, first, area_3d)


def _look() -> None:
    """A look at the cancel token (see :mod:`.watch`): between the stages of an unrolling,
    each 5-20 ms at 16,000 rulings."""
    check = watch_check()
    if check:
        check()


def _with_tips(
    a: FloatArray, b: FloatArray, tip_start: bool, tip_end: bool, area_3d: float | None
) -> Development:
    """Unroll a strip whose first and/or last ruling has zero length (its curves meet
    there): the rulings between are unrolled as usual and each tip is laid down as the
    corner of its triangle with the neighbouring ruling, away from the strip."""
    core = slice(1 if tip_start else 0, len(a) - 1 if tip_end else len(a))
    ca, cb = a[core], b[core]
    starts2d, ends2d, _ = _unrolled(ca, cb, linalg_norm(cb - ca))
    z_a = starts2d[:, 0] + 1j * starts2d[:, 1]
    z_b = ends2d[:, 0] + 1j * ends2d[:, 1]
    parts_a, parts_b = [z_a], [z_b]
    if tip_start:  # left of the first ruling: the strip runs on to its right
        u, h = _local(a[1:2], b[1:2], a[0:1])
        tip = _place(z_a[:1], z_b[:1], u, h)
        parts_a.insert(0, tip)
        parts_b.insert(0, tip)
    if tip_end:  # right of the last ruling
        u, h = _local(a[-2:-1], b[-2:-1], a[-1:])
        tip = _place(z_a[-1:], z_b[-1:], u, -h)
        parts_a.append(tip)
        parts_b.append(tip)
    za, zb = np.concatenate(parts_a), np.concatenate(parts_b)
    first = linalg_norm(a[1:] - b[:-1]) <= linalg_norm(b[1:] - a[:-1]) * (
        1 + DIAGONAL_TIE
    )
    starts2d = np.column_stack([za.real, za.imag])
    ends2d = np.column_stack([zb.real, zb.imag])
    return _development(a, b, starts2d, ends2d, first, area_3d)


def _unrolled(a: FloatArray, b: FloatArray, length: FloatArray) -> tuple[FloatArray, FloatArray, NDArray]:
    """The 2D ruling ends of a strip with no zero-length ruling, and each quad's diagonal."""
    n = len(a)
    a0, a1, b0, b1 = a[:-1], a[1:], b[:-1], b[1:]
    first = linalg_norm(a1 - b0) <= linalg_norm(b1 - a0) * (1 + DIAGONAL_TIE)
    col = first[:, None]

    # Frame i: A_i = 0, B_i = i·|r_i|. The first new vertex sits left of B_i → A_i,
    # the second left of the diagonal (B_i → A_{i+1}, or B_{i+1} → A_i).
    top = 1j * length[:-1]
    origin = np.zeros(n - 1, dtype=complex)
    p1 = np.where(col, a1, b1)
    u1, h1 = _local(b0, a0, p1)
    q1 = _place(top, origin, u1, h1)
    x3, y3, p2 = np.where(col, b0, p1), np.where(col, p1, a0), np.where(col, b1, a1)
    u2, h2 = _local(x3, y3, p2)
    q2 = _place(np.where(first, top, q1), np.where(first, q1, origin), u2, h2)
    next_a, next_b = np.where(first, q1, q2), np.where(first, q2, q1)

    # Compose the frames: R_{i+1} = R_i·r_i, t_{i+1} = t_i + R_i·A'_{i+1}.
    step = (next_b - next_a) / 1j
    rot = np.concatenate([[1.0 + 0j], np.cumprod(step / np.abs(step))])
    rot /= np.abs(rot)
    shift = np.concatenate([[0j], np.cumsum(rot[:-1] * next_a)])
    za, zb = shift, shift + rot * 1j * length
    starts2d = np.column_stack([za.real, za.imag])
    ends2d = np.column_stack([zb.real, zb.imag])
    return starts2d, ends2d, first


def _development(
    a: FloatArray, b: FloatArray, starts2d: FloatArray, ends2d: FloatArray, first: NDArray,
    area_3d: float | None,
) -> Development:
    """The :class:`Development` of the strip ``a → b`` laid down at ``starts2d → ends2d``."""
    n = len(a)
    vertices2d, vertices3d = np.vstack([starts2d, ends2d]), np.vstack([a, b])
    tmap = DevelopmentMap(vertices2d, vertices3d, first)
    _look()
    t2, t3 = vertices2d[tmap.triangles], vertices3d[tmap.triangles]
    # each triangle's edges, from each corner to the next
    edges2d = linalg_norm(t2 - t2.take(_NEXT_CORNER, axis=1))
    edges3d = linalg_norm(t3 - t3.take(_NEXT_CORNER, axis=1))
    diameter = float(np.linalg.norm(extent(vertices3d)))
    scale = np.where(edges3d > EDGE_COLLAPSED * diameter, edges3d, diameter)
    edge_error = float(np.max(np.abs(edges2d - edges3d) / scale))
    _look()

    area_2d = float(0.5 * tmap._area2.sum())
    area3 = float(bilinear_quad_areas(a, b).sum()) if area_3d is None else float(area_3d)
    normals = cross(t3[:, 1] - t3[:, 0], t3[:, 2] - t3[:, 0]).reshape(n - 1, 2, 3)
    hinge = np.arctan2(linalg_norm(cross(normals[:, 0], normals[:, 1])),
                       _dot(normals[:, 0], normals[:, 1]))
    # a quad with a collapsed edge (in a fan) is one triangle: it does not fold
    hinge = np.where(linalg_norm(normals).min(axis=1) > EDGE_COLLAPSED * diameter**2, hinge, 0.0)
    return Development(
        starts2d=starts2d, ends2d=ends2d, starts3d=a, ends3d=b,
        area_3d=area3, area_2d=area_2d,
        area_error=(area_2d - area3) / area3 if area3 > 0 else float("nan"),
        max_edge_length_error=edge_error, hinge_angles=hinge, map=tmap,
    )


#: Each corner's next one, round a triangle.
_NEXT_CORNER = np.array([1, 2, 0])


def unroll_surface(
    surface: Surface, segments: int, subdivisions: int = 8, edge_tolerance: float | None = None
) -> Development:
    """Unroll a smooth ruled surface: IsoMapping's accurate path.

    ``segments + 1`` rulings are the ones the user sees; between each pair
    ``subdivisions − 1`` more are sampled from the surface itself, so the chords the
    strip is made of hug the surface and the O(1/n²) chord error shrinks by
    ``subdivisions²`` (area error of a full cone at 100 segments: 2.9e-4 → 4.5e-6). The 3D area is the
    surface's own (exact cubature). ``Development.rulings2d`` picks the user's rulings.

    With ``edge_tolerance`` (relative to the strip's size) more rulings are sampled until
    both flat edges — chord polylines congruent to the 3D ones — are as long as the 3D
    edges to that tolerance (:func:`.edge_sampling.edge_subdivisions`, then
    :func:`.edge_sampling.edge_parameters`; a ruling at every corner of an edge besides):
    then two strips that share a curve have flat edges of the same length (their seam
    closes), whatever stations each strip samples the curve at. Where the edges are
    curved all along (a full cone's rim, tens of thousands of rulings), the
    development's :attr:`~Development.map` keeps ``subdivisions`` rulings per segment of
    them, at the places the fine unrolling laid them: a panel layout carried through it
    costs what it did at ``subdivisions``, and its flat corners sit on the accurate
    development.

    At site coordinates the rulings are sampled on the surface moved to its own anchor
    (:mod:`.local_frame`) and the development's 3D side is moved back: the flat shape is
    the one the surface unrolls to at the origin, not one whose quads turn by the
    rounding of their corners' world coordinates.

    Raises ValueError("surface has no straight rulings") for a non-ruled surface.
    """
    segments, subdivisions = segment_count(segments), segment_count(subdivisions, "Subdivisions")
    # sampled at site coordinates, each ruling's ends round to the coordinates' ulp (1.2e-7 m
    # at 1e9 m) and the quads, laid one after another, turn by that over their short rails:
    # sampled about the surface's own anchor they are as exact as at the origin
    frame = LocalFrame.around(surface)
    world, surface = surface, frame.to_local(surface)
    requested = u = panelled = None
    error, capped = float("nan"), False
    if edge_tolerance is None:
        rulings = surface.rulings(segments * subdivisions + 1)
    else:
        samples = Samples(surface)
        subdivisions, sampling, error = edge_subdivisions(samples, segments, subdivisions, edge_tolerance)
        if sampling.grid is not None:  # evenly spaced, with the rulings at the edges' kinks
            requested = sampling.grid[::subdivisions]
        if not error <= edge_tolerance:  # (NaN too) evenly spaced rulings did not get there
            plan = edge_parameters(samples, segments, subdivisions, edge_tolerance)
            if plan is not None:
                sampling, requested, panelled, error, capped = plan
        rulings = sampling.rulings
        if requested is not None:
            u = sampling.u
    # (the world surface's: a surface given by a function of world coordinates knows the
    # noise of its differenced derivatives only there, and its cubature stops at it)
    area_3d = world.area()
    _look()
    development = unroll_rulings(rulings[:, 0], rulings[:, 1], area_3d=area_3d)
    _look()
    upright = _upright(development, surface, u)
    _look()
    if panelled is not None:
        upright = replace(upright, map=_map_through(upright, panelled))
    if not frame.is_world:
        upright = upright.moved(frame.origin)
    return replace(upright, stride=subdivisions, requested=requested, edge_shortfall=error,
                   edge_capped=capped)


def _map_through(development: Development, keep: IntArray) -> DevelopmentMap:
    """The map of ``development`` triangulating only the rulings ``keep``, each quad cut
    along its shorter 3D diagonal as :func:`unroll_rulings` cuts them."""
    a3, b3 = development.starts3d[keep], development.ends3d[keep]
    first = np.linalg.norm(a3[1:] - b3[:-1], axis=1) <= np.linalg.norm(b3[1:] - a3[:-1], axis=1) * (
        1 + DIAGONAL_TIE
    )
    flat = np.vstack([development.starts2d[keep], development.ends2d[keep]])
    return DevelopmentMap(flat, np.vstack([a3, b3]), first)


def _upright(development: Development, surface: Surface, u: FloatArray | None = None) -> Development:
    """The development turned so that the ruling laid up the +Y axis (the first one with
    a length) runs exactly along the surface's own ruling direction there.

    The unrolling sees that ruling only through its two end points. Far from the origin
    they are rounded to the coordinates' ulp (2.3e-10 m at 2e6 m, 1.2e-7 m at 1e9 m),
    and where the first ruling is short — a strip tapering to a point, whose first ruling
    after the tip is 1 cm long on a 140 m roof — its direction, and with it the whole
    development's, turns by that over its length (6e-9 rad at 2e6 m, 3e-6 at 1e9 m), a
    rigid turn of the shape; the surface's derivative along the ruling is evaluated
    relative to the surface and carries no such error. The turn between the two, in the
    plane of the first triangle with area, is undone about the origin. ``u``: the
    rulings' parameters, when they are not evenly spaced."""
    laid = (development.starts2d == 0.0).all(axis=1) & (development.ends2d[:, 1] > 0.0)
    k = int(np.argmax(laid))
    m = development.map
    later = m.proper[m.proper >= 2 * k]
    if not laid[k] or later.size == 0:
        return development
    t = float(u[k]) if u is not None else k / (len(development.starts2d) - 1)
    if surface.ruling_direction == "v":
        along = surface.derivatives(t, 0.0, 1)[2][0]
    else:
        along = surface.derivatives(0.0, t, 1)[1][0]
    up = development.ends3d[k] - development.starts3d[k]
    # +X in the plane is up × the normal of the triangles, which all face +Z there (an
    # error in the normal tilts this out of the plane: it changes the turn to second order)
    corners = m.vertices3d[m.triangles[later[0]]]
    across = cross(up, cross(corners[1] - corners[0], corners[2] - corners[0]))
    scale = float(np.linalg.norm(up) * np.linalg.norm(across) * np.linalg.norm(along))
    if scale == 0.0 or not np.isfinite(scale):
        return development
    up, across = up / np.linalg.norm(up), across / np.linalg.norm(across)
    turn = float(np.arctan2(_dot(along, across), _dot(along, up)))
    if turn == 0.0 or abs(turn) > UPRIGHT_TURN:
        return development
    return development.rotated(float(np.rad2deg(turn)), np.zeros(2))


#: Largest turn (rad) :func:`_upright` undoes: the rounding of site coordinates turns a
#: development by microradians; more means the surface's parameter does not follow its
#: rulings, and the unrolled rulings stand as they are.
UPRIGHT_TURN = 1e-3
