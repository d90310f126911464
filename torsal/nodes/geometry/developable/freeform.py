"""Rationalise a freeform design: which layout of strips to make, rings or parameter lines.

Strips between parameter lines of one family (:func:`.rationalise.rationalise`) are smooth
wherever a family runs clear of the design's asymptotic directions. Where *both* families
cross them (:mod:`.asymptotic`: a design with two bumps and a valley between them), every
line from edge to edge passes where no smooth torsal strip can follow it, and the strips
crease there. Such a design is first laid out with strips between traced lines of
curvature that ring each of its bumps (:mod:`.ring_layout`); that layout is kept when it
is within the tolerance, covers the design's edge and has little of its area in fans,
and the parameter lines are used otherwise (their result then says why the rings were
not kept and, where one place says it, where: ``rings_refused``, ``rings_where``) — and
always with guides or a direction, which say which way the strips must run.

This choice sits above both layouts: a ring layout rationalises the caps round its bumps
between parameter lines (:mod:`.trimmed`), so it cannot live in :mod:`.rationalise`.
docs/geometry.md tells the whole method.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

import numpy as np
from numpy.typing import ArrayLike

from ..array_types import FloatArray
from ..curve_base import Curve
from ..surface_base import Surface
from .asymptotic import asymptotic_crossings
from .rationalise import Rationalisation, fan_area, rationalise
from .ring_layout import RingsRefused, ring_layout

#: Where both families of parameter lines cross asymptotic directions more than this
#: (:mod:`.asymptotic`: the double bump's 0.76 and 0.38; every other test design has a
#: family at 0), strips ringing the design's bumps along lines of curvature are tried
#: first (:mod:`.ring_layout`) ...
RINGS = 0.1
#: ... and kept when within the tolerance, covering the design's edge, with at most this
#: share of their area in fans (the issue's bar); the parameter lines otherwise.
RING_FANS = 0.1


def rationalise_freeform(
    design: Surface,
    tolerance: float,
    max_strips: int = 64,
    direction: ArrayLike | None = None,
    segments: int = 24,
    warp_tolerance: float = 1e-7,
    progress: Callable[[float], None] | None = None,
    guides: Sequence[Curve] = (),
    min_width: float = 0.0,
) -> Rationalisation:
    """Developable strips within ``tolerance`` of ``design``: rings round its bumps where
    both families of parameter lines cross its asymptotic directions and the rings are
    good (see the module), otherwise :func:`.rationalise.rationalise` with the same
    arguments (which also says what is wrong with a tolerance or a closed design)."""
    refused: tuple[str, FloatArray | None] | None = None
    if not guides and direction is None and _rings_worth_trying(design, tolerance):
        rings = _rings(design, tolerance, int(max_strips), segments, warp_tolerance, min_width)
        if isinstance(rings, Rationalisation):
            return rings
        refused = rings
    found = rationalise(design, tolerance, max_strips, direction, segments, warp_tolerance, progress, guides,
                        min_width)
    if refused is not None:
        found.rings_refused, found.rings_where = refused
    return found


def _rings_worth_trying(design: Surface, tolerance: float) -> bool:
    """Whether both families of ``design``'s parameter lines cross its asymptotic directions
    more than :data:`RINGS` (a usable tolerance and an open design only: the parameter lines'
    own checks name anything else)."""
    if not (tolerance > 0.0 and np.isfinite(tolerance)) or design.closed_u or design.closed_v:
        return False
    return min(asymptotic_crossings(design, family) for family in ("u", "v")) > RINGS


def _rings(design: Surface, tolerance: float, max_strips: int, segments: int, warp_tolerance: float,
           min_width: float) -> Rationalisation | tuple[str, FloatArray | None]:
    """The strips round the design's bumps (:mod:`.ring_layout`) when they are within the
    tolerance, cover the design's edge and keep at most :data:`RING_FANS` in fans; else why
    not (a phrase, with the distance) and where (a point, None when no one place says it)."""
    try:
        found = ring_layout(design, tolerance, max_strips, segments, warp_tolerance, min_width,
                            RING_FANS)
    except RingsRefused as exc:
        return str(exc), exc.where
    except ValueError as exc:
        return str(exc), None
    if not found.within:
        far = max(found.strips, key=lambda s: s.deviation)
        return f"a strip between them is {far.deviation:.4g} from the design", far.where
    if not found.covered:
        k = int(np.argmax(found.edge_gaps))
        return f"they leave the design's edge uncovered by {found.coverage:.4g}", found.edge_points[k]
    fans = fan_area(found.strips)
    if fans > RING_FANS:
        return f"{fans:.0%} of their area is in flat fans (at most {RING_FANS:.0%} is kept)", None
    return found
