"""developable.PaperStrip: a digital strip of paper, folded quad by quad (after Lachauer)."""

from __future__ import annotations

import dataclasses
import math
from typing import Any

import numpy as np

from torsal.engine.node import LIST, In, Node, NodeWarning, Out
from torsal.engine.types import INTEGER, NUMBER
from torsal.nodes.common import checks as check
from torsal.nodes.common.checks import number
from torsal.nodes.common.placement import NAMES, ORIGIN, placement_frame, placement_inputs
from torsal.nodes.common.values import LINE, SURFACE
from torsal.nodes.geometry.curves.line import Line
from torsal.nodes.geometry.development_placement import WORLD_XY, place
from torsal.nodes.geometry.paper_strip import face_warp, paper_strip
from torsal.nodes.geometry.ruled import RuledSurface
from torsal.nodes.limits import MAX_SEGMENTS

#: Faces whose planarity (off-plane distance / diagonal) exceeds this are reported.
PLANAR = 1e-12


def _angles(name: str, values: list[Any]) -> list[float]:
    if any(v is None for v in values):
        raise NodeWarning(f"{name} contains empty (null) items: remove them or fix what made them")
    return [number(f"{name} {i}", v) for i, v in enumerate(values)]


class PaperStrip(Node):
    """A strip of paper, bent and twisted without stretching: exactly developable.

    The strip is Length long (along its middle line) and Width wide, made of
    Segments flat quads between Segments + 1 rulings, each Width long. From one
    ruling to the next the strip

    1. folds about the previous ruling by the Curvature angle (rad; 0 keeps it
       flat, positive folds towards the face's front), and
    2. turns the next ruling within the new face so that it makes the IsoAngle
       (rad) with the strip's advancing direction: π/2 keeps the rulings parallel
       (bending alone: a cylinder), less leans them forward (a cone or a tangent
       developable, as a twisted paper strip does).

    IsoAngle and Curvature take one value per segment; a shorter list repeats its
    last value (so one value applies to all). Twelve segments with Curvature 2π/12
    and IsoAngle π/2 roll the strip into a closed cylinder with Length as its
    circumference.

    Every face is planar by construction, and Surface is exactly these faces: flat
    quads with straight edges between the fold lines. So the strip unrolls exactly:
    Development is the same faces laid flat — cut a sheet along its outline and it
    folds into Surface, every face's edges and angles kept. IsoMapping reproduces it
    with no area error. Placement says where Development lies: 1 at the origin (the
    default: first ruling from the origin up +Y, the strip running towards +X, where
    IsoMapping with Placement 1 lays its development of Surface), 0 beside the strip
    (in +X, flat at its lowest point, as IsoMapping's default), 2 on Plane; a rigid
    motion, no length or area changes. WarpAngles are measured on the faces (the turn
    of the tangent plane along each ruling, rad in [0, π]): 0 to rounding.

    Warns when neighbouring rulings cross inside the strip (the IsoAngle leans them
    too far for the segment length): raise IsoAngle towards π/2, narrow the strip or
    use fewer segments.
    """

    type_id = "developable.PaperStrip"
    nickname, aliases = "Strip", ("developable strip", "bent strip", "twisted strip", "paper")
    inputs = (
        In("Length", NUMBER, "L", "Length of the strip along its middle line, model units.",
           default=10.0),
        In("Width", NUMBER, "W", "Width of the strip: every ruling's length, model units.",
           default=1.0),
        In("IsoAngle", NUMBER, "I",
           "Angle between the advancing direction and the next ruling, rad, per segment (π/2: parallel).",
           default=math.pi / 2, access=LIST),
        In("Curvature", NUMBER, "K", "Fold angle about the previous ruling, rad, per segment (0: flat).",
           default=0.2, access=LIST),
        In("Segments", INTEGER, "S", "Number of flat quads (rulings minus one, 1 or more).",
           default=24, min=1, max=MAX_SEGMENTS),
        # at the origin by default, unlike IsoMapping's: the strip is built from the origin, and
        # files made before Placement existed keep their Development where it was
        dataclasses.replace(placement_inputs("Development")[0], default=ORIGIN, choices=tuple(NAMES.items())),
        placement_inputs("Development")[1],
    )
    outputs = (
        Out("Surface", SURFACE, "S", "The bent strip: its flat quads between the fold lines."),
        Out("Rulings", LINE, "R", "The fold lines, each Width long.", access=LIST),
        Out("Development", SURFACE, "D", "The same quads unfolded flat in the XY plane: the outline "
            "to cut."),
        Out("WarpAngles", NUMBER, "W",
            "Turn of the tangent plane along each ruling, rad in [0, π] (0: flat faces).", access=LIST),
    )

    def solve(self, length: Any, width: Any, iso_angle: list[Any], curvature: list[Any], segments: Any,
              placement: Any = ORIGIN, plane: Any = None
              ) -> tuple[RuledSurface, list[Line], RuledSurface, list[float]]:
        total = check.positive("Length", length)
        wide = check.positive("Width", width)
        n = check.segments(segments)
        iso = _angles("IsoAngle", iso_angle)
        kappa = _angles("Curvature", curvature)
        for name, values in (("IsoAngle", iso), ("Curvature", kappa)):
            if len(values) > n:
                self.remark(f"{name} has {len(values)} values for {n} segments: the last "
                            f"{len(values) - n} are not used")
        strip = paper_strip(total, wide, iso, kappa, n)
        if not strip.valid:
            bad = np.flatnonzero(strip.crossing)
            self.warn(
                f"Rulings cross inside the strip in {bad.size} of {n} segments (first: segment "
                f"{int(bad[0])}): the IsoAngle leans them too far for the segment length; raise "
                "IsoAngle towards π/2, narrow the strip or use fewer segments"
            )
        worst = float(strip.planarity.max())
        if worst > PLANAR:
            self.warn(f"A face is off plane by {worst:.2g} of its size (rounding at this scale?)")
        surface = RuledSurface.from_rulings(strip.starts, strip.ends, degree=1)
        flat2d = np.vstack([strip.starts2d, strip.ends2d])
        frame = placement_frame(self, placement, plane, np.vstack([strip.starts, strip.ends]),
                                [*flat2d.min(axis=0), *flat2d.max(axis=0)])
        if frame is WORLD_XY:  # in its own frame, as the strip was unfolded
            flat = np.zeros((len(strip.starts2d), 1))
            starts, ends = np.hstack([strip.starts2d, flat]), np.hstack([strip.ends2d, flat])
        else:
            starts, ends = place(frame, strip.starts2d), place(frame, strip.ends2d)
        development = RuledSurface.from_rulings(starts, ends, degree=1)
        warp = face_warp(strip.starts, strip.ends).tolist()
        return surface, Line.many(strip.starts, strip.ends), development, warp
