"""analysis.VectorAnalysis: cross product, dot product and angle of two lists of vectors.

The arithmetic is one vectorised numpy pass over all pairs (:func:`vector_products`);
what costs time at 10⁶ pairs is turning engine :class:`~torsal.engine.values.Vector` tuples
into arrays and back, which :func:`as_array` and :func:`as_vectors` do in bulk.
"""

from __future__ import annotations

import gc
import itertools
from collections.abc import Iterator, Sequence
from contextlib import contextmanager
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from torsal.engine.node import LIST, In, Node, NodeWarning, Out
from torsal.engine.types import NUMBER, VECTOR
from torsal.engine.values import Vector
from torsal.nodes.geometry.array_types import FloatArray

#: Above this many items, conversions pause the garbage collector: creating a million
#: tuples otherwise triggers dozens of full collections and takes 3–4× as long.
BULK = 10_000


@contextmanager
def _bulk(n: int) -> Iterator[None]:
    """Pause garbage collection while ``n`` new objects are made (only for large n)."""
    pause = n >= BULK and gc.isenabled()
    if pause:
        gc.disable()
    try:
        yield
    finally:
        if pause:
            gc.enable()


def as_array(name: str, items: Sequence[Any]) -> FloatArray:
    """A list of engine vectors (3-tuples) as an ``(n, 3)`` array, in one pass.

    Raises :class:`NodeWarning` naming the first empty (null) or non-finite item.
    """
    n = len(items)
    try:
        array = np.fromiter(itertools.chain.from_iterable(items), dtype=float, count=3 * n)
    except (TypeError, ValueError):
        empty = next((i for i, v in enumerate(items) if v is None), None)
        if empty is not None:
            raise NodeWarning(f"{name} has an empty (null) item at index {empty}: remove it or fix "
                              "what made it") from None
        raise NodeWarning(f"{name} has an item that is not a vector of three numbers") from None
    array = array.reshape(n, 3)
    bad = ~np.isfinite(array).all(axis=1)
    if bad.any():
        first = int(np.flatnonzero(bad)[0])
        raise NodeWarning(f"{name} has {int(bad.sum())} vectors with a coordinate that is not a finite "
                          f"number (NaN or infinite), the first at index {first}")
    return array


def as_vectors(array: ArrayLike) -> list[Vector]:
    """An ``(n, 3)`` array as engine vectors, in bulk (~0.3 s per million)."""
    values = np.asarray(array, dtype=float).reshape(-1, 3)
    with _bulk(len(values)):
        return Vector.many(values.tolist())


@dataclass(frozen=True)
class VectorProducts:
    """Cross products ``(n, 3)``, dot products ``(n,)`` and angles ``(n,)`` (rad, 0 … π) of
    n pairs; ``zero`` flags the pairs with a zero-length vector (their angle is 0)."""

    cross: FloatArray
    dot: FloatArray
    angle: FloatArray
    zero: NDArray[np.bool_]


def longest_list(a: FloatArray, b: FloatArray) -> tuple[FloatArray, FloatArray]:
    """Match two lists item by item, the shorter repeating its last item (Grasshopper's
    longest list): both come back with max(len(a), len(b)) rows."""
    n = max(len(a), len(b))
    if len(a) < n:
        a = a[np.minimum(np.arange(n), len(a) - 1)]
    if len(b) < n:
        b = b[np.minimum(np.arange(n), len(b) - 1)]
    return a, b


def vector_products(a: ArrayLike, b: ArrayLike) -> VectorProducts:
    """Cross product, dot product and angle of the pairs (a_i, b_i), all at once.

    ``a`` and ``b`` are ``(n, 3)`` and ``(m, 3)`` arrays, matched by :func:`longest_list`.
    The results are numpy's, bit for bit: ``np.cross(a, b)``, the row-wise dot product
    ``einsum("ij,ij->i")`` and ``arccos(clip(a·b / (|a| |b|), −1, 1))`` with the lengths
    from ``np.linalg.norm``. Where a or b has zero length the angle is 0 — a zero
    vector is parallel to every vector, so that |a × b| = |a||b| sin θ and
    a·b = |a||b| cos θ still hold — and ``zero`` is set.
    Vectors so small or large that |a||b| under- or overflows are normalised first.

    >>> p = vector_products([[1, 0, 0]], [[0, 2, 0]])
    >>> p.cross.tolist(), p.dot.tolist(), round(float(p.angle[0]), 6)
    ([[0.0, 0.0, 2.0]], [0.0], 1.570796)
    """
    a, b = longest_list(np.asarray(a, dtype=float).reshape(-1, 3), np.asarray(b, dtype=float).reshape(-1, 3))
    with np.errstate(all="ignore"):  # huge vectors may overflow Cross and Dot to ±inf, as they should
        cross = np.cross(a, b)
        dot = np.einsum("ij,ij->i", a, b)
        length_a = np.linalg.norm(a, axis=1)
        length_b = np.linalg.norm(b, axis=1)
        cosine = dot / (length_a * length_b)
    zero = ~(a != 0.0).any(axis=1) | ~(b != 0.0).any(axis=1)
    awkward = ~zero & ~np.isfinite(cosine)
    if awkward.any():  # |a||b| under- or overflowed: scale each vector to unit size first
        ua = a[awkward] / np.abs(a[awkward]).max(axis=1, keepdims=True)
        ub = b[awkward] / np.abs(b[awkward]).max(axis=1, keepdims=True)
        ua /= np.linalg.norm(ua, axis=1, keepdims=True)
        ub /= np.linalg.norm(ub, axis=1, keepdims=True)
        cosine[awkward] = np.einsum("ij,ij->i", ua, ub)
    angle = np.arccos(np.clip(cosine, -1.0, 1.0))
    angle[zero] = 0.0
    return VectorProducts(cross, dot, angle, zero)


class VectorAnalysis(Node):
    """Cross product, dot product and angle of two lists of vectors, pair by pair.

    The thesis's check of developability at a ruling: with the ruling R and the edge
    tangents T1, T2 at its ends, the normals are N1 = R × T1 and N2 = R × T2 (Cross),
    and the ruling is torsal — the surface developable there — when the Angle between
    N1 and N2 is 0 (or π: the normals' lines coincide).

    A and B are matched item by item; when one list is shorter its last vector is
    reused (longest list), so one B against a list of A compares each A with it.
    Angle is in radians, from 0 (same direction) through π/2 (perpendicular) to π
    (opposite). A zero-length vector has no direction: its Angle is given as 0 (it
    is parallel to everything, and Cross and Dot are 0 with it) and the node warns;
    check where it came from (two equal points make a zero vector). A million pairs
    take a fraction of a second.
    """

    type_id = "analysis.VectorAnalysis"
    nickname, aliases = "VecA", ("Cross Product", "Dot Product", "Vector Angle")
    inputs = (
        In("A", VECTOR, "A", "The first vectors.", access=LIST),
        In("B", VECTOR, "B", "The second vectors; the shorter list reuses its last vector.",
           access=LIST),
    )
    outputs = (
        Out("Cross", VECTOR, "X", "A × B: perpendicular to both, |A||B| sin(angle) long.", access=LIST),
        Out("Dot", NUMBER, "D", "A · B = |A||B| cos(angle): 0 when perpendicular.", access=LIST),
        Out("Angle", NUMBER, "θ", "The angle between A and B in radians, 0 to π (0 for a zero vector).",
            access=LIST),
    )

    def solve(self, a: list[Any], b: list[Any]) -> tuple[list[Vector], list[float], list[float]]:
        first, second = as_array("A", a), as_array("B", b)
        if len(first) == 0 or len(second) == 0:
            raise NodeWarning(f"{'A' if len(first) == 0 else 'B'} has no vectors")
        if len(first) != len(second):
            short, long_ = ("A", "B") if len(first) < len(second) else ("B", "A")
            counts = sorted((len(first), len(second)))
            self.remark(f"{long_} has {counts[1]} vectors, {short} has {counts[0]}: {short}'s last "
                        "vector is reused for the rest")
        result = vector_products(first, second)
        if result.zero.any():
            where = int(np.flatnonzero(result.zero)[0])
            self.warn(f"{int(result.zero.sum())} of {len(result.zero)} pairs have a zero-length vector "
                      f"(the first at index {where}): it has no direction, so their Angle is set to 0")
        with _bulk(len(result.dot)):
            return as_vectors(result.cross), result.dot.tolist(), result.angle.tolist()
