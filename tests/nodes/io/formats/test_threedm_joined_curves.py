"""Joined curves go to a .3dm as Rhino polycurves, their corners kept (read back with rhino3dm)."""

from __future__ import annotations

import math

import rhino3dm as rh

from torsal.nodes.geometry.curves import Arc, Line
from torsal.nodes.geometry.curves.pieces import join
from torsal.nodes.geometry.vectors import Plane
from torsal.nodes.io.formats.threedm import Entry, write_3dm


def test_an_arc_joined_to_a_line_is_written_as_a_two_segment_polycurve_with_its_corner(tmp_path):
    arc = Arc(Plane.from_normal([0, 0, 0], [0, 0, 1]), 2.0, 0.0, math.pi / 2)
    (joined,) = join([arc, Line([0, 2, 0], [0, 5, 0])], 1e-9)
    written = write_3dm(tmp_path / "joined.3dm", [Entry(joined, "Curves")])
    assert written.objects == 1 and written.deviation == 0.0
    (item,) = rh.File3dm.Read(str(tmp_path / "joined.3dm")).Objects
    curve = item.Geometry
    assert isinstance(curve, rh.PolyCurve) and curve.SegmentCount == 2 and not curve.HasGap
    arc_part, line_part = curve.SegmentCurve(0), curve.SegmentCurve(1)
    low, high = arc_part.Domain.T0, arc_part.Domain.T1
    on_arc = [arc_part.PointAt(low + (high - low) * k / 50) for k in range(51)]
    assert max(abs(math.hypot(p.X, p.Y) - 2.0) for p in on_arc) < 1e-12  # exact: a rational arc
    start, stop = line_part.PointAtStart, line_part.PointAtEnd
    assert (start.X, start.Y, stop.X, stop.Y) == (0.0, 2.0, 0.0, 5.0)
    end = curve.PointAtEnd
    assert (end.X, end.Y, end.Z) == (0.0, 5.0, 0.0)
    # the corner stays a corner: the arc arrives along -x, the line leaves along +y
    arrives, leaves = curve.SegmentCurve(0).TangentAtEnd, curve.SegmentCurve(1).TangentAtStart
    assert abs(arrives.X + 1) < 1e-12 and abs(leaves.Y - 1) < 1e-12
