"""developable.PaperStrip, solved in real graphs."""

from __future__ import annotations

import math

import numpy as np
import pytest
import shapely
import trimesh

from tests.support.direct_graphs import Chain
from torsal.nodes.developable.paper_strip import PaperStrip

#: A strip that bends and twists, differently in every segment.
ISO = [1.45, 1.5, 1.55, 1.4, 1.48]
CURVATURE = [0.25, -0.1, 0.4, 0.15, 0.3, -0.2, 0.05]


def strip(**values) -> Chain:
    chain = Chain()
    chain.add("strip", PaperStrip(), **values)
    return chain.solve()


def twisted() -> Chain:
    return strip(Length=12.0, Width=1.0, IsoAngle=ISO, Curvature=CURVATURE, Segments=40)


def lines(chain: Chain) -> np.ndarray:
    return np.array([[r.start, r.end] for r in chain.items("strip", "Rulings")])


def quad_distances(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """The four sides and two diagonals of every face A_i A_{i+1} B_{i+1} B_i: a quad with
    the same six distances is the same quad (for the flat one: unrolled without stretch)."""
    def gap(p, q):
        return np.linalg.norm(p - q, axis=1)

    return np.column_stack([gap(a[1:], a[:-1]), gap(b[1:], b[:-1]), gap(b[:-1], a[:-1]),
                            gap(b[1:], a[1:]), gap(b[1:], a[:-1]), gap(a[1:], b[:-1])])


def test_every_face_of_a_twisted_strip_is_planar_to_rounding():
    """B_{i+1} lies in the plane through A_i, B_i and A_{i+1}: measured 8.0e-16 off, for
    coordinates up to 12 (12 ε = 2.7e-15)."""
    chain = twisted()
    assert chain.result("strip").state == "ok"
    r = lines(chain)
    assert len(r) == 41
    a, b = r[:, 0], r[:, 1]
    normals = np.cross(b[:-1] - a[:-1], a[1:] - a[:-1])
    normals /= np.linalg.norm(normals, axis=1, keepdims=True)
    assert np.abs(np.einsum("ij,ij->i", b[1:] - a[:-1], normals)).max() < 4e-15


def test_a_twisted_strip_unrolls_with_zero_length_and_area_error():
    """Every face's six distances are kept in the Development (measured 1.3e-15, for
    coordinates up to 12), and the flat outline's area (shapely) is the 3D strip's area
    (trimesh, the faces split along a diagonal) to 3.3e-16."""
    chain = twisted()
    r = lines(chain)
    flat = chain.item("strip", "Development").ruling_lines
    assert np.abs(quad_distances(flat[:, 0], flat[:, 1]) - quad_distances(r[:, 0], r[:, 1])).max() < 5e-15
    outline = shapely.Polygon(np.vstack([flat[:, 0, :2], flat[::-1, 1, :2]]))
    n = len(r)
    faces = [[i, i + 1, n + i + 1] for i in range(n - 1)] + [[i, n + i + 1, n + i] for i in range(n - 1)]
    area_3d = trimesh.Trimesh(np.vstack([r[:, 0], r[:, 1]]), faces, process=False).area
    assert outline.area == pytest.approx(area_3d, rel=4e-15)


def test_development_output_is_one_simple_flat_polygon_in_the_xy_plane():
    flat = twisted().item("strip", "Development").ruling_lines
    assert np.all(flat[:, :, 2] == 0.0)
    outline = shapely.Polygon(np.vstack([flat[:, 0, :2], flat[::-1, 1, :2]]))
    assert outline.is_valid  # it does not overlap itself: one sheet can be cut


def test_rulings_are_width_long_and_the_middle_line_is_length_long():
    r = lines(twisted())
    assert np.abs(np.linalg.norm(r[:, 1] - r[:, 0], axis=1) - 1.0).max() < 1e-13
    middle = r.mean(axis=1)
    assert np.linalg.norm(np.diff(middle, axis=0), axis=1).sum() == pytest.approx(12.0, rel=1e-14)


def test_constant_curvature_2pi_over_segments_rolls_a_closed_cylinder():
    chain = strip(Length=2 * math.pi, Width=1.0, IsoAngle=[math.pi / 2],
                  Curvature=[2 * math.pi / 12], Segments=12)
    r = lines(chain)
    assert np.abs(r[0] - r[-1]).max() < 1e-12
    assert max(chain.items("strip", "WarpAngles")) < 1e-12


def test_flat_strip_with_parallel_rulings_unrolls_to_a_length_by_width_rectangle():
    flat = strip(Length=5.0, Width=2.0, IsoAngle=[math.pi / 2], Curvature=[0.0], Segments=4)
    development = flat.item("strip", "Development")
    assert development.area() == pytest.approx(10.0, rel=1e-14)


def test_rulings_leaning_too_far_cross_and_the_node_warns():
    chain = strip(Length=1.0, Width=4.0, IsoAngle=[0.3], Curvature=[0.1], Segments=10)
    assert chain.result("strip").state == "warning"
    assert chain.texts("strip") == [
        "Rulings cross inside the strip in 10 of 10 segments (first: segment 0): the IsoAngle leans "
        "them too far for the segment length; raise IsoAngle towards π/2, narrow the strip or use "
        "fewer segments"
    ]


def test_extra_per_segment_values_are_reported_unused():
    chain = strip(Segments=2, Curvature=[0.1, 0.2, 0.3])
    assert chain.texts("strip") == ["Curvature has 3 values for 2 segments: the last 1 are not used"]


@pytest.mark.parametrize(
    ("values", "message"),
    [
        ({"Segments": 0}, "Segments must be at least 1, not 0"),
        ({"Width": -1.0}, "Width must be a positive length, not -1"),
        ({"Length": 0.0}, "Length must be a positive length, not 0"),
    ],
)
def test_invalid_inputs_warn_with_what_to_change(values, message):
    chain = strip(**values)
    assert chain.result("strip").state == "warning"
    assert chain.texts("strip") == [message]
