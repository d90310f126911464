"""Sweeping a profile along a rail: rotation-minimising frames and the placed sections.

The frames are the double-reflection rotation-minimising frames of Wang, Jüttler, Zheng and
Liu (2008, "Computation of rotation minimizing frames", ACM TOG 27:1): from one station to
the next the frame is reflected in the chord's bisecting plane and then in the plane that
brings its tangent onto the next tangent. They do not twist about the rail (a profile swept
along a plane curve stays square to that plane), unlike Frenet frames, which flip at
inflections and are undefined on straight stretches. The error against the exact frame is
fourth order in the station spacing.
"""

from __future__ import annotations

import numpy as np

from .array_types import FloatArray
from .curve_base import Curve
from .vectors import perpendicular, unit


def rotation_minimising_frames(points: FloatArray, tangents: FloatArray, normal: FloatArray) -> FloatArray:
    """The normals ``(n, 3)`` of the rotation-minimising frames at ``points`` with unit
    ``tangents``, the first being ``normal`` (square to the first tangent)."""
    normals = np.empty_like(points)
    normals[0] = normal
    for i in range(len(points) - 1):  # each frame follows from the last: a recurrence
        v1 = points[i + 1] - points[i]
        c1 = v1 @ v1
        if c1 == 0.0:
            normals[i + 1] = normals[i]
            continue
        r = normals[i] - (2.0 / c1) * (v1 @ normals[i]) * v1
        t = tangents[i] - (2.0 / c1) * (v1 @ tangents[i]) * v1
        v2 = tangents[i + 1] - t
        c2 = v2 @ v2
        normals[i + 1] = r if c2 == 0.0 else r - (2.0 / c2) * (v2 @ r) * v2
    return normals


def swept_sections(rail: Curve, profile: Curve, count: int) -> list[Curve]:
    """``count`` copies of ``profile`` carried along ``rail`` at stations equally spaced by
    length: each copy keeps the place it has relative to the rail's frame at its start."""
    t = rail.divide_by_count(count - 1)
    if rail.closed:  # divide_by_count leaves out the end of a closed rail: sweep all round
        t = np.append(t, 1.0)
    points = rail.point_at(t)
    tangents = unit(rail.tangent_at(t))
    first = perpendicular(tangents[:1])[0]
    normals = rotation_minimising_frames(points, tangents, first)
    if rail.closed:
        normals = _closed_up(normals, tangents, t)
    binormals = np.cross(tangents, normals)
    start = _frame(points[0], normals[0], binormals[0], tangents[0])
    to_start = np.linalg.inv(start)
    return [profile.transformed(_frame(o, n, b, tg) @ to_start)
            for o, n, b, tg in zip(points, normals, binormals, tangents, strict=True)]


def _closed_up(normals: FloatArray, tangents: FloatArray, t: FloatArray) -> FloatArray:
    """Normals of a closed rail turned about their tangents, by a share of the angle the
    last frame lies off the first that grows evenly along the rail, so the frames meet
    again after one round (a closed space curve's rotation-minimising frames need not)."""
    end = tangents[-1]
    off = np.arctan2(np.cross(normals[-1], normals[0]) @ end, normals[-1] @ normals[0])
    angle = off * (t - t[0]) / (t[-1] - t[0])
    turned = (np.cos(angle)[:, None] * normals
              + np.sin(angle)[:, None] * np.cross(tangents, normals))  # Rodrigues: n ⟂ tangent
    return unit(turned)


def _frame(origin: FloatArray, x: FloatArray, y: FloatArray, z: FloatArray) -> FloatArray:
    """The 4 × 4 matrix taking the world frame onto (origin; x, y, z)."""
    m = np.eye(4)
    m[:3, 0], m[:3, 1], m[:3, 2], m[:3, 3] = x, y, z, origin
    return m
