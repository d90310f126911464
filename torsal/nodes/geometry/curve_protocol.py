"""What the kernel's curve helpers need of a curve: a structural type, no class to import.

Arc length (:mod:`.arclength`), closest points (:mod:`.closest`) and tessellation
(:mod:`.tessellate`) are used *by* :class:`~.curve_base.Curve`, so they cannot import it
without an import circle. They name this protocol instead (closest points extend it with
the cached search samples); every kernel curve satisfies it.
"""

from __future__ import annotations

from typing import Protocol

from numpy.typing import ArrayLike

from .array_types import FloatArray


class ParametricCurve(Protocol):
    """A curve on [0, 1]: points and derivatives at parameters, and where it is smooth."""

    def point_at(self, t: ArrayLike) -> FloatArray: ...

    def derivative_at(self, t: ArrayLike, order: int = 1) -> FloatArray: ...

    def derivatives(self, t: ArrayLike, order: int = 1) -> list[FloatArray]: ...

    def _breakpoints(self) -> FloatArray: ...
