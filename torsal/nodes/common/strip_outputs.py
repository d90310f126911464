"""What every surface-making toolbox node hands on: the loft of its rulings, the
rulings as lines, and their warp angles.

The thesis convention, kept here: a developable is *built on* its rulings, so the
output surface is the ruled surface whose rulings are exactly the output lines, and
the warp angles are reported with it so developability is visible, not assumed.

Every WarpAngles output means the same (see :mod:`torsal.nodes.geometry.developable.warp`):
the angle between the sheet's normal vectors at the ruling's two ends, 0 to π — the
turn of the tangent plane along the ruling, 0 where the ruling is torsal. Where no
tangent plane is defined (a zero-length ruling, a ruling along an edge's tangent) the
warp is NaN, never 0, and the node says so. A ruling called valid has had its warp
recomputed from the output rulings and found within the tolerance.
"""

from __future__ import annotations

from collections.abc import Sequence
from contextlib import suppress
from dataclasses import dataclass, field, replace

import numpy as np
from numpy.typing import ArrayLike

from torsal.engine.node import Node, NodeWarning
from torsal.nodes.geometry.array_types import BoolArray, FloatArray
from torsal.nodes.geometry.curve_base import Curve
from torsal.nodes.geometry.curve_rail import ruled_between, ruled_between_all
from torsal.nodes.geometry.curves.line import Line
from torsal.nodes.geometry.developable.measure import within_tolerance
from torsal.nodes.geometry.developable.warp import curve_warp, warp_angles, warp_of_rulings
from torsal.nodes.geometry.ruled import RuledSurface

#: The help text every WarpAngles output shares (a node may add a sentence).
WARP_HELP = (
    "Warp angle of each ruling, rad, 0 to π: the angle between the sheet's normals at its two "
    "ends, i.e. the turn of the tangent plane along it (0 = torsal, developable there; NaN where "
    "no tangent plane is defined)."
)


_UNDEFINED = "The warp is undefined (NaN) at"


@dataclass(frozen=True)
class StripOutputs:
    """``Surface``, ``Rulings`` and ``WarpAngles`` of one ruled strip, ready for a node,
    with ``Valid`` when a tolerance was given and the messages the node should show."""

    surface: RuledSurface
    rulings: list[Line]
    warp: list[float]
    valid: list[bool] | None = None
    messages: tuple[str, ...] = ()
    #: Where ``warp`` is NaN, when the maker had it at hand (else :meth:`report` finds it).
    undefined: BoolArray | None = field(default=None, repr=False, compare=False)

    def as_tuple(self) -> tuple[RuledSurface, list[Line], list[float]]:
        return self.surface, self.rulings, self.warp

    def report(self, node: Node, explained: ArrayLike | None = None) -> None:
        """Show the messages on ``node`` as warnings; the one about NaN warps is left out
        when every NaN ruling is among those ``explained`` (a mask the node has already
        warned about, saying that the warp is undefined there)."""
        for text in self.messages:
            if text.startswith(_UNDEFINED) and explained is not None:
                nan = self.undefined
                if nan is None:
                    nan = np.isnan(np.asarray(self.warp, dtype=float))
                if not (nan & ~np.asarray(explained, dtype=bool)).any():
                    continue
            node.warn(text)


def undefined_message(warp: ArrayLike) -> str | None:
    """The warning for NaN warps: how many, the first, and why; None when there are none."""
    return _undefined(np.asarray(warp, dtype=float))[1]


def _undefined(w: FloatArray) -> tuple[BoolArray, str | None]:
    """Where the warps ``w`` are NaN, and :func:`undefined_message`."""
    bad = np.isnan(w)
    if not bad.any():
        return bad, None
    return bad, (
        f"{_UNDEFINED} {int(bad.sum())} of {w.size} rulings (first: ruling "
        f"{int(np.argmax(bad))}): a ruling there has zero length or runs along an edge's tangent, "
        "so the sheet has no tangent plane to measure"
    )


def strip_outputs(
    starts: ArrayLike,
    ends: ArrayLike,
    tangents_a: ArrayLike | None = None,
    tangents_b: ArrayLike | None = None,
    *,
    warp: ArrayLike | None = None,
    apex_a: ArrayLike | None = None,
    apex_b: ArrayLike | None = None,
    surface: RuledSurface | None = None,
    source: str = "the inputs",
) -> StripOutputs:
    """Loft ``(n, 3)`` ruling ends into a ruled surface, with lines and warp angles.

    When the exact edge tangents are known (a cylinder's section curve, a tangent
    developable's edge) the warp uses them (``apex_a``/``apex_b`` flag ends on the edge
    of regression, see :func:`~torsal.nodes.geometry.developable.warp.warp_angles`); otherwise
    it uses the edge polylines' tangents (second-order accurate in the ruling spacing).
    A caller that has the warp angles already passes ``warp``. NaN warps stay NaN and
    add a message.

    Rulings that make no strip (fewer than two, a point that is not a finite number, no
    surface through them) are one item refused: a :class:`~torsal.engine.node.NodeWarning` naming
    ``source`` (the inputs the rulings were made from, as the node's user knows them), so
    this call's outputs are null and the node's other items are still made.
    """
    a, b = _checked(starts, ends, source)
    if warp is not None:
        w = np.asarray(warp, dtype=float)
    elif tangents_a is not None and tangents_b is not None:
        w = warp_angles(a, b, tangents_a, tangents_b, apex_a=apex_a, apex_b=apex_b)
    else:
        w = warp_of_rulings(a, b)
    if surface is None:  # (a caller with a better surface through these rulings passes it)
        surface = _loft(a, b, source)
    undefined, message = _undefined(w)
    messages = (message,) if message else ()
    return StripOutputs(surface, _lines(a, b), w.tolist(), messages=messages, undefined=undefined)


def _checked(starts: ArrayLike, ends: ArrayLike, source: str) -> tuple[FloatArray, FloatArray]:
    """The ruling ends as float arrays; refused (a :class:`~torsal.engine.node.NodeWarning` naming
    ``source``) when they make no strip: fewer than two, or a point that is not finite."""
    a = np.asarray(starts, dtype=float)
    b = np.asarray(ends, dtype=float)
    if len(a) < 2:
        raise NodeWarning(
            f"A strip needs at least two rulings; {source} gave {len(a)}: set Segments to 1 or more"
        )
    if not (np.isfinite(a).all() and np.isfinite(b).all()):
        raise NodeWarning(
            f"Some rulings have points that are not finite numbers: check {source} for NaN"
        )
    return a, b


def _loft(a: FloatArray, b: FloatArray, source: str) -> RuledSurface:
    """The loft through the rulings (:meth:`RuledSurface.from_rulings`), or the warning why not."""
    try:
        return RuledSurface.from_rulings(a, b)
    except ValueError as exc:
        raise NodeWarning(f"The rulings from {source} do not make a surface: {exc}") from None


def _lines(a: FloatArray, b: FloatArray) -> list[Line]:
    """The rulings as lines, from ends :func:`_checked` has passed (finite; ``(n, 3)`` unless a
    surface came with them, when :meth:`Line.many` takes whatever shape they have)."""
    return Line._of_rows(a, b) if a.shape == b.shape and a.shape[1:] == (3,) else Line.many(a, b)


def curve_strip_outputs(
    curve_a: Curve,
    curve_b: Curve,
    s: ArrayLike,
    t: ArrayLike,
    starts: ArrayLike,
    ends: ArrayLike,
    tolerance: float,
    claimed: ArrayLike | None = None,
    source: str = "CurveA and CurveB",
    warp: FloatArray | None = None,
    valid: BoolArray | None = None,
) -> StripOutputs:
    """The outputs of a strip between two curves whose rulings run from ``A(s)`` to ``B(t)``:
    the Surface whose edges run on the two curves through those rulings
    (:func:`~torsal.nodes.geometry.curve_rail.ruled_between`: its tangent plane along each ruling
    is the curves', so the warp measured on the surface is the warp reported), the warp
    recomputed from the output rulings with the curves' exact tangents
    (:func:`~torsal.nodes.geometry.developable.warp.curve_warp`), and ``valid`` where it is a
    number within ``tolerance`` (plus what the ends' rounding alone adds far from the
    origin, as the solver allows: :func:`~torsal.nodes.geometry.developable.measure.within_tolerance`).

    ``claimed`` is what the solver thought valid; rulings it accepted that the
    recomputation rejects are counted in a message. ``source`` names the inputs the curves
    come from in the warnings of :func:`strip_outputs`. ``warp`` is that recomputed warp
    where the caller has it (:func:`~torsal.nodes.geometry.developable.warp.curve_warps` of
    several strips at once), and ``valid`` its :func:`within_tolerance` where the caller has
    that too.
    """
    starts, ends = np.asarray(starts, dtype=float), np.asarray(ends, dtype=float)
    w = curve_warp(curve_a, curve_b, s, t, starts, ends) if warp is None else warp
    # edges on the curves themselves, so neighbouring strips meet exactly; parameters that
    # do not run one way keep the loft through the rulings (the rulings' ends are the
    # curves' points at s and t: the rails take them rather than evaluate them again)
    on_curves = None
    with suppress(ValueError):
        on_curves = ruled_between(curve_a, s, curve_b, t, points=(starts, ends))
    outputs = strip_outputs(starts, ends, warp=w, surface=on_curves, source=source)
    if valid is None:
        valid = within_tolerance(w, tolerance, starts, ends)
    messages = outputs.messages
    if claimed is not None:
        refused = np.asarray(claimed, dtype=bool) & ~valid & ~outputs.undefined
        messages += _refused_message(refused, w, tolerance)
    return replace(outputs, valid=valid.tolist(), messages=messages)


#: One strip of :func:`curve_strips_outputs`: CurveA, CurveB, s, t, starts, ends, the
#: tolerance, what the solver claimed valid (or None), the recomputed warp and its Valid.
CurveStrip = tuple[Curve, Curve, FloatArray, FloatArray, FloatArray, FloatArray, float, BoolArray | None,
                   FloatArray, BoolArray]


def curve_strips_outputs(
    strips: Sequence[CurveStrip], source: str = "CurveA and CurveB"
) -> list[StripOutputs | NodeWarning]:
    """:func:`curve_strip_outputs` of every strip of ``strips``, each with its recomputed
    warp and Valid, whose rulings are finite and two or more (the caller has checked what
    :func:`strip_outputs` checks): their Surfaces' rails fitted together
    (:func:`~torsal.nodes.geometry.curve_rail.ruled_between_all`), their lines made from
    one copy of all their ends, the NaN warps and the refused rulings found at once. Each
    strip's outputs are the ones it gets alone; a strip refused (no surface through its
    rulings) gets the NodeWarning in its place."""
    if not strips:
        return []
    on_curves = ruled_between_all([(a, s, b, t, (starts, ends)) for a, b, s, t, starts, ends, *_ in strips])
    counts = [len(strip[4]) for strip in strips]
    bounds = np.zeros(len(strips) + 1, dtype=np.int64)
    np.cumsum(counts, out=bounds[1:])
    starts = np.concatenate([strip[4] for strip in strips])
    ends = np.concatenate([strip[5] for strip in strips])
    warp = np.concatenate([strip[8] for strip in strips])
    valid = np.concatenate([strip[9] for strip in strips])
    undefined = np.isnan(warp)
    lines = _lines(starts, ends)  # (one copy of all ends; each line keeps a view of its rows)
    claimed = [strip[7] for strip in strips]
    # the rulings the solver accepted that the recomputation rejects, of the strips that say
    refused = np.zeros(len(warp), dtype=bool)
    for claim, low, high in zip(claimed, bounds[:-1].tolist(), bounds[1:].tolist(), strict=True):
        if claim is not None:
            refused[low:high] = claim
    refused &= ~valid & ~undefined
    news = np.logical_or.reduceat(refused | undefined, bounds[:-1]).tolist()  # (no strip is empty)
    made: list[StripOutputs | NodeWarning] = []
    for k, (strip, surface) in enumerate(zip(strips, on_curves, strict=True)):
        low, high = int(bounds[k]), int(bounds[k + 1])
        if isinstance(surface, ValueError):  # the loft through the rulings
            try:
                surface = _loft(strip[4], strip[5], source)
            except NodeWarning as exc:
                made.append(exc)
                continue
        w = warp[low:high]
        messages: tuple[str, ...] = ()
        if news[k]:
            message = _undefined(w)[1]
            messages = (message,) if message else ()
            messages += _refused_message(refused[low:high], w, strip[6])
        made.append(StripOutputs(surface, lines[low:high], w.tolist(), valid[low:high].tolist(), messages,
                                 undefined[low:high]))
    return made


def _refused_message(refused: BoolArray, warp: FloatArray, tolerance: float) -> tuple[str, ...]:
    """The message counting the rulings the solver accepted that the recomputation
    rejects (``refused``), if there are any."""
    if not refused.any():
        return ()
    return (
        f"{int(refused.sum())} rulings the solver accepted have a recomputed warp above "
        f"{tolerance:g} rad (largest {float(warp[refused].max()):.3g} rad, first: ruling "
        f"{int(np.argmax(refused))}): they are marked Valid = false",
    )
