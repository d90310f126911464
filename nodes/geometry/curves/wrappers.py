"""Generic reversed and transformed views of any curve (NURBS, lines and polylines
override these with exact new curves)."""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from ..curve_base import Curve, FloatArray
from ..transforms import check_matrix, is_affine


class ReversedCurve(Curve):
    """``C(1 − t)`` for a wrapped curve C; the k-th derivative gains a factor (−1)^k."""

    def __init__(self, curve: Curve) -> None:
        self.curve = curve
        self.closed = curve.closed
        a, b = curve.domain
        self.domain = (-b, -a)

    def derivatives(self, t: ArrayLike, order: int = 1) -> list[FloatArray]:
        t = np.atleast_1d(np.asarray(t, dtype=float)).reshape(-1)
        values = self.curve.derivatives(1.0 - t, order)
        return [v if k % 2 == 0 else -v for k, v in enumerate(values)]

    @property
    def anchor(self) -> FloatArray:
        return self.curve.anchor

    def local_derivatives(self, t: ArrayLike, order: int = 1) -> list[FloatArray]:
        t = np.atleast_1d(np.asarray(t, dtype=float)).reshape(-1)
        values = self.curve.local_derivatives(1.0 - t, order)
        return [v if k % 2 == 0 else -v for k, v in enumerate(values)]

    def _breakpoints(self) -> FloatArray:
        return np.sort(1.0 - self.curve._breakpoints())

    def reversed(self) -> Curve:
        return self.curve

    def __repr__(self) -> str:
        return f"ReversedCurve({self.curve!r})"


class TransformedCurve(Curve):
    """``A·C(t) + b`` for a wrapped curve C and an affine 4×4 transform [A b; 0 1].

    Derivatives are ``A·C⁽ᵏ⁾``. A perspective transform is rejected here: it is exact
    only for NURBS curves (:meth:`NurbsCurve.transformed`).
    """

    def __init__(self, curve: Curve, matrix: ArrayLike) -> None:
        m = check_matrix(matrix)
        if not is_affine(m):
            raise ValueError("Perspective transforms apply only to NURBS curves.")
        self.curve = curve
        self.matrix = m
        self.closed = curve.closed
        self.domain = curve.domain

    def derivatives(self, t: ArrayLike, order: int = 1) -> list[FloatArray]:
        values = self.curve.derivatives(t, order)
        linear = self.matrix[:3, :3].T
        out = [v @ linear for v in values]
        out[0] = out[0] + self.matrix[:3, 3]
        return out

    @property
    def anchor(self) -> FloatArray:
        return self.matrix[:3, :3] @ self.curve.anchor + self.matrix[:3, 3]

    def local_derivatives(self, t: ArrayLike, order: int = 1) -> list[FloatArray]:
        linear = self.matrix[:3, :3].T
        return [v @ linear for v in self.curve.local_derivatives(t, order)]

    def _breakpoints(self) -> FloatArray:
        return self.curve._breakpoints()

    def transformed(self, matrix: ArrayLike) -> Curve:
        return TransformedCurve(self.curve, check_matrix(matrix) @ self.matrix)

    def __repr__(self) -> str:
        return f"TransformedCurve({self.curve!r})"
