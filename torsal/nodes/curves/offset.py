"""Offsetting planar curves sideways within a plane.

Method
------
Every point of the curve moves by Distance along its *offset direction*
``n = unit(T_p × Z)``, where Z is the Plane's normal and ``T_p`` the curve's unit
tangent projected into the Plane. Seen from the side Z points to, n is on the
curve's right: outwards for a counter-clockwise closed curve, so a positive
Distance enlarges it. Heights above the Plane are kept.

- Lines, polylines and degree-1 NURBS curves are offset exactly: each segment
  moves sideways and neighbouring segments meet at mitred corners.
- Circles and arcs lying in a plane parallel to the Plane are offset exactly (a
  concentric circle or arc).
- Any other curve is *sampled and re-interpolated*: the exact offset points at a
  set of parameters (the curve's own adaptive tessellation, at least 64 of them)
  are joined by a chord-length cubic spline (periodic when the curve is closed);
  the exact offset at the middle of every sample interval is then measured
  against the spline (closest-point distance), the intervals that miss by more
  than the tolerance are halved, and this repeats until all are within it. The
  tolerance is ``OFFSET_TOLERANCE`` (1e-8) times the curve's size (the diagonal
  of its bounding box, or |Distance| if larger). Kinks in the curve are rounded
  over by the spline.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from torsal.engine.node import In, Node, Out
from torsal.engine.types import NUMBER, PLANE
from torsal.engine.values import WORLD_XY
from torsal.nodes.common.checks import ZERO_LENGTH, given, number
from torsal.nodes.common.convert import kernel_errors, kernel_plane
from torsal.nodes.common.values import CURVE
from torsal.nodes.geometry import curves as kernel
from torsal.nodes.geometry.curve_base import Curve
from torsal.nodes.geometry.vectors import Plane as KernelPlane
from torsal.nodes.geometry.vectors import unit

OFFSET_TOLERANCE = 1e-8
"""How far (relative to the curve's size) a sampled offset may stray from the exact one."""

MIN_SAMPLES = 64
MAX_ROUNDS = 16


class OffsetProblem(ValueError):
    """The offset cannot be made; the message says why, for a designer."""


def _size(curve: Curve, distance: float) -> float:
    box = np.asarray(curve.bounding_box(), dtype=float)
    return max(float(np.linalg.norm(box[1] - box[0])), abs(distance), 1e-300)


def _directions(tangents: np.ndarray, z: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Unit offset directions ``unit(T_p × z)`` and the lengths of the projected tangents."""
    projected = tangents - (tangents @ z)[:, None] * z
    return unit(np.cross(projected, z)), np.linalg.norm(projected, axis=1)


def offset_polyline(
    vertices: np.ndarray, closed: bool, distance: float, plane: KernelPlane
) -> np.ndarray:
    """The vertices of a polyline moved sideways by ``distance``, with mitred corners.

    ``vertices`` lists each corner once (a closed polyline does not repeat its first
    vertex). Raises :class:`OffsetProblem` where a segment is parallel to the normal
    or the polyline turns straight back on itself.
    """
    keep = np.concatenate([[True], np.any(vertices[1:] != vertices[:-1], axis=1)])
    p = vertices[keep]
    if closed and len(p) > 1 and np.array_equal(p[0], p[-1]):
        p = p[:-1]
    ends = np.roll(p, -1, axis=0) if closed else p[1:]
    segments = ends - p[: len(ends)]
    normals, lengths = _directions(segments, plane.z)
    if np.any(lengths <= ZERO_LENGTH * max(1.0, float(np.abs(p).max()))):
        i = int(np.argmin(lengths))
        raise OffsetProblem(
            f"Segment {i} runs along the Plane's normal, so it has no sideways direction to move in"
        )
    if closed:
        before, after = np.roll(normals, 1, axis=0), normals
    else:
        before = np.vstack([normals[:1], normals])
        after = np.vstack([normals, normals[-1:]])
    cosine = np.einsum("ij,ij->i", before, after)
    if np.any(cosine <= -1 + 1e-9):
        i = int(np.argmin(cosine))
        raise OffsetProblem(f"The polyline turns straight back on itself at vertex {i}")
    # offset lines of the two segments meet at  p + d (n1 + n2) / (1 + n1·n2)
    return p + distance * (before + after) / (1.0 + cosine)[:, None]


def _exact(curve: Curve, distance: float, plane: KernelPlane) -> Curve | None:
    """The exact offset of lines, polylines, circles and arcs; None for other curves."""
    if isinstance(curve, kernel.Line):
        start, end = offset_polyline(np.stack([curve.start, curve.end]), False, distance, plane)
        return kernel.Line(start, end)
    if isinstance(curve, kernel.Polyline):
        p = offset_polyline(curve.points, curve.closed, distance, plane)
        return kernel.Polyline(p, closed=curve.closed)
    if isinstance(curve, kernel.Circle | kernel.Arc) and abs(abs(curve.plane.z @ plane.z) - 1) < 1e-12:
        # counter-clockwise about the Plane's normal: the right-hand side is outwards
        radius = curve.radius + distance * float(np.sign(curve.plane.z @ plane.z))
        if radius <= 0:
            raise OffsetProblem(
                f"Offsetting a circle of radius {curve.radius:g} inwards by {abs(distance):g} "
                "leaves nothing: the distance is at least the radius"
            )
        if isinstance(curve, kernel.Circle):
            return kernel.Circle(curve.plane, radius)
        return kernel.Arc(curve.plane, radius, curve.start_angle, curve.end_angle)
    if isinstance(curve, kernel.NurbsCurve) and curve.degree == 1:
        return kernel.Polyline(
            offset_polyline(np.asarray(curve.control_points), curve.closed, distance, plane),
            closed=curve.closed,
        )
    return None


def offset_curve(curve: Curve, distance: float, plane: KernelPlane) -> tuple[Curve, list[str]]:
    """``curve`` offset sideways by ``distance`` in ``plane`` (see the module's notes).

    Returns the offset and notes for the designer (loops, non-planarity).
    """
    notes = []
    size = _size(curve, distance)
    tolerance = OFFSET_TOLERANCE * size
    start = [curve.tessellate(1e-3 * size), np.linspace(0.0, 1.0, MIN_SAMPLES + 1)]
    probe = np.unique(np.concatenate(start))
    heights = plane.signed_distance(curve.point_at(probe))
    if np.ptp(heights) > 1e-9 * size:
        notes.append(
            f"The curve is not flat in the Plane (its height above it varies by {np.ptp(heights):.3g}): "
            "each point was moved within the Plane, keeping its height"
        )
    exact = _exact(curve, distance, plane)
    if exact is not None:
        return exact, notes

    z = plane.z

    def offset_points(t: np.ndarray) -> np.ndarray:
        directions, lengths = _directions(curve.tangent_at(t), z)
        flat = lengths <= 1e-9
        if np.any(flat):
            raise OffsetProblem(
                f"At t = {t[np.argmax(flat)]:.6g} the curve runs along the Plane's normal, "
                "so it has no sideways direction to move in"
            )
        return curve.point_at(t) + distance * directions

    # d·(κN·n) ≥ 1 where the offset moves past the centre of curvature: a loop or cusp
    sideways = _directions(curve.tangent_at(probe), z)[0]
    bend = distance * np.einsum("ij,ij->i", curve.curvature_vector_at(probe), sideways)
    if np.max(bend) >= 1 - 1e-9:
        i = int(np.argmax(bend))
        radius = abs(distance) / bend[i]
        notes.append(
            f"Distance {abs(distance):g} is more than the radius of curvature ({radius:.4g}) on the "
            f"inside of the bend at t = {probe[i]:.4g}: the offset loops over itself there"
        )

    t = probe
    for _ in range(MAX_ROUNDS):
        samples = offset_points(t)
        spline = kernel.InterpolatedCurve(samples[:-1] if curve.closed else samples, closed=curve.closed)
        middles = 0.5 * (t[:-1] + t[1:])
        errors = spline.closest_point(offset_points(middles)).distances
        if errors.max() <= tolerance:
            return spline, notes
        t = np.sort(np.concatenate([t, middles[errors > tolerance]]))
    notes.append(
        f"The offset is within {errors.max():.3g} of the exact one, not the {tolerance:.3g} aimed for"
    )
    return spline, notes


class Offset(Node):
    """Move a flat curve sideways by Distance, within a Plane: a parallel curve.

    Seen from the side the Plane's normal points to, a positive Distance moves the
    curve to its right: outwards for a counter-clockwise closed curve (a circle of
    radius r becomes one of radius r + Distance), inwards for a clockwise one. A
    negative Distance moves it the other way.

    Lines, polylines, circles and arcs are offset exactly (polyline corners are
    mitred). Other curves are sampled, each sample moved exactly, and a cubic
    spline passed through them, refined until it is within 1e-8 of the curve's
    size of the exact offset everywhere; kinks get rounded. The node warns when the
    curve is not flat in the Plane (each point is then moved within the Plane,
    keeping its height) and when Distance exceeds a bend's radius, where the
    offset loops over itself.
    """

    type_id = "curves.Offset"
    nickname, aliases = "Offset", ("Offset Curve", "parallel curve")
    inputs = (
        In("Curve", CURVE, "C", "The curve to offset; it should lie flat in the Plane."),
        In("Distance", NUMBER, "D", "How far to move it, in model units; negative is to the left.",
           default=1.0),
        In("Plane", PLANE, "P", "The plane to offset in; its normal decides left and right.",
           default=WORLD_XY),
    )
    outputs = (Out("Curve", CURVE, "C", "The offset curve."),)

    def solve(self, curve: Any, distance: Any, plane: Any) -> Curve:
        c = given("Curve", curve)
        d = number("Distance", distance)
        frame = kernel_plane("Plane", plane)
        if d == 0:
            return c
        with kernel_errors():  # an OffsetProblem is a ValueError: it becomes a warning too
            result, notes = offset_curve(c, d, frame)
        for note in notes:
            self.warn(note)
        return result
