"""patching.SurfacePatching, in the graph it is made for:

curve → CylindricalSurface / ConicalSurface → IsoMapping (Map) → SurfacePatching
                                             StaggeredPattern (Pattern, Tile) ↗
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import pytest
import shapely

from tests.support.direct_graphs import Chain
from torsal.engine.graph import GraphError
from torsal.engine.values import Point, Vector
from torsal.nodes.analysis.iso_mapping import IsoMapping
from torsal.nodes.curves.primitives import Circle, Line
from torsal.nodes.developable.conical import ConicalSurface
from torsal.nodes.developable.cylindrical import CylindricalSurface
from torsal.nodes.geometry.curves.line import Line as KernelLine
from torsal.nodes.geometry.curves.line import Polyline
from torsal.nodes.geometry.parametric_surface import cylinder as cylinder_surface
from torsal.nodes.geometry.parametric_surface import sphere
from torsal.nodes.patching.staggered import StaggeredPattern
from torsal.nodes.patching.surface_patching import SurfacePatching

SEGMENTS = 48


def patched(surface: str = "cone", tile: bool = True, iso: bool = True, bond: dict | None = None,
            **values) -> Chain:
    """A cone (apex √3 above a unit circle: slant 2) or a cylinder (radius 1, height 2),
    unrolled by IsoMapping and panelled with a running bond."""
    chain = Chain()
    chain.add("curve", Circle(), Radius=1.0)
    if surface == "cone":
        chain.add("surface", ConicalSurface(), Apex=Point(0, 0, math.sqrt(3)), Height=5.0,
                  Segments=SEGMENTS)
    else:
        chain.add("surface", CylindricalSurface(), Direction=Vector(0, 0, 1), Height=2.0,
                  Segments=SEGMENTS)
    chain.wire("curve", "Circle", "surface", "Curve")
    chain.add("bond", StaggeredPattern(), **(bond or {"Width": 0.3, "Height": 0.2, "Offset": 0.15}))
    chain.add("patch", SurfacePatching(), **{"Placement": 1, **values})  # the flat outputs at the origin
    chain.wire("surface", "Surface", "patch", "Surface")
    chain.wire("bond", "Pattern", "patch", "Pattern")
    if tile:
        chain.wire("bond", "Tile", "patch", "Tile")
    if iso:
        chain.add("iso", IsoMapping(), Segments=SEGMENTS)
        chain.wire("surface", "Surface", "iso", "Surface")
        chain.wire("iso", "Map", "patch", "Development")
    return chain.solve()


@pytest.fixture(scope="module")
def cone() -> Chain:
    return patched("cone")


@pytest.fixture(scope="module")
def cylinder() -> Chain:
    return patched("cylinder")


def again(chain: Chain, rotation: float = 0.0, scale: float = 1.0) -> Chain:
    """Re-solve a shared graph with new Rotation and Scale (only SurfacePatching re-solves)."""
    chain.set("patch", "Rotation", rotation)
    chain.set("patch", "Scale", scale)
    return chain.solve()


def sourced(development, pattern, tile=None, surface=None, **values) -> Chain:
    """SurfacePatching fed by Source nodes (kernel objects made elsewhere)."""
    chain = Chain()
    chain.add("patch", SurfacePatching(), **{"Placement": 1, **values})  # the flat outputs at the origin
    for name, items in (("Development", [development]), ("Pattern", list(pattern)), ("Tile", [tile]),
                        ("Surface", [surface])):
        if items and items[0] is not None:
            chain.source(name, *items)
            chain.wire(name, "Tree", "patch", name)
    return chain.solve()


def flat_rings(chain: Chain) -> list[np.ndarray]:
    return [np.asarray(c.points)[:, :2] for c in chain.items("patch", "PanelsFlat")]


def rings_3d(chain: Chain) -> list[np.ndarray]:
    return [np.asarray(c.points) for c in chain.items("patch", "Panels3D")]


def turned_development(chain: Chain, rotation: float):
    return chain.item("iso", "Map").rotated(rotation)


def cross2(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


@dataclass
class Facets:
    """The rulings a development's map triangulates (its panels' facets)."""

    starts2d: np.ndarray
    ends2d: np.ndarray
    starts3d: np.ndarray
    ends3d: np.ndarray


def map_facets(development) -> Facets:
    """The rulings of ``development.map``: 8 a segment of the unrolled ones, laid where the
    fine unrolling put them (a full cone's rim needs 168 a segment for its length)."""
    m = development.map
    return Facets(m.vertices2d[:m.n], m.vertices2d[m.n:], m.vertices3d[:m.n], m.vertices3d[m.n:])


def facet_images(development, flat: np.ndarray) -> np.ndarray:
    """Flat points carried onto the cone by the affine map of the flat facet each lies in.

    The map of a cone's development is a fan of flat triangles (apex, foot i, foot i + 1),
    one per pair of neighbouring rulings; a point with barycentric coordinates (s, t) on the
    flat arms of its triangle is apex + s·arm_i + t·arm_{i+1} on the 3D ones.
    """
    apex2, apex3 = development.ends2d[0], development.ends3d[0]
    arms2, arms3 = development.starts2d - apex2, development.starts3d - apex3
    sense = np.sign(cross2(arms2[0], arms2[1]))
    turns = np.arctan2(sense * cross2(arms2[:-1], arms2[1:]), np.einsum("ij,ij->i", arms2[:-1], arms2[1:]))
    bounds = np.concatenate([[0.0], np.cumsum(turns)])
    w = flat - apex2
    angle = np.arctan2(sense * cross2(arms2[0], w), w @ arms2[0])
    angle = np.where(angle < -1e-9, angle + 2 * math.pi, np.maximum(angle, 0.0))  # (on the first arm)
    i = np.clip(np.searchsorted(bounds, angle) - 1, 0, len(turns) - 1)
    a, b = arms2[i], arms2[i + 1]
    s, t = cross2(w, b) / cross2(a, b), cross2(a, w) / cross2(a, b)
    return apex3 + s[:, None] * arms3[i] + t[:, None] * arms3[i + 1]


@pytest.mark.parametrize("rotation", [0.0, 30.0, 90.0])
def test_flat_rulings_are_an_isometric_image_of_the_cones_rulings(cone, rotation):
    """Every flat ruling as long as its 3D one, every step between neighbouring feet too
    (measured 5.5e-16, for rulings 2 long): the fan of flat triangles is congruent.
    Its apex is one point, and the arms keep their length, to the rounding of the n frames
    composed on the way (3.9e-13 and 3.0e-13 at the 8,065 rulings the rim's length needs)."""
    dev = turned_development(again(cone, rotation), rotation)
    arms2, arms3 = dev.starts2d - dev.ends2d[0], dev.starts3d - dev.ends3d[0]
    rounding = 2e-16 * len(arms2) * 2.0  # n frames, rulings 2 long
    assert np.abs(dev.ends2d - dev.ends2d[0]).max() < rounding  # one apex image
    assert np.abs(np.linalg.norm(arms2, axis=1) - np.linalg.norm(arms3, axis=1)).max() < rounding
    steps2, steps3 = np.diff(arms2, axis=0), np.diff(arms3, axis=0)
    assert np.abs(np.linalg.norm(steps2, axis=1) - np.linalg.norm(steps3, axis=1)).max() < 2e-15


@pytest.mark.parametrize("rotation", [0.0, 30.0, 90.0])
def test_panels_3d_are_the_flat_panels_carried_onto_the_cone_facet_by_facet(cone, rotation):
    """Each flat panel corner, carried by its facet's affine map (:func:`facet_images`, on the
    map's facets), is a corner of the 3D panel (measured 1.3e-11), and each 3D panel is as
    long as its flat one to the facets' own stretch (3D panels are split where they cross a
    ruling, so each piece lies in one facet). The map's 384 facets are laid on the accurate
    development: their arms keep their length (rounding), their rim steps are the flat
    distances between the feet, longer than the 3D chords by what the rim's arc is over its
    chord (measured 8.4e-6; the panels' lengths 7.4e-6)."""
    chain = again(cone, rotation)
    assert chain.result("patch").state == "ok", chain.texts("patch")
    facets = map_facets(turned_development(chain, rotation))
    arms2, arms3 = facets.starts2d - facets.ends2d[0], facets.starts3d - facets.ends3d[0]
    assert np.abs(np.linalg.norm(arms2, axis=1) - np.linalg.norm(arms3, axis=1)).max() < 1e-12
    steps2 = np.linalg.norm(np.diff(arms2, axis=0), axis=1)
    steps3 = np.linalg.norm(np.diff(arms3, axis=0), axis=1)
    # the 3D step is the chord 2 sin(Δθ/2) of a unit circle over the arc Δθ = 2π/384 that the
    # flat step (the slant 2 times the sector's angle Δθ/2) stays within rounding of
    arc = 2 * math.pi / 384
    np.testing.assert_allclose(steps3, 2 * math.sin(arc / 2), rtol=1e-5)
    stretch = float(np.abs(steps2 / steps3 - 1).max())
    assert stretch < 1.2 * (arc / (2 * math.sin(arc / 2)) - 1)
    flat, panels_3d = flat_rings(chain), rings_3d(chain)
    assert len(flat) == len(panels_3d) > 100
    for ring, panel in zip(flat, panels_3d, strict=True):
        images = facet_images(facets, ring)
        assert np.linalg.norm(images[:, None, :] - panel[None, :, :], axis=2).min(axis=1).max() < 3e-11
        length_2d = np.linalg.norm(np.diff(ring, axis=0), axis=1).sum()
        assert abs(np.linalg.norm(np.diff(panel, axis=0), axis=1).sum() / length_2d - 1) <= stretch


@pytest.mark.parametrize("rotation", [0.0, 17.0, 45.0])
def test_panel_areas_add_up_to_the_development_area_when_the_pattern_covers_it(cone, rotation):
    """The outline of the development's map is the polygon apex, feet (shapely): panels that
    cover it add up to its area (measured 6e-16). It is the cone's π r L = 2π less what the
    chords between its 385 feet cut off the flat sector, (Δφ)²/6 with Δφ = π/384 (1.1e-5;
    measured 1.2e-5, the Circle's 48-span rim)."""
    chain = again(cone, rotation, scale=1.5)
    facets = map_facets(chain.item("iso", "Map"))
    outline = shapely.Polygon(np.vstack([facets.ends2d[:1], facets.starts2d]))
    assert outline.is_valid
    assert sum(chain.items("patch", "PanelAreas")) == pytest.approx(outline.area, rel=1e-13)
    assert outline.area == pytest.approx(2 * math.pi, rel=3e-5)
    assert outline.area == pytest.approx(2 * math.pi * (1 - (math.pi / 384) ** 2 / 6), rel=2e-6)


@pytest.mark.parametrize("rotation", [0.0, 20.0, -35.0, 90.0])
def test_rotation_turns_the_panel_rows_on_a_cylinder_so_they_fall_at_the_rotation_angle(cylinder, rotation):
    # The cylinder's first ruling runs up from z = 0; unrolled it runs up +Y and the
    # strip continues towards +X (along the circle). Turning the development by α under
    # the axis-aligned pattern turns the pattern by −α on the surface: every row edge
    # (a full panel's bottom edge, from its lower-left to its lower-right corner) drops
    # by sin α per unit length as it runs along the strip.
    chain = again(cylinder, rotation)
    dev = turned_development(chain, rotation)
    areas = np.array(chain.items("patch", "PanelAreas"))
    full = [r for r, a in zip(flat_rings(chain), areas, strict=True) if abs(a - 0.06) < 1e-12]
    assert len(full) > 20
    corners = np.array([r[:2] for r in full])  # (panels, lower-left / lower-right, 2)
    ends = dev.map.to_3d(corners.reshape(-1, 2)).reshape(-1, 2, 3)
    drop = (ends[:, 1, 2] - ends[:, 0, 2]) / np.linalg.norm(corners[:, 1] - corners[:, 0], axis=1)
    assert np.abs(drop + math.sin(math.radians(rotation))).max() < 1e-12


def test_turning_the_development_itself_adds_to_the_rotation(cone):
    base = again(cone, 50.0)
    chain = sourced(base.item("iso", "Map").rotated(20.0), base.items("bond", "Pattern"),
                    base.item("bond", "Tile"), Rotation=30.0)
    a, b = rings_3d(base), rings_3d(chain)
    assert len(a) == len(b) > 100
    assert max(np.abs(p - q).max() for p, q in zip(a, b, strict=True)) < 1e-9


def test_waste_on_a_rectangle_is_the_cut_off_share_of_whole_panels():
    # a flat 6.5 × 2 rectangle (a "cylinder" on a straight line) under a 1 × 1 grid:
    # 7 columns × 2 rows of panels, the last column cut to half: waste 1 − 13/14
    chain = Chain()
    chain.add("curve", Line(), Start=Point(0, 0, 0), End=Point(6.5, 0, 0))
    chain.add("surface", CylindricalSurface(), Height=2.0, Segments=13)
    chain.wire("curve", "Line", "surface", "Curve")
    chain.add("iso", IsoMapping(), Segments=13)
    chain.wire("surface", "Surface", "iso", "Surface")
    chain.add("bond", StaggeredPattern(), Width=1.0, Height=1.0, Offset=0.0)
    chain.add("patch", SurfacePatching())
    chain.wire("iso", "Map", "patch", "Development")
    chain.wire("bond", "Pattern", "patch", "Pattern")
    chain.wire("bond", "Tile", "patch", "Tile")
    chain.solve()
    areas = np.array(chain.items("patch", "PanelAreas"))
    assert len(areas) == 14
    assert sorted(areas.round(12).tolist()) == [0.5] * 2 + [1.0] * 12
    assert chain.item("patch", "Waste") == pytest.approx(1 - 13 / 14, abs=1e-12)
    assert chain.items("patch", "PanelIDs") == [f"P-{i:03d}" for i in range(1, 15)]


def test_bounds_are_the_scaled_tile_and_the_development_rectangle(cylinder):
    chain = again(cylinder, scale=2.0)
    tile = np.asarray(chain.item("patch", "PatternBounds").points)
    box = np.asarray(chain.item("patch", "DevelopmentBounds").points)
    xmin, ymin, xmax, ymax = chain.item("iso", "Map").bounds
    corners = [[xmin, ymin, 0], [xmax, ymin, 0], [xmax, ymax, 0], [xmin, ymax, 0]]
    assert np.abs(box[:4] - corners).max() < 1e-14
    assert np.abs(tile[2] - tile[0] - [0.6, 0.8, 0.0]).max() < 1e-15
    assert np.abs(tile[0] - [xmin, ymin, 0.0]).max() < 1e-14


def test_flat_panels_are_closed_and_lie_in_the_xy_plane(cone):
    chain = again(cone)
    panels = chain.items("patch", "PanelsFlat")
    assert all(isinstance(p, Polyline) and p.closed for p in panels)
    assert all(np.all(np.asarray(p.points)[:, 2] == 0.0) for p in panels)
    assert all(p.closed for p in chain.items("patch", "Panels3D"))


def test_a_running_bond_without_its_tile_leaves_gaps_and_the_node_says_so(cone):
    chain = sourced(cone.item("iso", "Map"), cone.items("bond", "Pattern"))
    assert chain.texts("patch") == [
        "The pattern covers 67% of its tile, so the tiling leaves gaps (a running bond overhangs its "
        "tile: wire StaggeredPattern's Tile into Tile)"
    ]


def test_without_a_development_the_surface_is_unrolled_here(cone):
    surface = cylinder_surface(1.0, 2.0)
    chain = sourced(None, cone.items("bond", "Pattern"), cone.item("bond", "Tile"), surface=surface)
    assert chain.texts("patch") == [
        "No Development wired: the Surface was unrolled here with 48 segments (wire IsoMapping to choose)"
    ]
    # the unit cylinder 2 high, unrolled to 2π × 2 short of what its flat facets cut off
    # (measured 1.1e-5)
    assert sum(chain.items("patch", "PanelAreas")) == pytest.approx(4 * math.pi, rel=2e-5)


def test_a_development_of_another_surface_warns(cone):
    chain = sourced(cone.item("iso", "Map"), cone.items("bond", "Pattern"), cone.item("bond", "Tile"),
                    surface=sphere(1.0))
    assert chain.result("patch").state == "warning"
    (text,) = chain.texts("patch")
    assert text.startswith("The Development's rulings lie up to ")
    assert text.endswith("it was not unrolled from this Surface; wire the same surface into IsoMapping")


def test_neither_development_nor_surface_warns(cone):
    chain = sourced(None, cone.items("bond", "Pattern"))
    assert chain.result("patch").state == "warning"
    assert chain.texts("patch") == [
        "Give a Development (IsoMapping's Map output) or a developable Surface"
    ]


def test_scale_zero_warns(cone):
    chain = sourced(cone.item("iso", "Map"), cone.items("bond", "Pattern"), cone.item("bond", "Tile"),
                    Scale=0.0)
    assert chain.result("patch").state == "warning"
    assert chain.texts("patch") == ["Scale must be positive, not 0"]


def test_an_open_pattern_curve_warns(cone):
    chain = sourced(cone.item("iso", "Map"), [KernelLine([0, 0, 0], [1, 0, 0])])
    assert chain.result("patch").state == "warning"
    assert chain.texts("patch") == ["Pattern curve 0 is open: a panel outline must be a closed curve"]


def test_the_flat_development_surface_cannot_be_wired_where_the_map_belongs(cone):
    # IsoMapping's Development output is the flat surface; SurfacePatching needs its Map
    with pytest.raises(GraphError, match=r"gives Surface, which .*Development \(Development\) cannot take"):
        cone.wire("iso", "Development", "patch", "Development")
