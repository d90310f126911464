"""Surface coupling: the two edge curves of a developable that joins two patches along
straight edges with G1 continuity (the thesis's SurfaceCoupling, 6.2.1, Fig. 6.11).

Geometry
--------
Patch A meets the connector along its straight edge P0 → P1 (a ruling), patch B along
Q0 → Q1. At each end of such an edge the patch's curved boundary has a tangent; turned
to point *away* from the patch it is the outward tangent T. A developable has one
tangent plane along a ruling, spanned by the ruling and T at either end; the connector
joins the patch G1 exactly when its own tangent plane along the shared ruling is that
plane, i.e. when its edge curves leave P0 and P1 along T(P0) and T(P1).

Construction (the thesis's, made precise)
-----------------------------------------
1. *Pairing*: P0, P1 are joined to Q0, Q1 or to Q1, Q0, whichever pair of chords is
   shorter in total (the connector then does not twist through itself).
2. *Handles*: the tangent line P + μT lies in patch A's tangent plane, so it meets the
   line where the two patches' tangent planes intersect (the thesis's dashed line) at
   its crossing with patch B's plane: μ = n_B·(Q − P) / (n_B·T), with n_B the normal of
   B's tangent plane at the paired corner Q. The inner control point sits 2/3 of the
   way there, P + (2/3)|μ| T — with the same rule at Q this makes the cubic the degree
   elevation of the quadratic through the intersection point when both tangent lines
   meet it (coplanar chords). An intersection behind the patch (μ < 0) is mirrored to
   the outward side, as the thesis does, so the curve always leaves along +T. Where
   the tangent line runs parallel to B's plane (parallel or coincident planes) or the
   crossing is further than the chord |Q − P|, the handle is capped at |Q − P|/3 and
   |Q − P| respectively.
3. Each curve is the cubic Bézier P, P + h_P T_P, Q + h_Q T_Q, Q (a degree-3 NURBS with
   four control points). Its end tangents are exactly ±T: G1 with both patches'
   boundaries, to rounding.

The construction commutes with similarities, so two patches cut from one cone between
two sections related by a scaling about the apex (or from one cylinder between two
parallel sections) get connector curves related by the same map, and the developable
between them is a cone (cylinder) too: exactly developable. For general patches the
two cubics bound a developable only approximately; RulingDevelopable then flags the
rulings it cannot make torsal.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from .array_types import FloatArray
from .curves import NurbsCurve
from .vec_ops import cross, dot, norm, unit

if TYPE_CHECKING:
    from .surface_base import Surface

#: Corners of each edge in (u, v), in the edge's direction (numbering as Surface.edges()).
EDGE_CORNERS = {
    0: ((0.0, 0.0), (1.0, 0.0)),
    1: ((1.0, 0.0), (1.0, 1.0)),
    2: ((1.0, 1.0), (0.0, 1.0)),
    3: ((0.0, 1.0), (0.0, 0.0)),
}
#: Which first derivative crosses each edge, and its sign pointing out of the patch.
EDGE_OUTWARD = {0: ("v", -1.0), 1: ("u", 1.0), 2: ("v", 1.0), 3: ("u", -1.0)}
#: An edge counts as straight when no sample strays further than this from its chord
#: (relative to the chord's length).
STRAIGHT = 1e-7
#: |n_B·T| below this: the tangent line runs parallel to the other patch's plane.
PARALLEL = 1e-9
#: Handle length as a share of the distance to the tangent-plane intersection.
HANDLE = 2.0 / 3.0


@dataclass(frozen=True)
class EdgeRuling:
    """A straight edge of a patch, where a connector joins it."""

    start: FloatArray  #: (3,) first corner, in the edge's direction
    end: FloatArray  #: (3,) second corner
    outward: FloatArray  #: (2, 3) unit tangents of the curved boundary at the corners, pointing out
    normals: FloatArray  #: (2, 3) unit normals of the tangent planes at the corners (ruling × outward)
    warp: float  #: angle between those normals, rad, 0 to π (0 when the edge is torsal)


@dataclass(frozen=True)
class Coupling:
    """The two connector curves and what they were built from."""

    curve_a: NurbsCurve  #: from the start of edge A to its partner on B
    curve_b: NurbsCurve  #: from the end of edge A to its partner on B
    edge_a: EdgeRuling
    edge_b: EdgeRuling
    reversed_b: bool  #: True when edge A's start is joined to edge B's end
    capped: int  #: handles capped because the tangent planes (nearly) do not meet


def edge_ruling(surface: Surface, edge: int, name: str = "the surface") -> EdgeRuling:
    """The straight edge ``edge`` (0: v = 0, 1: u = 1, 2: v = 1, 3: u = 0) of a patch,
    with the outward tangents and tangent planes at its corners.

    Raises ValueError when the edge is not straight or the patch degenerates there.
    """
    if edge not in EDGE_CORNERS:
        raise ValueError(f"Edge numbers run from 0 to 3; got {edge}.")
    (u0, v0), (u1, v1) = EDGE_CORNERS[edge]
    x = np.linspace(0.0, 1.0, 17)
    samples = surface.point_at(u0 + (u1 - u0) * x, v0 + (v1 - v0) * x)
    start, end = samples[0], samples[-1]
    chord = end - start
    length = float(norm(chord))
    if length == 0.0:
        raise ValueError(f"Edge {edge} of {name} has zero length (the patch collapses to a point there).")
    offsets = samples - start
    off = offsets - np.outer(offsets @ chord / length**2, chord)
    bow = float(norm(off).max())
    if bow > STRAIGHT * length:
        raise ValueError(
            f"Edge {edge} of {name} is not straight (it bows {bow:.3g} away from its chord): "
            "couple along a straight edge, a ruling of the patch."
        )
    which, sign = EDGE_OUTWARD[edge]
    _, su, sv = surface.derivatives(np.array([u0, u1]), np.array([v0, v1]), 1)
    outward = sign * (su if which == "u" else sv)
    if np.any(norm(outward) <= 1e-12 * length):
        raise ValueError(f"The boundary of {name} stops at a corner of edge {edge} (zero tangent).")
    outward = unit(outward)
    normals = cross(np.broadcast_to(chord, (2, 3)), outward)
    if np.any(norm(normals) <= 1e-12 * length):
        raise ValueError(
            f"At a corner of edge {edge} of {name} the boundary runs along the edge: no tangent plane."
        )
    normals = unit(normals)
    # the angle between the normal vectors, 0 to π (as every warp in Torsal: developable/warp.py)
    warp = float(np.arctan2(norm(cross(normals[0], normals[1])), dot(normals[0], normals[1])))
    return EdgeRuling(start, end, outward, normals, warp)


def _handles(
    points: FloatArray, tangents: FloatArray, partners: FloatArray, normals: FloatArray
) -> tuple[FloatArray, FloatArray]:
    """Handle lengths at ``points`` (n, 3) along ``tangents`` towards the partner corners'
    tangent planes (through ``partners`` with ``normals``), and whether each was capped."""
    chord = norm(partners - points)
    across = dot(normals, tangents)
    parallel = np.abs(across) <= PARALLEL
    mu = np.abs(dot(normals, partners - points) / np.where(parallel, 1.0, across))
    far = ~parallel & (HANDLE * mu > chord)
    handle = np.where(parallel, chord / 3.0, np.minimum(HANDLE * mu, chord))
    return handle, (parallel | far).astype(float)


def couple(surface_a: Surface, edge_a: int, surface_b: Surface, edge_b: int) -> Coupling:
    """The two cubic connector curves between edge ``edge_a`` of ``surface_a`` and edge
    ``edge_b`` of ``surface_b`` (see the module docstring)."""
    a = edge_ruling(surface_a, edge_a, "SurfaceA")
    b = edge_ruling(surface_b, edge_b, "SurfaceB")
    straight = norm(b.start - a.start) + norm(b.end - a.end)
    crossed = norm(b.end - a.start) + norm(b.start - a.end)
    reversed_b = bool(crossed < straight)
    q = np.array([b.end, b.start]) if reversed_b else np.array([b.start, b.end])
    tq = b.outward[::-1] if reversed_b else b.outward
    nq = b.normals[::-1] if reversed_b else b.normals
    p = np.array([a.start, a.end])
    if np.any(norm(q - p) <= 1e-12 * max(float(norm(a.end - a.start)), 1e-300)):
        raise ValueError("The two edges share a corner: there is no gap for a connecting surface.")
    h_p, capped_p = _handles(p, a.outward, q, nq)
    h_q, capped_q = _handles(q, tq, p, a.normals)
    curves = [
        NurbsCurve(np.array([p[i], p[i] + h_p[i] * a.outward[i], q[i] + h_q[i] * tq[i], q[i]]), degree=3)
        for i in range(2)
    ]
    return Coupling(curves[0], curves[1], a, b, reversed_b, int(capped_p.sum() + capped_q.sum()))
