"""developable.Rationalise on a trimmed design: the strips are made inside the trim.

The design is a saddle z = x²/24 − 3y²/32 over 12 × 8 m as a Rhino NURBS surface made with
rhino3dm (it is quadratic, so one biquadratic Bézier patch is exactly it), written to a
``.3dm`` and read by Import3dm; a freeform trim loop (a wavy oval, not convex) is laid on it
in (u, v) (rhino3dm cannot make a trimmed freeform face: it trims planes only). Every check
is independent of the kernel: distances from the design and the feet of the closest points
by the Newton iteration of :mod:`tests.support.freeform_designs` on the closed form; inside the
trim by shapely on the loop; distances from the strips by trimesh's closest point on dense
triangles of them; the exported faces read back with rhino3dm.
"""

from __future__ import annotations

import itertools
import uuid

import numpy as np
import pytest
import rhino3dm as rh
import shapely
import trimesh
from scipy.spatial import cKDTree

from tests.nodes.io.test_rhino_strips import corners, normal_twist, surface_of
from tests.support.freeform_designs import Design
from tests.support.node_helpers import allowed, run, texts, tree
from tests.support.strip_grids import grid, items
from torsal.engine.solver import OK
from torsal.nodes.developable.rationalise import Rationalise
from torsal.nodes.geometry.trimmed_surface import TrimmedSurface
from torsal.nodes.io.rhino import Export3dm, Import3dm

TOL = 0.02


def _saddle(x, y):
    zero = 0 * x
    return x * x / 24 - 3 * y * y / 32, x / 12, -3 * y / 16, 1 / 12 + zero, zero, -3 / 16 + zero


SADDLE = Design("saddle", _saddle, (-6.0, 6.0), (-4.0, 4.0))


def blob(count: int = 193) -> np.ndarray:
    """The trim loop in (u, v): a wavy oval (not convex)."""
    angle = np.linspace(0.0, 2.0 * np.pi, count)
    return np.column_stack([0.5 + 0.4 * np.cos(angle), 0.5 + 0.42 * np.sin(angle) + 0.05 * np.sin(3 * angle)])


def saddle_3dm(path) -> str:
    """The saddle as one biquadratic Bézier patch, by its polar form: x and y are linear in
    u and v, and z's control values are f's blossom at (x_i, x_i'), (y_j, y_j')."""
    (x0, x1), (y0, y1) = SADDLE.x, SADDLE.y
    pairs_x = [(x0, x0), (x0, x1), (x1, x1)]
    pairs_y = [(y0, y0), (y0, y1), (y1, y1)]
    surface = rh.NurbsSurface.Create(3, False, 3, 3, 3, 3)
    for i, (xa, xb) in enumerate(pairs_x):
        for j, (ya, yb) in enumerate(pairs_y):
            z = xa * xb / 24 - 3 * ya * yb / 32  # x² and y² in the polar form
            surface.Points[(i, j)] = rh.Point4d((xa + xb) / 2, (ya + yb) / 2, z, 1.0)
    for knots in (surface.KnotsU, surface.KnotsV):
        for k, value in enumerate([0.0, 0.0, 1.0, 1.0]):
            knots[k] = value
    model = rh.File3dm()
    model.Settings.ModelUnitSystem = rh.UnitSystem.Meters
    attributes = rh.ObjectAttributes()
    attributes.Id = uuid.UUID(int=1)
    model.Objects.AddSurface(surface, attributes)
    assert model.Write(str(path), 7)
    return str(path)


@pytest.fixture(scope="module")
def solved(tmp_path_factory):
    folder = tmp_path_factory.mktemp("trim")
    imported = run(Import3dm(), Path=saddle_3dm(folder / "saddle.3dm"))
    (surface,) = imported.outputs["Surfaces"].all_items()
    design = TrimmedSurface(surface, blob())
    return folder, run(Rationalise(), Surface=tree({(0,): [design]}), Tolerance=TOL, MaxStrips=40)


def feet(points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Each point's closest point on the saddle, as (u, v) of the patch, and its distance."""
    (x0, x1), (y0, y1) = SADDLE.x, SADDLE.y
    x, y, distance = SADDLE.nearest(points)
    return np.column_stack([(x - x0) / (x1 - x0), (y - y0) / (y1 - y0)]), distance


def loop_points(count: int = 2000) -> np.ndarray:
    """Dense points along the trim loop, on the design (its polygon in (u, v), as read)."""
    ring = shapely.LinearRing(blob())
    at = np.linspace(0, 1, count)
    uv = shapely.get_coordinates(shapely.line_interpolate_point(ring, at, normalized=True))
    (x0, x1), (y0, y1) = SADDLE.x, SADDLE.y
    return SADDLE.points(x0 + uv[:, 0] * (x1 - x0), y0 + uv[:, 1] * (y1 - y0))


def strip_mesh(strip, per: int = 16, nv: int = 25) -> trimesh.Trimesh:
    """Triangles of ``per`` samples between consecutive rulings (a cut strip's end, where the
    trim runs nearly along its rulings, is a short stretch of its parameter) by ``nv`` across."""
    rulings = np.asarray(strip.ruling_parameters, dtype=float)
    steps = np.linspace(0.0, 1.0, per + 1)[:-1]
    u = np.concatenate([(rulings[:-1, None] + np.diff(rulings)[:, None] * steps).ravel(), rulings[-1:]])
    uu, vv = np.meshgrid(u, np.linspace(0.0, 1.0, nv), indexing="ij")
    points = strip.point_at(uu.ravel(), vv.ravel()).reshape(len(u), nv, 3)
    nu = len(u)
    a = (np.arange(nu - 1)[:, None] * nv + np.arange(nv - 1)).ravel()
    faces = np.concatenate([np.stack([a, a + nv, a + nv + 1], 1), np.stack([a, a + nv + 1, a + 1], 1)])
    return trimesh.Trimesh(points.reshape(-1, 3), faces, process=False)


def distance_to_mesh(mesh: trimesh.Trimesh, points: np.ndarray, nearest: int = 16) -> np.ndarray:
    """Each point's distance to the mesh: trimesh's closest point on the triangles whose
    centres are nearest it."""
    _, index = cKDTree(mesh.triangles_center).query(points, k=nearest)
    query = np.repeat(points, nearest, axis=0)
    found = trimesh.triangles.closest_point(mesh.triangles[index.ravel()], query)
    return np.linalg.norm(found - query, axis=1).reshape(len(points), nearest).min(axis=1)


def test_the_strips_lie_within_the_tolerance_of_the_design_and_inside_its_trim(solved):
    _, result = solved
    assert result.state == OK, texts(result)
    strips = items(result, "Strips")
    assert strips
    points = np.concatenate([grid(s, 121, 21).reshape(-1, 3) for s in strips])
    uv, distance = feet(points)
    assert distance.max() <= TOL  # measured 1.76 cm
    # every point's foot lies inside the trim, or the point is within the tolerance of the trim
    inside = shapely.contains_xy(shapely.Polygon(blob()), uv[:, 0], uv[:, 1])
    loop = loop_points()
    outside = points[~inside]
    near = np.linalg.norm(outside[:, None] - loop[None], axis=2).min(axis=1) if len(outside) else np.zeros(0)
    assert near.max(initial=0.0) <= TOL
    assert inside.mean() >= 0.9  # the strips keep inside (their cut edges reach 1 cm over the trim)
    # the node's certified deviation bounds the dense independent samples
    deviation = items(result, "Deviation")
    assert max(deviation) >= distance.max() and max(deviation) <= TOL


def test_the_trim_loop_is_covered_within_the_tolerance(solved):
    _, result = solved
    loop = loop_points()
    gaps = np.full(len(loop), np.inf)
    for strip in items(result, "Strips"):
        gaps = np.minimum(gaps, distance_to_mesh(strip_mesh(strip), loop))
    assert gaps.max() <= TOL  # measured 1.6 cm (the strips lie up to 1.76 cm off the design)


def test_the_strips_area_is_the_trimmed_designs(solved):
    _, result = solved
    total = 0.0
    for strip in items(result, "Strips"):
        mesh = strip_mesh(strip)
        total += float(mesh.area)
    # the trimmed saddle's area from the closed form, on the loop's polygon in (u, v)
    (x0, x1), (y0, y1) = SADDLE.x, SADDLE.y
    u, v = np.meshgrid(np.linspace(0, 1, 801), np.linspace(0, 1, 801), indexing="ij")
    x, y = x0 + u * (x1 - x0), y0 + v * (y1 - y0)
    element = np.sqrt(1 + SADDLE.height(x, y, 1) ** 2 + SADDLE.height(x, y, 2) ** 2) * (x1 - x0) * (y1 - y0)
    keep = shapely.contains_xy(shapely.Polygon(blob()), u, v)
    area = float((element * keep).sum() / 800**2)
    assert abs(total - area) <= 0.01 * area


def test_every_ruling_is_torsal_and_the_exported_faces_are_developable_and_join(solved):
    folder, result = solved
    assert all(kind == "torsal" for kind in items(result, "Kind"))
    assert max(items(result, "WarpAngles")) <= 1e-7
    strips = items(result, "Strips")
    exported = run(Export3dm(), Path="strips.3dm", Write=True, writes=allowed(folder),
                   Surfaces=tree({(0,): strips}))
    assert exported.state == OK, texts(exported)
    objects = list(rh.File3dm.Read(str(folder / "strips.3dm")).Objects)
    faces = [o for o in objects if o.Attributes.GetUserString("TorsalFace") == "torsal"]
    assert faces and all(o.Geometry.IsValid for o in objects)
    twists = [normal_twist(surface_of(o), 60) for o in faces]
    assert max(twists) <= 1e-6  # measured 6.7e-9
    size = float(np.ptp(np.concatenate([grid(s, 21, 3).reshape(-1, 3) for s in strips]), axis=0).max())
    for index in range(len(strips)):
        own = [o for o in objects if o.Attributes.GetUserString("TorsalIndex") == str(index)]
        assert own
        for before, after in itertools.pairwise(own):  # each pair shares a ruling: 2 corners
            a, b = corners(before), corners(after)
            near = np.linalg.norm(a[:, None] - b[None], axis=2).min(axis=1)
            assert np.sort(near)[1] <= 1e-9 * size


def test_the_strips_file_is_at_most_a_fifth_of_the_one_surface_form(solved):
    from torsal.nodes.io.formats import threedm

    folder, result = solved
    strips = items(result, "Strips")
    threedm.write_3dm(folder / "faces.3dm", threedm.tree_entries(tree({(0,): strips}), "S", "Strip"))
    naive = rh.File3dm()  # the form written before: one interpolated surface per strip
    for strip in strips:
        naive.Objects.AddSurface(threedm.rhino_surface(threedm.surface_form(strip).nurbs))
    assert naive.Write(str(folder / "naive.3dm"), 7)
    size, naive_size = ((folder / name).stat().st_size for name in ("faces.3dm", "naive.3dm"))
    assert size <= 0.2 * naive_size  # measured 6.5 %
