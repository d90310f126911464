"""Moving kernel geometry to a frame at the model and back (nodes/geometry/local_frame.py).

Each kind is built twice, independently: from points about the origin and from the same
points plus 1e9 m (whole numbers and halves, so every moved coordinate is exact). Moved
back by −1e9 m, the far object must be the same kind as the near one and evaluate where
it does to the near object's own rounding (1e-14 of its size); in world coordinates each
position far out is only known to 1.2e-7 m.
"""

from __future__ import annotations

import numpy as np
import pytest

from torsal.nodes.geometry.curve_base import ReversedCurve, TransformedCurve
from torsal.nodes.geometry.curve_rail import CurveRail, ruled_between
from torsal.nodes.geometry.curves.conics import Arc, Circle
from torsal.nodes.geometry.curves.interpolated import InterpolatedCurve
from torsal.nodes.geometry.curves.line import Line, Polyline
from torsal.nodes.geometry.curves.nurbs import NurbsCurve
from torsal.nodes.geometry.developable.guided import SurfaceCurve
from torsal.nodes.geometry.local_frame import NEAR, LocalFrame, frame_origin, frame_origins, translated
from torsal.nodes.geometry.nurbs_surface import Loft, NurbsSurface
from torsal.nodes.geometry.parametric_surface import ParametricSurface
from torsal.nodes.geometry.ruled import RuledSurface, SplineRail
from torsal.nodes.geometry.surface_base import IsoCurve, TransformedSurface
from torsal.nodes.geometry.transforms import translation
from torsal.nodes.geometry.vectors import Plane

FAR = np.array([1e9, 1e9, 1e9])
WAVE = np.array([[0, 0, 0], [3, 0.5, 0], [6, 0, 1], [9, -0.5, 0], [12, 0, 0.5]], dtype=float)
TOP = WAVE + np.array([0.0, 2.0, 3.0])
T = np.linspace(0.0, 1.0, 33)
U, V = (a.ravel() for a in np.meshgrid(np.linspace(0.0, 1.0, 9), np.linspace(0.0, 1.0, 9)))


def _saddle(u, v):
    return np.column_stack([u, v, u * v / 8.0])


def _grid(offset):
    x, y = np.meshgrid(np.arange(5.0), np.arange(4.0), indexing="ij")
    return np.stack([2 * x, 2 * y, (x - 2) ** 2 / 2], axis=2) + offset


def _path(t, order):
    out = [np.column_stack([t, 0.3 + 0.2 * t * t])]
    if order >= 1:
        out.append(np.column_stack([np.ones_like(t), 0.4 * t]))
    if order >= 2:
        out.append(np.column_stack([np.zeros_like(t), np.full_like(t, 0.4)]))
    return out


SADDLE = ParametricSurface(_saddle, (-4, 4), (-4, 4))

def _nurbs(o):
    return NurbsCurve(WAVE + o, degree=3)


def _top(o):
    return NurbsCurve(TOP + o, degree=3)


#: Kinds whose defining data (control points, vertices, planes) are exact 1e9 m out.
CURVES = {
    "nurbs": _nurbs,
    "nurbs (rational)": lambda o: NurbsCurve(WAVE + o, degree=3, weights=[1, 2, 1, 2, 1]),
    "circle": lambda o: Circle(Plane.from_axes(np.add(o, [1.0, 2.0, 0.5]), [1, 0, 0], [0, 1, 1]), 4.0),
    "arc": lambda o: Arc(Plane.from_axes(np.add(o, [1.0, 2.0, 0.5]), [1, 0, 0], [0, 1, 1]), 4.0, 0.5, 2.5),
    "line": lambda o: Line(WAVE[0] + o, WAVE[2] + o),
    "polyline": lambda o: Polyline(WAVE + o),
    "spline rail": lambda o: SplineRail(np.linspace(0, 1, len(WAVE)), WAVE + o),
    "reversed": lambda o: ReversedCurve(_nurbs(o)),
    "transformed": lambda o: TransformedCurve(_nurbs(np.zeros(3)), translation(o)),
    "curve rail": lambda o: CurveRail(_nurbs(o), [0.0, 0.5, 1.0], [0.1, 0.3, 0.9]),
    "isocurve": lambda o: IsoCurve(NurbsSurface(_grid(o)), "u", 0.4),
    "surface curve": lambda o: SurfaceCurve(NurbsSurface(_grid(o)), _path),
}

SURFACES = {
    "ruled between curves": lambda o: RuledSurface(_nurbs(o), _top(o)),
    "ruled from rulings": lambda o: RuledSurface.from_rulings(WAVE + o, TOP + o),
    "ruled on curves": lambda o: ruled_between(_nurbs(o), [0.0, 0.4, 1.0], _top(o), [0.0, 0.6, 1.0]),
    "nurbs": lambda o: NurbsSurface(_grid(o)),
    "transformed": lambda o: TransformedSurface(SADDLE, translation(np.add(o, [0.0, 0.0, 1.0]))),
}

#: Kinds made by computing coordinates far out (a fit, samples): rounded there on making.
MADE_FAR = {
    "interpolated": lambda o: InterpolatedCurve(WAVE + o),
    "loft": lambda o: Loft([InterpolatedCurve(WAVE + o), InterpolatedCurve(TOP + o)]),
}


def _close(got, expected, size: float) -> bool:
    scale = max(size, float(np.abs(expected).max()))  # (derivatives may be larger than the size)
    return float(np.abs(got - expected).max()) <= 1e-14 * scale


@pytest.mark.parametrize("kind", CURVES)
def test_a_far_curve_moved_to_the_origin_is_the_curve_made_there(kind):
    near, far = CURVES[kind](np.zeros(3)), CURVES[kind](FAR)
    moved = translated(far, -FAR)
    assert type(moved) is type(near)
    size = float(np.ptp(near.point_at(T), axis=0).max())
    for order in (0, 1, 2):
        assert _close(moved.derivatives(T, order)[order], near.derivatives(T, order)[order], size)


@pytest.mark.parametrize("kind", SURFACES)
def test_a_far_surface_moved_to_the_origin_is_the_surface_made_there(kind):
    near, far = SURFACES[kind](np.zeros(3)), SURFACES[kind](FAR)
    moved = translated(far, -FAR)
    assert type(moved) is type(near)
    expected, got = near.derivatives(U, V, 2), moved.derivatives(U, V, 2)
    size = float(np.ptp(expected[0], axis=0).max())
    for e, g in zip(expected, got, strict=True):
        assert _close(g, e, size)


@pytest.mark.parametrize("kind", MADE_FAR)
def test_a_curve_made_far_out_moves_exactly_on_its_control_points(kind):
    """Its control points were rounded to 1e9 m's ulp when it was made; moving them
    back is exact (x − 1e9 for x near 1e9), and the moved object evaluates where the far
    one does, moved, to that one's rounding (half an ulp of 1e9 m)."""
    far = MADE_FAR[kind](FAR)
    moved = translated(far, -FAR)
    assert type(moved) is type(far)
    assert np.array_equal(moved.control_points, far.control_points - FAR)
    points = moved.point_at(U, V) if kind == "loft" else moved.point_at(T)
    far_points = far.point_at(U, V) if kind == "loft" else far.point_at(T)
    assert np.abs(points - (far_points - FAR)).max() <= 0.5 * np.spacing(1e9)


def test_a_moved_interpolated_curve_keeps_its_interpolation_points_moved():
    moved = translated(InterpolatedCurve(WAVE + FAR), -FAR)
    assert np.array_equal(moved.points, WAVE)


def test_a_moved_loft_keeps_its_curves_moved():
    moved = translated(MADE_FAR["loft"](FAR), -FAR)
    assert np.array_equal(moved.curves[1].points, TOP)


def test_a_transformed_surface_moved_back_by_its_translation_is_the_surface_itself():
    assert translated(SADDLE.transformed(translation(FAR)), -FAR) is SADDLE


def test_a_zero_offset_hands_the_geometry_on_as_it_is():
    curve = InterpolatedCurve(WAVE)
    assert translated(curve, np.zeros(3)) is curve


def test_a_function_surface_is_moved_as_its_generic_transformed_view():
    moved = translated(SADDLE, FAR)
    assert isinstance(moved, TransformedSurface)
    assert np.array_equal(moved.point_at(U, V), SADDLE.point_at(U, V) + FAR)


def test_a_model_near_the_origin_is_solved_in_world_coordinates():
    surface = RuledSurface(InterpolatedCurve(WAVE), InterpolatedCurve(TOP))
    frame = LocalFrame.around(surface)
    assert frame.is_world
    assert frame.to_local(surface) is surface


def test_the_frame_is_anchored_at_the_box_centre_rounded_to_the_power_of_two_above_the_extent():
    # extent 12 m → multiples of 16 m; centre 1e9 + (6, 20, 5) → 1e9 + (0, 16, 0)
    points = np.array([[0.0, 14.0, 0.0], [12.0, 26.0, 10.0]]) + FAR
    assert np.array_equal(frame_origin(points), np.add(FAR, [0.0, 16.0, 0.0]))


def test_the_frame_stays_at_the_world_origin_within_near_extents_of_it():
    assert not frame_origin(np.array([[0.0, 0, 0], [1.0, 1, 1]]) + 0.9 * NEAR).any()
    assert frame_origin(np.array([[0.0, 0, 0], [1.0, 1, 1]]) + 2 * NEAR).any()


def test_geometry_moved_back_from_the_frame_is_the_original_and_built_on_it():
    """An isocurve of the local design, moved back, is an isocurve of the design itself."""
    design = NurbsSurface(_grid(FAR))
    frame = LocalFrame.around(design)
    local = frame.to_local(design)
    assert frame.to_world(local) is design
    boundary = frame.to_world(IsoCurve(local, "v", 0.25))
    assert boundary.surface is design
    assert np.array_equal(boundary.point_at(T), IsoCurve(design, "v", 0.25).point_at(T))


def test_a_strip_solved_in_the_frame_far_out_matches_the_strip_at_the_origin():
    """The ruled surface between two far curves, built on the local curves and moved back:
    its points are the origin's moved, to half an ulp of 1e9 m (one rounding)."""
    near = ruled_between(_nurbs(np.zeros(3)), [0.0, 0.5, 1.0], _top(np.zeros(3)), [0.0, 0.5, 1.0])
    a, b = _nurbs(FAR), _top(FAR)
    frame = LocalFrame.around(a, b)
    local = ruled_between(frame.to_local(a), [0.0, 0.5, 1.0], frame.to_local(b), [0.0, 0.5, 1.0])
    world = frame.to_world(local)
    assert isinstance(world, RuledSurface)
    assert np.abs(world.point_at(U, V) - FAR - near.point_at(U, V)).max() <= 0.5 * np.spacing(1e9) * 1.01
    assert np.abs(frame.points_to_world(local.ruling_lines) - FAR - near.ruling_lines).max() <= (
        0.5 * np.spacing(1e9) * 1.01)


def test_frames_of_several_groups_are_found_at_once_as_each_alone():
    site = np.array([[1e6, 2e6, 0.0], [1e6 + 3.0, 2e6 + 1.0, 2.0]])  # extent 3: steps of 4 m
    groups = [site, np.array([[0.0, 0, 0], [1, 1, 1]]), np.empty((0, 3)),
              np.array([[np.nan, 0, 0], [1e9, 0, 0]]), site + 5e8]
    together = frame_origins(np.concatenate(groups), [len(g) for g in groups])
    np.testing.assert_array_equal(together[0], [1e6, 2e6, 0.0])  # the centre rounded to 4 m
    np.testing.assert_array_equal(together[1:4], np.zeros((3, 3)))  # near the origin, empty, not finite
    for group, origin in zip(groups, together, strict=True):
        np.testing.assert_array_equal(origin, frame_origin(group))
    line = Line([1e6, 0, 0], [1e6 + 1, 0, 0])
    frames = LocalFrame.around_each([(line,), (line, None), ()])
    alone = LocalFrame.around(line).origin.tolist()
    assert [f.origin.tolist() for f in frames] == [alone, alone, [0.0, 0, 0]]
