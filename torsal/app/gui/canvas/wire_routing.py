"""Wire routing: a wire bends around the nodes it does not connect to.

A wire is the usual horizontal-tangent bezier from its output to its input. When that
curve would cross another node's rectangle, it takes a detour instead: it leaves its
output, runs above (or below, whichever is the shorter way) the nodes in its way, and
comes back down to its input, each bend a horizontal-tangent curve, so it still reads
as one wire. Backward wires (an input to the left of its output) keep their loop.

Cheap on purpose (the canvas holds graphs of thousands of nodes): node rectangles sit in
a coarse grid (:class:`NodeGrid`), a wire looks only at the nodes in the cells its curve
covers, and a curve is sampled only when such a node overlaps its bounding box.
"""

from __future__ import annotations

import itertools
from collections.abc import Iterable

from PySide6.QtCore import QPointF, QRectF
from PySide6.QtGui import QPainterPath

CELL = 240.0  # grid cell, scene units: a few nodes wide
CLEAR = 10.0  # how far a detour passes from the nodes it goes round
MIN_DX = 40.0  # the shortest tangent of a plain wire (as before routing)
MAX_TRIES = 4  # detours widened to take in nodes the previous detour hit

Box = tuple[float, float, float, float]  # left, top, right, bottom


class NodeGrid:
    """Node rectangles indexed by the grid cells they cover."""

    def __init__(self) -> None:
        self.boxes: dict[str, Box] = {}
        self._cells_of: dict[str, list[tuple[int, int]]] = {}
        self._cells: dict[tuple[int, int], set[str]] = {}

    def clear(self) -> None:
        self.boxes.clear()
        self._cells_of.clear()
        self._cells.clear()

    @staticmethod
    def _cover(box: Box) -> list[tuple[int, int]]:
        x0, y0 = int(box[0] // CELL), int(box[1] // CELL)
        x1, y1 = int(box[2] // CELL), int(box[3] // CELL)
        return [(i, j) for i in range(x0, x1 + 1) for j in range(y0, y1 + 1)]

    def set(self, node_id: str, rect: QRectF) -> None:
        """Place (or move) ``node_id`` at scene rectangle ``rect``."""
        box = (rect.left(), rect.top(), rect.right(), rect.bottom())
        if self.boxes.get(node_id) == box:
            return
        cells = self._cover(box)
        old = self._cells_of.get(node_id)
        if old != cells:
            for cell in old or ():
                members = self._cells.get(cell)
                if members is not None:
                    members.discard(node_id)
                    if not members:
                        del self._cells[cell]
            for cell in cells:
                self._cells.setdefault(cell, set()).add(node_id)
            self._cells_of[node_id] = cells
        self.boxes[node_id] = box

    def remove(self, node_id: str) -> None:
        for cell in self._cells_of.pop(node_id, ()):
            members = self._cells.get(cell)
            if members is not None:
                members.discard(node_id)
                if not members:
                    del self._cells[cell]
        self.boxes.pop(node_id, None)

    def overlapping(self, box: Box, skip: tuple[str, ...] = ()) -> dict[str, Box]:
        """The nodes whose rectangles overlap ``box``, but those in ``skip``."""
        found: dict[str, Box] = {}
        x0, y0 = int(box[0] // CELL), int(box[1] // CELL)
        x1, y1 = int(box[2] // CELL), int(box[3] // CELL)
        if (x1 - x0 + 1) * (y1 - y0 + 1) > len(self._cells):  # a huge box: look at every cell
            cells: Iterable[set[str]] = self._cells.values()
        else:
            cells = (self._cells.get((i, j), ()) for i in range(x0, x1 + 1) for j in range(y0, y1 + 1))
        for members in cells:
            for node_id in members:
                if node_id in skip or node_id in found:
                    continue
                other = self.boxes[node_id]
                if other[0] < box[2] and other[2] > box[0] and other[1] < box[3] and other[3] > box[1]:
                    found[node_id] = other
        return found


def _cubic_points(
    p0: QPointF, p1: QPointF, p2: QPointF, p3: QPointF, count: int
) -> list[tuple[float, float]]:
    points = []
    for k in range(count + 1):
        t = k / count
        u = 1.0 - t
        a, b, c, d = u * u * u, 3 * u * u * t, 3 * u * t * t, t * t * t
        points.append(
            (
                a * p0.x() + b * p1.x() + c * p2.x() + d * p3.x(),
                a * p0.y() + b * p1.y() + c * p2.y() + d * p3.y(),
            )
        )
    return points


def _samples(length: float) -> int:
    return max(8, min(64, int(length / 12.0)))


def _hits(points: list[tuple[float, float]], boxes: dict[str, Box]) -> dict[str, Box]:
    """The boxes a polyline through ``points`` enters (each segment tested against each box)."""
    hit: dict[str, Box] = {}
    for node_id, (left, top, right, bottom) in boxes.items():
        for (ax, ay), (bx, by) in itertools.pairwise(points):
            if _segment_meets_box(ax, ay, bx, by, left, top, right, bottom):
                hit[node_id] = (left, top, right, bottom)
                break
    return hit


def _segment_meets_box(
    ax: float, ay: float, bx: float, by: float, left: float, top: float, right: float, bottom: float
) -> bool:
    """Whether segment a–b passes through the box (Liang–Barsky clipping)."""
    t0, t1 = 0.0, 1.0
    dx, dy = bx - ax, by - ay
    for p, q in ((-dx, ax - left), (dx, right - ax), (-dy, ay - top), (dy, bottom - ay)):
        if p == 0.0:
            if q < 0.0:
                return False
            continue
        r = q / p
        if p < 0.0:
            t0 = max(t0, r)
        else:
            t1 = min(t1, r)
        if t0 > t1:
            return False
    return True


def plain_controls(start: QPointF, end: QPointF) -> tuple[QPointF, QPointF]:
    """The control points of a plain wire: horizontal tangents, longer for longer wires."""
    dx = max(MIN_DX, abs(end.x() - start.x()) * 0.5)
    return QPointF(start.x() + dx, start.y()), QPointF(end.x() - dx, end.y())


def plain_path(start: QPointF, end: QPointF) -> QPainterPath:
    c1, c2 = plain_controls(start, end)
    path = QPainterPath(start)
    path.cubicTo(c1, c2, end)
    return path


def _bend(start: QPointF, end: QPointF) -> tuple[QPointF, QPointF]:
    """A detour's bend: horizontal tangents no longer than half the run, so it never
    overshoots sideways into what it goes round."""
    dx = max(1.0, abs(end.x() - start.x()) * 0.5)
    return QPointF(start.x() + dx, start.y()), QPointF(end.x() - dx, end.y())


def _detour(start: QPointF, end: QPointF, around: Box) -> tuple[QPainterPath, list[tuple[float, float]]]:
    """A path from ``start`` to ``end`` over or under ``around`` (the shorter way), and
    points along it for checking."""
    left, top, right, bottom = around
    above, below = top - CLEAR, bottom + CLEAR
    cost_above = abs(start.y() - above) + abs(end.y() - above)
    cost_below = abs(start.y() - below) + abs(end.y() - below)
    y = above if cost_above <= cost_below else below
    # the level run spans the obstacles, kept within the wire's own extent
    run_left = min(max(left - CLEAR, start.x() + 1.0), end.x() - 2.0)
    run_right = max(min(right + CLEAR, end.x() - 1.0), run_left + 1.0)
    a, b = QPointF(run_left, y), QPointF(run_right, y)
    c1, c2 = _bend(start, a)
    c3, c4 = _bend(b, end)
    path = QPainterPath(start)
    path.cubicTo(c1, c2, a)
    path.lineTo(b)
    path.cubicTo(c3, c4, end)
    first = _cubic_points(start, c1, c2, a, _samples(abs(a.x() - start.x()) + abs(a.y() - start.y())))
    last = _cubic_points(b, c3, c4, end, _samples(abs(end.x() - b.x()) + abs(end.y() - b.y())))
    return path, [*first, *last]  # first's end and last's start join in the level run


def _union(boxes: Iterable[Box]) -> Box:
    boxes = list(boxes)
    return (
        min(b[0] for b in boxes),
        min(b[1] for b in boxes),
        max(b[2] for b in boxes),
        max(b[3] for b in boxes),
    )


def _grown(boxes: dict[str, Box]) -> dict[str, Box]:
    """Boxes with half the clearance added: a wire grazing a node's edge counts as crossing."""
    m = CLEAR / 2
    return {k: (b[0] - m, b[1] - m, b[2] + m, b[3] + m) for k, b in boxes.items()}


def route(
    start: QPointF, end: QPointF, grid: NodeGrid | None, ends: tuple[str, str] = ("", "")
) -> QPainterPath:
    """The path of a wire from ``start`` to ``end`` that avoids the nodes in ``grid`` other
    than ``ends`` (the two it connects)."""
    sx, sy, ex, ey = start.x(), start.y(), end.x(), end.y()
    if grid is None or ex - sx < 4 * CLEAR:  # no grid, or a backward wire: its loop
        return plain_path(start, end)
    # the plain curve lies within its end points' box widened by its first tangent
    box = (sx, min(sy, ey) - CLEAR, max(ex, sx + max(MIN_DX, (ex - sx) * 0.5)), max(sy, ey) + CLEAR)
    near = grid.overlapping(box, ends)
    if not near:
        return plain_path(start, end)
    c1, c2 = plain_controls(start, end)
    length = abs(end.x() - start.x()) + abs(end.y() - start.y())
    points = _cubic_points(start, c1, c2, end, _samples(length))
    blocking = _hits(points, _grown(near))
    if not blocking:
        return plain_path(start, end)
    path = plain_path(start, end)
    for _ in range(MAX_TRIES):
        around = _union(near[k] for k in blocking)
        path, points = _detour(start, end, around)
        reach = (
            min(start.x(), around[0]) - CLEAR,
            min(start.y(), end.y(), around[1] - 2 * CLEAR),
            max(end.x(), around[2]) + CLEAR,
            max(start.y(), end.y(), around[3] + 2 * CLEAR),
        )
        near.update(grid.overlapping(reach, ends))
        more = _hits(points, _grown(near))
        more = {k: v for k, v in more.items() if k not in blocking}
        if not more:
            break
        blocking.update(more)
    return path
