"""Sweep1: a profile carried along one rail, as Grasshopper's and Rhino's Sweep1."""

from __future__ import annotations

from typing import Any

import numpy as np

from torsal.engine.node import In, Node, NodeWarning, Out
from torsal.engine.types import INTEGER
from torsal.nodes.common.checks import count
from torsal.nodes.common.convert import kernel_errors
from torsal.nodes.common.geometry_checks import curve
from torsal.nodes.common.values import CURVE, SURFACE
from torsal.nodes.geometry import nurbs_surface
from torsal.nodes.geometry.surface_base import Surface
from torsal.nodes.geometry.sweep import swept_sections

#: Points along the profile at which each placed copy is interpolated (as Loft does).
SAMPLES = 257
#: The most sections a sweep is lofted through.
MAX_SECTIONS = 2_000


class Sweep1(Node):
    """Carry a profile curve along a rail: the surface a moulding or a gutter traces.

    The profile keeps the place it has relative to the rail's start: draw it square to
    the rail at its start (any place works, as in Rhino). Along the rail it turns with
    rotation-minimising frames, never twisting about the rail, so a profile swept along
    a flat rail stays square to its plane. The surface is lofted through Sections copies
    of the profile equally spaced along the rail (u along the profile, v along the rail);
    more Sections follow a sharply bending rail more closely. On a closed rail the frames
    are turned evenly along the way by the angle they would miss after one round (a
    closed space curve's rotation-minimising frames need not meet), so the last copy is
    the first and the sweep closes. A sweep is developable only in special cases (a straight profile along a
    flat rail, which gives a cylinder or a plane); check one with Surface Analysis.
    """

    type_id = "surfaces.Sweep1"
    nickname, aliases = "Swp1", ("Sweep1", "Sweep 1", "sweep", "sweep along rail", "extrude along curve")
    inputs = (
        In("Rail", CURVE, "R", "The path the profile follows."),
        In("Profile", CURVE, "S", "The section curve, placed at the rail's start."),
        In("Sections", INTEGER, "N", "How many copies of the profile the surface is lofted through "
           "(4 or more).", default=33),
    )
    outputs = (Out("Surface", SURFACE, "S", "The swept surface."),)

    def solve(self, rail: Any, profile: Any, sections: Any) -> Surface:
        path = curve("Rail", rail)
        shape = curve("Profile", profile)
        n = count("Sections", sections, least=4, limit=MAX_SECTIONS)
        with kernel_errors():
            copies = swept_sections(path, shape, n)
            points = [c.point_at(np.array([0.0, 0.5, 1.0])) for c in copies]
            if not all(np.all(np.isfinite(p)) for p in points):
                raise NodeWarning("The rail has no tangent somewhere (a cusp or a standstill), so it "
                                  "cannot be swept")
            return nurbs_surface.Loft(copies, samples=SAMPLES)
