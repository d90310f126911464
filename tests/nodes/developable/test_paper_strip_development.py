"""PaperStrip's Surface is its flat quads and its Development is the same quads unfolded:
a sheet cut along the development folds into the surface's faces, every face's edge
lengths and angles kept (expected values from the face's closed form)."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
import shapely

from tests.support.direct_graphs import Chain
from torsal.app.headless import run_file
from torsal.nodes.developable.paper_strip import PaperStrip
from torsal.nodes.io.formats.cutfiles import surface_outline

LENGTH, WIDTH, SEGMENTS = 9.0, 1.2, 18
ISO = 1.35  # rad, every segment: each face is the same trapezoid-like quad
CURVATURE = [0.3, -0.2, 0.45, 0.1, -0.35, 0.25]  # per segment (the last repeats): bent both ways
EXAMPLE = Path(__file__).resolve().parents[3] / "torsal" / "resources" / "examples" / "paper-strip.graph"


def face_in_its_plane() -> np.ndarray:
    """Corners A_i, A_{i+1}, B_{i+1}, B_i of every face in the face's own frame (ruling i
    along x from its middle, the strip advancing along y): ruling i + 1 is ruling i turned
    by θ = π/2 − iso within the face, its middle a step L/S further on."""
    theta, step, half = math.pi / 2 - ISO, LENGTH / SEGMENTS, WIDTH / 2
    turned = half * np.array([math.cos(theta), math.sin(theta)])
    ahead = np.array([0.0, step])
    return np.array([[-half, 0.0], ahead - turned, ahead + turned, [half, 0.0]])


def lengths_and_angles(quads: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Four sides and two diagonals, and the four corner angles, of quads ``(k, 4, d)``."""
    sides = np.roll(quads, -1, axis=1) - quads
    diagonals = quads[:, 2:] - quads[:, :2]
    lengths = np.concatenate([np.linalg.norm(sides, axis=2), np.linalg.norm(diagonals, axis=2)], axis=1)
    into, out = -np.roll(sides, 1, axis=1), sides
    cos = np.einsum("kjd,kjd->kj", into, out) / np.linalg.norm(into, axis=2) / np.linalg.norm(out, axis=2)
    return lengths, np.arccos(np.clip(cos, -1.0, 1.0))


def solved() -> Chain:
    chain = Chain()
    chain.add("strip", PaperStrip(), Length=LENGTH, Width=WIDTH, IsoAngle=[ISO], Curvature=CURVATURE,
              Segments=SEGMENTS)
    return chain.solve()


def corners(surface) -> np.ndarray:
    """The surface's faces ``(S, 4, 3)``: its points at the corners of each u span."""
    u = np.linspace(0.0, 1.0, SEGMENTS + 1)
    a = surface.point_at(u, np.zeros_like(u))
    b = surface.point_at(u, np.ones_like(u))
    return np.stack([a[:-1], a[1:], b[1:], b[:-1]], axis=1)


def test_every_face_keeps_its_closed_form_lengths_and_angles_in_3d_and_flat():
    chain = solved()
    expected_lengths, expected_angles = lengths_and_angles(face_in_its_plane()[None])
    for port in ("Surface", "Development"):
        lengths, angles = lengths_and_angles(corners(chain.item("strip", port)))
        assert np.abs(lengths - expected_lengths).max() < 1e-13 * LENGTH, port
        assert np.abs(angles - expected_angles).max() < 1e-12, port


def test_surface_is_the_flat_quads_between_the_fold_lines():
    surface = solved().item("strip", "Surface")
    quads = corners(surface)
    t, v = np.meshgrid(np.linspace(0.0, 1.0, 7), np.linspace(0.0, 1.0, 5), indexing="ij")
    t, v = t.ravel(), v.ravel()
    u = (np.arange(SEGMENTS)[:, None] + t[None, :]) / SEGMENTS
    points = surface.point_at(u.ravel(), np.tile(v, SEGMENTS)).reshape(SEGMENTS, -1, 3)
    bilinear = ((1 - v)[:, None] * ((1 - t)[:, None] * quads[:, None, 0] + t[:, None] * quads[:, None, 1])
                + v[:, None] * ((1 - t)[:, None] * quads[:, None, 3] + t[:, None] * quads[:, None, 2]))
    assert np.abs(points - bilinear).max() < 1e-13 * LENGTH
    # and bent: the faces are not all in one plane
    normals = np.cross(quads[:, 1] - quads[:, 0], quads[:, 3] - quads[:, 0])
    normals /= np.linalg.norm(normals, axis=1, keepdims=True)
    assert np.einsum("ij,ij->i", normals[:-1], normals[1:]).min() < math.cos(0.09)


def test_development_outline_is_the_unrolled_fold_polygon():
    development = solved().item("strip", "Development")
    flat = development.ruling_lines
    polygon = shapely.Polygon(np.vstack([flat[:, 0, :2], flat[::-1, 1, :2]]))
    outline = shapely.Polygon(surface_outline(development, 1e-9).points[:, :2])
    assert polygon.is_valid and outline.is_valid
    assert outline.symmetric_difference(polygon).area < 1e-13 * polygon.area
    assert polygon.area == pytest.approx(SEGMENTS * shapely.Polygon(face_in_its_plane()).area, rel=1e-13)


def test_warp_along_every_fold_line_is_zero():
    assert max(solved().items("strip", "WarpAngles")) < 1e-14


def test_iso_mapping_of_the_paper_strip_example_has_no_area_error():
    """The spec: zero area and length error, to rounding. AreaError sums the areas of the
    Map's n = 321 strips (measured 3.7e-16); an edge keeps its length to ~n rounding units,
    the flat frames composed one after another (measured 2.4e-14)."""
    result = run_file(EXAMPLE).solver.result("unroll")
    rulings = len(result.outputs["Map"].all_items()[0].starts2d)
    assert abs(result.outputs["AreaError"].all_items()[0]) < 1e-14
    assert result.outputs["EdgeError"].all_items()[0] < 1e-15 * rulings
