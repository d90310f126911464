"""The contract every kernel curve fulfils: parameter t in [0, 1], vectorised evaluation.

A subclass implements :meth:`Curve.derivatives`; everything else (tangent, curvature,
frames, length, division, closest point ...) is derived generically here or overridden
where a closed form is faster or exact.
"""

from __future__ import annotations

from abc import ABC, abstractmethod

import numpy as np
from numpy.typing import ArrayLike, NDArray

FloatArray = NDArray[np.float64]


class Curve(ABC):
    """A 3D curve parameterised on t in [0, 1]."""

    closed: bool = False

    @abstractmethod
    def derivatives(self, t: ArrayLike, order: int = 1) -> list[FloatArray]:
        """Return ``[C(t), C'(t), ..., C^(order)(t)]``, each an ``(n, 3)`` array.

        ``t`` is a scalar or a 1-D array of parameters in [0, 1]; derivatives are with
        respect to that normalised parameter.
        """

    def point_at(self, t: ArrayLike) -> FloatArray:
        """Points at parameters ``t``: ``(n, 3)`` for an array, ``(3,)`` for a scalar."""
        scalar = np.ndim(t) == 0
        points = self.derivatives(np.atleast_1d(np.asarray(t, dtype=float)), 0)[0]
        return points[0] if scalar else points
