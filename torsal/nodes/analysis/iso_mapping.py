"""analysis.IsoMapping: unroll a ruled surface into the XY plane, strip by strip."""

from __future__ import annotations

from typing import Any

import numpy as np

from torsal.engine.node import LIST, In, Node, NodeWarning, Out
from torsal.engine.types import INTEGER, NUMBER, TEXT
from torsal.nodes.common.checks import analysis_segments as segments
from torsal.nodes.common.convert import sentence
from torsal.nodes.common.geometry_checks import ruled_surface
from torsal.nodes.common.placement import placement_frame, placement_inputs
from torsal.nodes.common.values import DEVELOPMENT, LINE, SURFACE
from torsal.nodes.geometry.curves.line import Line
from torsal.nodes.geometry.development_placement import place
from torsal.nodes.geometry.ruled import RuledSurface
from torsal.nodes.geometry.unroll import Development, unroll_surface
from torsal.nodes.geometry.vectors import Plane
from torsal.nodes.geometry.watch import watched
from torsal.nodes.limits import MAX_ANALYSIS_SEGMENTS

#: Above this relative area difference the node says what it may mean.
AREA_NOTE = 1e-3
#: Fewest rulings unrolled per strip the user sees, as in the kernel's ``unroll_surface``:
#: the chords then hug the surface and the area error shrinks 64-fold.
SUBDIVISIONS = 8
#: More are sampled until both flat edges are as long as the 3D edges to this share of the
#: surface's size (``unroll_surface``'s ``edge_tolerance``): 4 µm on a 40 m strip, so two
#: strips that share a curve have flat edges of the same length and their seam closes.
EDGE_TOLERANCE = 1e-7


def development_surface(development: Development, frame: Plane | None = None) -> RuledSurface:
    """The development as a flat surface: the loft of every unrolled ruling (the requested
    ones and those between them) with straight edges from one to the next — exactly the
    outline of the unrolled triangles, the polygon a sheet is cut along — whose rulings
    are the requested ones (:attr:`Development.rulings2d`). Its u parameter is the 3D
    surface's at every unrolled ruling when they were sampled evenly. ``frame``: where
    the development's XY plane is laid (:mod:`torsal.nodes.geometry.development_placement`;
    default: where it was unrolled)."""
    zero = np.zeros((len(development.starts2d), 1))
    if frame is None:
        starts, ends = np.hstack([development.starts2d, zero]), np.hstack([development.ends2d, zero])
    else:
        starts, ends = place(frame, development.starts2d), place(frame, development.ends2d)
    surface = RuledSurface.from_rulings(starts, ends, degree=1)
    requested = development.requested_rulings
    assert surface.ruling_lines is not None and surface.ruling_parameters is not None
    surface.ruling_lines = surface.ruling_lines[requested]
    surface.ruling_parameters = surface.ruling_parameters[requested]
    return surface


def overlaps(development: Development) -> bool:
    """Whether the development covers part of the plane twice (it cannot be cut from one
    sheet): its outline crosses or touches itself, vertices that coincide to rounding (a
    cone's apex, visited once per ruling) counted once (:attr:`Development.overlaps`)."""
    return development.overlaps


def area_text(development: Development) -> str:
    """The Area output: both areas, their difference and the difference in per cent."""
    a3, a2 = development.area_3d, development.area_2d
    return (f"input area {a3:.6g}, development area {a2:.6g}, difference {a2 - a3:+.3g} "
            f"({100 * development.area_error:+.3g} %)")


def edge_text(development: Development) -> str:
    """The remark when the flat edges were not sampled to :data:`EDGE_TOLERANCE`."""
    count = len(development.starts2d)
    most = ", as many as the unrolling samples," if development.edge_capped else ""
    why = f"{count:,} rulings{most} were not enough"
    return (f"The flat edges may be shorter than the 3D edges by more than {EDGE_TOLERANCE:g} of the "
            f"surface's size: {why} (estimated {development.edge_shortfall:.1g} short). An edge with a "
            "corner the surface does not mark (a curve given by a formula with a kink) converges more "
            "slowly than that estimate assumes and may be shorter still: give the edge a knot or vertex "
            "at the corner, or split the surface there")


class IsoMapping(Node):
    """Unroll a ruled surface into the XY plane, keeping the length of every ruling.

    The surface is cut into Segments strips between Segments + 1 rulings; each strip
    is split into two triangles and the triangles are laid flat one after another,
    each congruent to its 3D original, so rulings, both edges and the strips' widths
    keep their lengths (EdgeError shows it: rounding level). Between the rulings you
    see, at least 7 more per strip are unrolled too — as many as it takes for both
    flat edges to be as long as the curved 3D edges to 1e-7 of the surface's size:
    evenly, up to 4096 rulings in all; where that is not enough, up to 32768: each strip
    as many as its own stretch of the edges needs where the edges run fast over some
    strips only (a fan sweeping a long stretch of one curve from a point of the other),
    evenly where they are curved all along (a full cone's rim: 88 a strip at 100
    Segments), and one on every corner of an edge (a NURBS rail's kinked knots, a
    polyline's vertices) — so two strips made between a shared curve have flat edges of
    the same length and their seam closes. Development is the outline of all these triangles,
    edge by straight edge, so a sheet cut along it is exactly what was unrolled. The
    first ruling starts at the origin and runs up the Y axis; the strip continues
    towards +X. Map triangulates the same rulings, except where the edges are curved all
    along: there it keeps 8 a strip of them, laid where the fine unrolling put them, so
    panels cost what they did (its outline is within the chords' sag of Development's).

    Placement says where Development and Rulings are shown, so the flat development
    does not cut through the 3D model: 0 Beside model (the default) lays it flat beside
    the surface's bounding box in +X, a fifth of the surface's size away, at the height
    of its lowest point and level with its front (least y); 1 Origin leaves it where it
    was unrolled; 2 On plane carries that frame onto Plane (the origin to the plane's
    origin, X and Y along its axes). Wire a value list (0, 1, 2) to choose. Each is a
    rigid motion: lengths, areas and every figure stay the same. Map stays in the
    unrolled frame (SurfacePatching has a Placement input of its own: give it the same
    to lay the panels over this Development).

    For a developable surface (cylinder, cone, tangent developable, the output of the
    developable nodes) the unrolling is an isometry: areas agree (AreaError a few 1e-6 at
    100 segments) and a cone becomes a circular sector, a cylinder a rectangle. A
    twisted ruled surface (a hyperbolic paraboloid) has no true development: its
    rulings still keep their lengths, but the area does not, and AreaError says by
    how much — a measure of how far the surface is from developable. Map carries
    points and panel outlines between the development and the surface (wire it into
    SurfacePatching). A surface without straight rulings gives an error; a
    development that overlaps itself (a tangent developable of more than a turn)
    gives a warning, as it cannot be cut from one sheet.
    """

    type_id = "analysis.IsoMapping"
    nickname, aliases = "Unroll", ("Unroll Surface", "unfold", "flatten", "development", "flat pattern")
    inputs = (
        In("Surface", SURFACE, "S", "The ruled surface to unroll (its rulings must be straight lines)."),
        In("Segments", INTEGER, "N", "How many strips to cut it into: rulings minus one (1 or more).",
           default=100, min=1, max=MAX_ANALYSIS_SEGMENTS),
        *placement_inputs("Development and Rulings"),
    )
    outputs = (
        Out("Development", SURFACE, "D", "The unrolled surface in the XY plane: the unrolled triangles' "
            "outline, with the flat rulings."),
        Out("Rulings", LINE, "R", "The Segments + 1 rulings laid flat, in order.", access=LIST),
        Out("Area", TEXT, "A", "Area of the input and of the development, their difference and "
            "the difference in per cent."),
        Out("AreaInput", NUMBER, "Ai", "Area of the input surface, in square model units."),
        Out("AreaDevelopment", NUMBER, "Ad", "Area of the development, in square model units."),
        Out("EdgeError", NUMBER, "Ee", "Largest relative change of any edge length in the unrolling "
            "(rounding level: ~1e-15, up to ~1e-8 on the shortest edges of a finely sampled strip)."),
        Out("AreaError", NUMBER, "Ae", "(development area − input area) / input area: ~0 for a "
            "developable surface."),
        Out("Map", DEVELOPMENT, "M", "The development with its map to and from the 3D surface, for "
            "SurfacePatching (in the unrolled frame, whatever Placement)."),
    )

    def solve(self, surface: Any, count: Any, placement: Any = 0, plane: Any = None) -> tuple[Any, ...]:
        s = ruled_surface(surface, "IsoMapping")
        n = segments(count)
        try:
            with watched(self.check_cancelled, self.progress):
                development = unroll_surface(s, n, SUBDIVISIONS, EDGE_TOLERANCE)
        except ValueError as exc:
            raise NodeWarning(f"The surface cannot be unrolled: {sentence(exc)}") from None
        starts2d, ends2d = development.rulings2d
        frame = placement_frame(self, placement, plane, np.vstack([development.starts3d, development.ends3d]),
                                development.bounds)
        self.check_cancelled()
        if overlaps(development):
            self.warn("The development overlaps itself, so it cannot be cut from one sheet: unroll "
                      "less of the surface (fewer turns) or split it into pieces")
        if development.edge_capped or development.edge_shortfall > EDGE_TOLERANCE:
            self.remark(edge_text(development))
        if abs(development.area_error) > AREA_NOTE:
            self.remark(f"The development's area differs from the surface's by "
                        f"{100 * development.area_error:+.3g} %: for a developable surface raise "
                        "Segments; a twisted ruled surface has no true development, only its rulings "
                        "keep their lengths")
        return (
            development_surface(development, frame),
            Line.many(place(frame, starts2d), place(frame, ends2d)),
            area_text(development),
            float(development.area_3d),
            float(development.area_2d),
            float(development.max_edge_length_error),
            float(development.area_error),
            development,
        )
