"""Placement of IsoMapping's and SurfacePatching's flat outputs: beside the model, at the
origin, or on a plane — always a rigid motion of the unrolled development.

The model is a whole cone around a vertical axis (base radius R at CENTRE, apex H above
it), whose bounding box is known in closed form: CENTRE ± (R, R, 0) up to the apex.
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial.distance import pdist

from tests.support.direct_graphs import Chain
from torsal.engine.values import Plane, Point, Vector
from torsal.nodes.analysis.iso_mapping import IsoMapping
from torsal.nodes.geometry.parametric_surface import cone
from torsal.nodes.patching.staggered import StaggeredPattern
from torsal.nodes.patching.surface_patching import SurfacePatching

R, H = 2.0, 3.0
CENTRE = np.array([3.0, -1.0, 1.5])
BOX_LOW = CENTRE - [R, R, 0.0]
BOX_HIGH = CENTRE + np.array([R, R, H])
SIZE = float(np.linalg.norm(BOX_HIGH - BOX_LOW))
SEGMENTS = 24
#: A vertical plane through (1, 2, 3), its X axis along (1, 1, 0) (not unit: made so).
TILTED = Plane(Point(1.0, 2.0, 3.0), Vector(1.0, 1.0, 0.0), Vector(0.0, 0.0, 2.0))

BESIDE, ORIGIN, ON_PLANE = 0, 1, 2
FLAT_OUTPUTS = ("PatternBounds", "DevelopmentBounds", "PanelsFlat")


def graph(placement: int, plane: Plane | None = None, patching: bool = False) -> Chain:
    """The cone unrolled by IsoMapping (and panelled by SurfacePatching) at ``placement``."""
    chain = Chain()
    chain.source("surface", cone(R, H, CENTRE))
    chain.add("iso", IsoMapping(), Segments=SEGMENTS, Placement=placement)
    chain.wire("surface", "Tree", "iso", "Surface")
    if plane is not None:
        chain.set("iso", "Plane", plane)
    if patching:
        chain.add("bond", StaggeredPattern(), Width=0.7, Height=0.4, Offset=0.35)
        chain.add("patch", SurfacePatching(), Placement=placement)
        if plane is not None:
            chain.set("patch", "Plane", plane)
        chain.wire("surface", "Tree", "patch", "Surface")
        chain.wire("iso", "Map", "patch", "Development")
        chain.wire("bond", "Pattern", "patch", "Pattern")
        chain.wire("bond", "Tile", "patch", "Tile")
    return chain.solve()


@pytest.fixture(scope="module")
def unrolled() -> dict[int, Chain]:
    return {BESIDE: graph(BESIDE), ORIGIN: graph(ORIGIN), ON_PLANE: graph(ON_PLANE, TILTED)}


@pytest.fixture(scope="module")
def panelled() -> dict[int, Chain]:
    return {BESIDE: graph(BESIDE, patching=True), ORIGIN: graph(ORIGIN, patching=True)}


def development_points(chain: Chain) -> np.ndarray:
    """Points of IsoMapping's Development (a grid over the flat surface) and Rulings' ends."""
    flat = chain.item("iso", "Development")
    u, v = (a.ravel() for a in np.meshgrid(np.linspace(0, 1, 41), np.linspace(0, 1, 5)))
    rulings = chain.items("iso", "Rulings")
    ends = np.array([p for line in rulings for p in (line.start, line.end)], dtype=float)
    return np.vstack([flat.point_at(u, v), ends])


def panel_points(chain: Chain) -> np.ndarray:
    return np.vstack([np.asarray(c.points, dtype=float) for name in FLAT_OUTPUTS
                      for c in chain.items("patch", name)])


def test_beside_model_development_lies_outside_the_models_bounding_box(unrolled):
    points = development_points(unrolled[BESIDE])
    assert points[:, 0].min() > BOX_HIGH[0] + 0.1 * SIZE  # in +X, with a gap
    assert unrolled[BESIDE].texts("iso") == []


def test_beside_model_development_is_flat_at_the_models_lowest_point(unrolled):
    z = development_points(unrolled[BESIDE])[:, 2]
    assert np.abs(z - BOX_LOW[2]).max() <= 1e-15 * SIZE


def test_beside_model_development_is_level_with_the_models_front(unrolled):
    y = development_points(unrolled[BESIDE])[:, 1]
    assert abs(y.min() - BOX_LOW[1]) <= 1e-15 * SIZE


@pytest.mark.parametrize("placement", [BESIDE, ON_PLANE])
def test_placement_is_a_rigid_motion_of_the_origin_development(unrolled, placement):
    """Every pairwise distance is kept: to 1e-12 of itself for points apart (the apex's
    rulings meet in one point, whose copies are apart by rounding), to 1e-15 of the size
    for all."""
    placed = pdist(development_points(unrolled[placement]))
    origin = pdist(development_points(unrolled[ORIGIN]))
    assert np.abs(placed - origin).max() <= 1e-15 * SIZE
    apart = origin > 1e-9 * SIZE
    np.testing.assert_allclose(placed[apart], origin[apart], rtol=1e-12, atol=0)


@pytest.mark.parametrize("placement", [BESIDE, ON_PLANE])
def test_placement_leaves_every_measured_output_unchanged(unrolled, placement):
    for port in ("AreaError", "AreaInput", "AreaDevelopment", "EdgeError", "Area"):
        assert unrolled[placement].item("iso", port) == unrolled[ORIGIN].item("iso", port), port


def test_origin_placement_starts_the_first_ruling_at_the_origin(unrolled):
    first = unrolled[ORIGIN].items("iso", "Rulings")[0]
    assert np.abs(np.asarray(first.start, dtype=float)).max() <= 1e-15 * SIZE
    assert np.abs(development_points(unrolled[ORIGIN])[:, 2]).max() == 0.0


def test_on_plane_lays_the_origin_on_the_planes_origin_and_the_development_in_the_plane(unrolled):
    chain = unrolled[ON_PLANE]
    first = chain.items("iso", "Rulings")[0]
    assert np.abs(np.asarray(first.start, dtype=float) - TILTED.origin).max() <= 1e-15 * SIZE
    normal = np.cross(TILTED.x, TILTED.y) / np.linalg.norm(np.cross(TILTED.x, TILTED.y))
    off = (development_points(chain) - np.asarray(TILTED.origin)) @ normal
    assert np.abs(off).max() <= 1e-15 * SIZE


def test_on_plane_without_a_plane_says_so_and_uses_the_world_xy_plane(unrolled):
    chain = graph(ON_PLANE)
    assert any("no Plane is wired" in t for t in chain.texts("iso"))
    assert np.array_equal(development_points(chain), development_points(unrolled[ORIGIN]))


def test_a_plane_with_another_placement_is_remarked_and_not_used(unrolled):
    chain = graph(BESIDE, TILTED)
    assert any("Plane is used only when Placement is 2" in t for t in chain.texts("iso"))
    assert np.array_equal(development_points(chain), development_points(unrolled[BESIDE]))


def test_patching_flat_outputs_beside_model_lie_outside_the_models_bounding_box(panelled):
    points = panel_points(panelled[BESIDE])
    assert points[:, 0].min() > BOX_HIGH[0] + 0.1 * SIZE
    assert np.abs(points[:, 2] - BOX_LOW[2]).max() <= 1e-15 * SIZE


def test_patching_placement_is_a_rigid_motion_of_the_flat_outputs(panelled):
    placed, origin = pdist(panel_points(panelled[BESIDE])), pdist(panel_points(panelled[ORIGIN]))
    assert np.abs(placed - origin).max() <= 1e-15 * SIZE
    apart = origin > 1e-9 * SIZE
    np.testing.assert_allclose(placed[apart], origin[apart], rtol=1e-12, atol=0)


def test_patching_placement_leaves_areas_waste_and_3d_panels_unchanged(panelled):
    beside, origin = panelled[BESIDE], panelled[ORIGIN]
    assert beside.items("patch", "PanelAreas") == origin.items("patch", "PanelAreas")
    assert beside.item("patch", "Waste") == origin.item("patch", "Waste")
    for a, b in zip(beside.items("patch", "Panels3D"), origin.items("patch", "Panels3D"), strict=True):
        assert np.array_equal(a.points, b.points)


def test_patching_beside_model_lays_the_panels_on_iso_mappings_development(panelled):
    """At Rotation 0 both nodes move their flat frame by the same translation, so the flat
    panels stay on IsoMapping's Development."""
    beside, origin = panelled[BESIDE], panelled[ORIGIN]
    iso_shift = development_points(beside) - development_points(origin)
    patch_shift = panel_points(beside) - panel_points(origin)
    assert np.ptp(iso_shift, axis=0).max() <= 2e-15 * SIZE
    assert np.abs(patch_shift - iso_shift[0]).max() <= 2e-15 * SIZE


def test_a_plane_with_parallel_axes_is_refused_naming_the_plane():
    chain = graph(ON_PLANE, Plane(Point(0.0, 0.0, 0.0), Vector(1.0, 0.0, 0.0), Vector(2.0, 0.0, 0.0)))
    assert any("Plane's X and Y axes are parallel" in t for t in chain.texts("iso"))


def test_a_placement_out_of_range_is_refused_naming_the_input():
    chain = graph(3)
    assert chain.result("iso").state == "warning" and chain.items("iso", "Development") == []
    assert any(t.startswith("Placement is 3") for t in chain.texts("iso"))
