"""developable.RulingDevelopable: the developable strip between two space curves."""

from __future__ import annotations

from collections.abc import Collection, Sequence
from typing import Any, NamedTuple

import numpy as np

from torsal.engine.node import LIST, In, Node, NodeError, NodeWarning, Out
from torsal.engine.types import BOOLEAN, INTEGER, NUMBER, POINT, TEXT
from torsal.nodes.common.checks import angle as angle_input
from torsal.nodes.common.checks import segments as segments_input
from torsal.nodes.common.checks import tolerance as tolerance_input
from torsal.nodes.common.convert import sentence
from torsal.nodes.common.geometry_checks import curve as curve_input
from torsal.nodes.common.geometry_checks import curves_with_length
from torsal.nodes.common.strip_folds import FoldReport, fold_report, fold_reports, strips_crossings
from torsal.nodes.common.strip_outputs import (
    WARP_HELP,
    StripOutputs,
    curve_strip_outputs,
    curve_strips_outputs,
)
from torsal.nodes.common.values import CURVE, LINE, SURFACE
from torsal.nodes.geometry.coincidence import coincident, ends_differ_each
from torsal.nodes.geometry.curve_base import Curve
from torsal.nodes.geometry.curves.line import Line
from torsal.nodes.geometry.curves.shared_knots import partitions_kept
from torsal.nodes.geometry.developable import RulingResult, ruling_developable, ruling_developables
from torsal.nodes.geometry.developable.alternatives import align_b, better_pairing
from torsal.nodes.geometry.developable.kinds import RulingKinds, ruling_kinds, ruling_kinds_all
from torsal.nodes.geometry.developable.measure import within_tolerance
from torsal.nodes.geometry.developable.stack import Stack
from torsal.nodes.geometry.developable.warp import curve_warps
from torsal.nodes.geometry.local_frame import LocalFrame
from torsal.nodes.geometry.strip_crossings import Crossings
from torsal.nodes.geometry.vec_ops import norm, position_roundings, rounding_of
from torsal.nodes.geometry.watch import watched
from torsal.nodes.limits import MAX_SEGMENTS, MAX_STRIP_RULINGS, MAX_STRIP_SOLVES


class _Row(NamedTuple):
    """One call's checked inputs, its curves moved into a frame anchored at them (solved,
    checked and measured there as at the world origin; site coordinates round only when
    the outputs are moved back)."""

    a: Curve
    b: Curve
    segments: int
    tolerance: float
    fan_limit: float
    crease_angle: float
    frame: LocalFrame
    #: why b is CurveB reversed, completing "CurveB runs against CurveA" (:func:`align_b`); "" if it is not
    reversed_b: str = ""


#: One call's checked inputs, the curves where they are: CurveA, CurveB, Segments,
#: WarpTolerance, FanLimit and CreaseAngle.
_Checked = tuple[Curve, Curve, int, float, float, float]


def _arguments(
    curve_a: Any, curve_b: Any, segments: Any, tolerance: Any, fan_limit: Any, crease_angle: Any,
    with_length: Collection[int] = (), apart: bool = False,
) -> _Checked:
    """One call's checked inputs: the curves (never one curve twice), Segments,
    WarpTolerance, FanLimit and CreaseAngle. The curves whose ids are in ``with_length``
    are known to have a length, and with ``apart`` their ends lie apart, so they are not
    one curve (found for every row at once: :meth:`RulingDevelopable.solve_many`)."""
    a = curve_a if id(curve_a) in with_length else curve_input("CurveA", curve_a)
    b = curve_b if id(curve_b) in with_length else curve_input("CurveB", curve_b)
    n = segments_input(segments)
    tol = tolerance_input("WarpTolerance", tolerance)
    limit = fan_limit_input(fan_limit)
    sharp = angle_input("CreaseAngle", crease_angle, "0.5", largest=np.pi)
    if not apart:
        _distinct(a, b)
    return a, b, n, tol, limit, sharp


def _placed(checked: _Checked, frame: LocalFrame) -> _Row:
    """The row of one call's ``checked`` inputs, its curves moved into ``frame`` (anchored at them)."""
    a, b, *rest = checked
    return _Row(frame.to_local(a), frame.to_local(b), *rest, frame)


def _flipped(row: _Row, reversed_b: tuple[Curve, str] | None) -> _Row:
    """``row`` with CurveB reversed where :func:`align_b` reversed it, and why."""
    return row if reversed_b is None else row._replace(b=reversed_b[0], reversed_b=reversed_b[1])


def _distinct(curve_a: Curve, curve_b: Curve) -> None:
    """Refuses one curve given as both edges."""
    if coincident(curve_a, curve_b):
        raise NodeError(
            "CurveA and CurveB are the same curve, so there is no strip between them: "
            "give two different edges (e.g. a bottom and a top curve)"
        )


def solve_strip(curve_a: Curve, curve_b: Curve, segments: int, tolerance: float) -> RulingResult:
    """The kernel's strip between two checked curves, with its errors as node errors."""
    _distinct(curve_a, curve_b)
    try:
        return ruling_developable(curve_a, curve_b, segments, tolerance)
    except ValueError as exc:
        raise NodeError(sentence(exc)) from None


def _tips(starts: np.ndarray, ends: np.ndarray) -> np.ndarray:
    """The first and last rulings where they have zero length (to rounding): the curves
    meet there and the strip tapers to a point."""
    columns = np.concatenate([starts.T, ends.T], axis=1)  # (3, 2n): as extent() reduces them
    size = float((columns.max(axis=1) - columns.min(axis=1)).max()) or 1.0
    tip = np.zeros(len(starts), dtype=bool)
    first_last = slice(None, None, max(len(starts) - 1, 1))
    tip[first_last] = norm(ends[first_last] - starts[first_last]) <= 1e-12 * size
    return tip


def _valid_and_tips(
    strips: list[tuple[_Row, RulingResult, np.ndarray]],
) -> list[tuple[np.ndarray, np.ndarray]]:
    """For each strip ``(row, result, warp)`` (finite rulings, two or more): whether each
    ruling's recomputed ``warp`` is within WarpTolerance (:func:`within_tolerance`, allowing
    for the rounding of the strip's world position, as :func:`rounding_of` its frame's origin
    allows one strip at a time) and its tips (:func:`_tips`), of every strip at once."""
    if not strips:
        return []
    rulings = Stack.of([result.starts for _, result, _ in strips])
    starts = np.concatenate([result.starts for _, result, _ in strips])
    ends = np.concatenate([result.ends for _, result, _ in strips])
    # the rounding of the larger of each strip's position roundings: of its starts, its ends
    # and (the least there is, in its frame) its origin
    origins = np.array([row.frame.origin for row, _, _ in strips])
    largest = np.maximum(rulings.reduce_max(np.maximum(np.abs(starts), np.abs(ends))).max(axis=1),
                         np.abs(origins).max(axis=1))
    rounding = rulings.repeat(position_roundings(largest))
    tolerance = rulings.repeat(np.array([row.tolerance for row, _, _ in strips]))
    warp = np.concatenate([warp for _, _, warp in strips])
    valid = within_tolerance(warp, tolerance, starts, ends, rounding)
    # the tips: first and last rulings of no length, to 1e-12 of the strip's size (1 if it has none)
    low = np.minimum(rulings.reduce_min(starts), rulings.reduce_min(ends))
    size = (np.maximum(rulings.reduce_max(starts), rulings.reduce_max(ends)) - low).max(axis=1)
    ends_of = np.concatenate([rulings.starts, rulings.offsets[1:] - 1])
    short = norm(ends[ends_of] - starts[ends_of]) <= 1e-12 * np.tile(np.where(size != 0.0, size, 1.0), 2)
    tips = np.zeros(len(starts), dtype=bool)
    tips[ends_of] = short
    return list(zip(rulings.split(valid), rulings.split(tips), strict=True))


def fan_limit_input(value: Any) -> float:
    """FanLimit: a share of the strip's area, from 0 to 1."""
    if value is None:
        raise NodeError("FanLimit is empty: give a share of the strip's area from 0 to 1, such as 0.1")
    x = float(value)
    if not (0.0 <= x <= 1.0):
        raise NodeError(f"FanLimit must be a share of the strip's area from 0 to 1, such as 0.1, not {x:g}")
    return x


class RulingDevelopable(Node):
    """The developable surface between two curves: find, for each point of CurveA, the
    ruling to CurveB along which the sheet has one tangent plane.

    Segments + 1 stations are spaced evenly along CurveA (by length). For each, the
    ruling to CurveB is *torsal*: the ruling and the two curves' tangents at its ends
    lie in one plane, so a flat sheet bent along it fits without twisting (warp 0).
    Every such partner on CurveB is found (the search is certified: two candidates
    close together are never missed between samples), solved to machine precision,
    and rulings never cross. Where the two curves bound a flat piece (two straight
    segments at an angle, like the middle of the ZVE roof edge) the strip is drawn as
    triangles: fans of rulings through single points, added to the station rulings.

    Where no torsal ruling exists over a stretch (the curves there bound no
    developable), the strip is closed by flat triangles, each with two corners on one
    curve and one on the other, so the Surface still spans both curves from end to
    end, stays developable (it unrolls exactly) and has no holes. Those rulings are
    marked Kind = "fan" and the node reports their share of the strip's area.

    At the strip's ends, where the curves' end points have no torsal partner (the
    usual case when both edges end on a rim), the end is closed by one cone through
    the end point of a curve, joined to the torsal rulings at the torsal ruling through
    that very point: the sheet stays smooth there (no fold) and exactly developable,
    so this is reported, never warned about. Fans that need apexes on both curves
    fold the sheet at every change of apex: the node warns when those take more than
    FanLimit of the area, and names swapping the curves or reversing CurveB only when
    it has solved that alternative and found it needs fewer of them. A CurveB drawn
    against CurveA (its torsal rulings run backwards along it, or its ends lie nearer
    CurveA's crossed than in order) is reversed for the solve, as a loft aligns its
    curves, when that closes less of the strip with fans — and, when fans close as much
    of the strip either way (nothing in the strip tells the two ways apart), when its ends
    say it runs against CurveA, as Rhino's Loft reads them: so CurveB drawn either way
    gives one strip. A remark says so.

    Kind tells each ruling what it is, recomputed from the output alone (its end points,
    the curves' exact tangents there and which ends it shares with its neighbours):

    - "torsal": the planes through the ruling and each curve's tangent agree within
      WarpTolerance; both curves are tangent to the sheet there. Valid.
    - "fan": inside a cone through one point of a curve (its neighbours on both sides
      share that end): the sheet is smooth and developable there, but the curve through
      the apex is not tangent to it. Valid (a cone is developable), never torsal.
    - "crease": the sheet folds along the ruling (a flat triangle through a point of A
      beside one through a point of B, or a fan turning back over itself). Never Valid.

    A torsal ruling whose warp is above WarpTolerance (a warped stretch) is "torsal" and
    not Valid. Torsal is the share of torsal, Valid rulings of the strip (fans and creases
    count against it), the number to maximise for a strip bent from one sheet; the mean of
    Valid also counts the fans. The node warns where the sheet folds by more than
    CreaseAngle or passes through itself (pairs of the strip's triangles, drawn between
    consecutive rulings, that cross), and Folds gives those places: the middle of each
    such crease, then a point of each crossing.
    """

    type_id = "developable.RulingDevelopable"
    nickname, aliases = "RDev", ("ruling", "developable", "developable loft", "Edge Surface")
    inputs = (
        In("CurveA", CURVE, "A", "The base curve: the rulings start at Segments + 1 points along it."),
        In("CurveB", CURVE, "B", "The other edge of the strip, running the same way as CurveA (drawn "
           "against it, it is reversed for the solve)."),
        In("Segments", INTEGER, "S", "Number of rulings minus one (1 or more).", default=24,
           min=1, max=MAX_SEGMENTS),
        In("WarpTolerance", NUMBER, "W",
           "Largest warp angle (rad) a ruling may keep and count as valid: the twist between "
           "the sheet's normals at its two ends. 0.01 rad is invisible on most sheets; for a "
           "material allowed k rad/m over rulings about L m long, use k·L.", default=0.01),
        In("FanLimit", NUMBER, "F",
           "Largest share of the strip's area (0 to 1) that may be closed by creased fans of flat "
           "triangles without a warning; 0.1 = 10 %. Smooth cones through one point never warn.",
           default=0.1),
        In("CreaseAngle", NUMBER, "C",
           "Creases of the sheet sharper than this angle (rad, the turn of its plane across the "
           "crease) are named in a warning and given in Folds; 0.5 rad is about 29°.", default=0.5),
    )
    outputs = (
        Out("Surface", SURFACE, "S", "The developable strip, lofted through its rulings."),
        Out("Rulings", LINE, "R", "The rulings from CurveA to CurveB, in order along the strip.",
            access=LIST),
        Out("WarpAngles", NUMBER, "W", f"{WARP_HELP} Recomputed from the output rulings and the "
            "curves' tangents.", access=LIST),
        Out("Valid", BOOLEAN, "V", "Whether each ruling's recomputed warp is a number within "
            "WarpTolerance.", access=LIST),
        Out("Kind", TEXT, "K",
            'Per ruling: "torsal" where both curves are tangent to the sheet (Valid when its warp is '
            'within WarpTolerance), "fan" inside a cone through one point of a curve (developable, '
            'Valid), "crease" where the sheet folds (never Valid).', access=LIST),
        Out("Torsal", NUMBER, "T", "The share of the strip's rulings that are torsal and Valid, 0 to 1 "
            "(fans and creases count against it)."),
        Out("Folds", POINT, "F", "Where the sheet creases by more than CreaseAngle (the middle of the "
            "ruling), then where its triangles cross each other.", access=LIST),
    )

    # a list of values multiplies the strips solved: bounded before the first (docs in limits)
    max_calls = MAX_STRIP_SOLVES
    max_work = MAX_STRIP_RULINGS
    work_unit = "rulings"

    def call_work(self, curve_a: Any, curve_b: Any, segments: Any, *rest: Any) -> int:
        return segments + 1 if isinstance(segments, int) and 1 <= segments <= MAX_SEGMENTS else 1

    def solve(
        self, curve_a: Any, curve_b: Any, segments: Any, tolerance: Any, fan_limit: Any, crease_angle: Any
    ) -> tuple[Any, list[Any], list[float], list[bool], list[str], float, list[Any]]:
        checked = _arguments(curve_a, curve_b, segments, tolerance, fan_limit, crease_angle)
        row = _placed(checked, LocalFrame.around(checked[0], checked[1]))
        self.check_cancelled()
        # (the inputs were rounded at their world coordinates: the kernel's tests that allow
        # for the rounding of positions allow for that, as a solve there would)
        with watched(self.check_cancelled), rounding_of(row.frame.origin):  # (the kernel looks at the token)
            job = (row.a, row.b, row.segments, row.tolerance)
            results = ruling_developables([job])
            flipped = align_b([job], results)[0]
            result = results[0]
        row = _flipped(row, flipped)
        if isinstance(result, ValueError):
            raise NodeError(sentence(result))
        return self._outputs(row, result)

    def solve_many(self, *columns: Sequence[Any]) -> list[Any] | None:
        """Every strip of the solve at once (:func:`ruling_developables`: each step of the
        kernel runs once for all of them), with each row's outputs and messages as
        :meth:`solve` gives them."""
        with partitions_kept():  # (each list of curves sorted by knots once in the solve's steps)
            return self._solve_rows(columns)

    def _solve_rows(self, columns: Sequence[Sequence[Any]]) -> list[Any]:
        """:meth:`solve_many`'s work."""
        checked: list[_Checked | NodeWarning] = []
        stop: Exception | None = None  # what ends the solve at a row, after the rows before it
        # the curves' lengths, and whether each row's two curves are one, looked at once for
        # all rows (each curve once: a roof's edge is two strips' curve)
        with_length = curves_with_length([*columns[0], *columns[1]])
        pairs = list(zip(columns[0], columns[1], strict=True))
        both = [id(a) in with_length and id(b) in with_length for a, b in pairs]
        differ = iter(ends_differ_each([pair for pair, ok in zip(pairs, both, strict=True) if ok]))
        apart = [ok and next(differ) for ok in both]
        for row, ends_apart in zip(zip(*columns, strict=True), apart, strict=True):
            try:
                checked.append(_arguments(*row, with_length=with_length, apart=ends_apart))
            except NodeWarning as exc:  # that row is refused, the others are made
                checked.append(exc)
            except Exception as exc:  # (solve raises it at that row, after the rows before)
                stop = exc
                break
        # each row's frame, around its two curves (their boxes found at once)
        curves = [row[:2] for row in checked if not isinstance(row, NodeWarning)]
        frames = iter(LocalFrame.around_each(curves))
        rows = [row if isinstance(row, NodeWarning) else _placed(row, next(frames)) for row in checked]
        jobs = [(r.a, r.b, r.segments, r.tolerance) for r in rows if not isinstance(r, NodeWarning)]
        self.check_cancelled()
        # (one rounding allowance for the batch: that of the strip farthest out, in practice
        # every strip of one model sits at the same site)
        far = np.array([r.frame.origin for r in rows if not isinstance(r, NodeWarning)] or [np.zeros(3)])
        with watched(self.check_cancelled), rounding_of(far):
            results = ruling_developables(jobs)
            flips = iter(align_b(jobs, results))
            rows = [row if isinstance(row, NodeWarning) else _flipped(row, next(flips)) for row in rows]
            # every strip's warp recomputed from its output rulings at once
            made = [(row, result) for row, result in zip(
                (row for row in rows if not isinstance(row, NodeWarning)), results, strict=True
            ) if not isinstance(result, ValueError)]
            warps = curve_warps([(row.a, row.b, r.s, r.t, r.starts, r.ends) for row, r in made])
            # what each ruling is, and where each strip's sheet passes through itself (of the
            # strips whose rulings make a strip: the others are refused by their outputs)
            whole = [len(r.starts) >= 2 and bool(np.isfinite(r.starts).all() and np.isfinite(r.ends).all())
                     for _, r in made]
            judged = iter(ruling_kinds_all([
                (row.a, row.b, r.s, r.t, r.starts, r.ends, row.tolerance, warp)
                for (row, r), warp, ok in zip(made, warps, whole, strict=True) if ok
            ]))
            kinds = [next(judged) if ok else None for ok in whole]
        # which rulings are within WarpTolerance, and the tips, of the strips whose rulings make one
        checked = iter(_valid_and_tips(
            [(row, r, warp) for (row, r), warp, ok in zip(made, warps, whole, strict=True) if ok]))
        checks = [next(checked) if ok else None for ok in whole]
        # the Surface, Rulings and WarpAngles of those strips, made together
        outs = iter(curve_strips_outputs([
            (row.a, row.b, r.s, r.t, r.starts, r.ends, row.tolerance, r.valid, warp, check[0])
            for (row, r), warp, ok, check in zip(made, warps, whole, checks, strict=True) if ok
        ]))
        strips = [next(outs) if ok else None for ok in whole]
        crossed = strips_crossings([(r.starts, r.ends) for _, r in made])
        # where those strips fold (each strip's report alone where it has one)
        reports = iter(fold_reports([
            (r.starts, r.ends, kind.crease_angle, row.crease_angle, row.frame.origin, crossing)
            for (row, r), kind, crossing in zip(made, kinds, crossed, strict=True) if kind is not None
        ]))
        folds = [None if kind is None else next(reports) for kind in kinds]
        per_strip = iter(zip(warps, kinds, checks, strips, crossed, folds, strict=True))
        solved = iter(results)
        outputs: list[Any] = []
        for row in rows:
            if isinstance(row, NodeWarning):
                self.refuse_row(row)
                outputs.append(None)
                continue
            result = next(solved)
            if isinstance(result, ValueError):
                raise NodeError(sentence(result))
            warp, kind, check, strip, crossing, fold = next(per_strip)
            try:
                if isinstance(strip, NodeWarning):
                    raise strip
                outputs.append(self._outputs(row, result, warp, kind, check, crossing, strip, fold))
            except NodeWarning as exc:
                self.refuse_row(exc)
                outputs.append(None)
        if stop is not None:
            raise stop
        return outputs

    def _outputs(
        self,
        row: _Row,
        result: RulingResult,
        warp: np.ndarray | None = None,
        kinds: RulingKinds | None = None,
        checks: tuple[np.ndarray, np.ndarray] | None = None,
        crossed: Crossings | None = None,
        strip: StripOutputs | None = None,
        folds: FoldReport | None = None,
    ) -> tuple[Any, list[Any], list[float], list[bool], list[str], float, list[Any]]:
        """The outputs of one strip from the kernel's result (and its recomputed ``warp``, its
        rulings' ``kinds``, which of them are within WarpTolerance and its tips
        (:func:`_valid_and_tips`), its self-crossings, its Surface, Rulings and WarpAngles
        (:func:`curve_strips_outputs`) and its folds (:func:`fold_reports`), where they are
        at hand), and what the node says of it."""
        valid, tip = checks if checks is not None else (None, None)
        a, b, n, tol, limit, sharp, frame, reversed_b = row
        if reversed_b:
            self.remark(f"CurveB runs against CurveA{reversed_b}: the strip is solved with CurveB reversed, "
                        "as a loft aligns its curves")
        # Valid from the warp recomputed from the output rulings and the curves' tangents
        with rounding_of(frame.origin):
            if strip is None:
                strip = curve_strip_outputs(
                    a, b, result.s, result.t, result.starts, result.ends, tol, result.valid, warp=warp,
                    valid=valid,
                )
            if kinds is None:
                kinds = ruling_kinds(a, b, result.s, result.t, result.starts, result.ends, tol, strip.warp)
        self.check_cancelled()
        if result.message:
            if result.creased_share > limit:
                with rounding_of(frame.origin):
                    hint = better_pairing(a, b, n, tol, result)
                text = f"{result.message}, above FanLimit {100 * limit:.3g} %"
                self.warn(f"{text}; {hint}" if hint else text)
            else:
                self.remark(result.message)
        if tip is None:
            tip = _tips(result.starts, result.ends)
        if tip.any():
            where = " and ".join(name for name, at in (("start", tip[0]), ("end", tip[-1])) if at)
            self.remark(f"the strip tapers to a point at its {where} (the curves meet there): the "
                        "warp of that zero-length ruling is undefined, so it is not Valid")
        # a fan ruling's or a tip's undefined warp is no news
        strip.report(self, explained=result.fan | tip)
        torsal_fans = int(np.count_nonzero(~result.stations & ~result.fan))
        if torsal_fans:
            self.remark(
                f"{len(result.s)} rulings: {n + 1} from the stations and {torsal_fans} in fans through "
                "single points (the flat triangles of the strip)"
            )
        if folds is None:
            folds = fold_report(result.starts, result.ends, kinds.crease_angle, sharp, frame.origin, crossed)
        if folds.message:
            self.warn(folds.message)
        surface, rulings = strip.surface, strip.rulings
        if not frame.is_world:
            surface = frame.to_world(surface)
            rulings = Line.many(frame.points_to_world(result.starts), frame.points_to_world(result.ends))
        valid = kinds.valid.tolist()
        return surface, rulings, strip.warp, valid, kinds.kind, kinds.torsal_share, folds.points
