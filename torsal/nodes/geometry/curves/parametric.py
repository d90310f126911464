"""Curves given by a vectorised function of a parameter, e.g. compiled from expressions."""

from __future__ import annotations

from collections.abc import Callable, Sequence

import numpy as np
from numpy.typing import ArrayLike

from .. import finite_differences
from ..array_types import FloatArray
from ..curve_base import Curve

CurveFunction = Callable[[FloatArray], ArrayLike]


def _as_points_of(values: ArrayLike, count: int) -> FloatArray:
    """A function's result as ``(count, 3)``: an array ``(count, 3|2)`` or a tuple of columns.

    A tuple or list of 2 or 3 coordinates may hold scalars (``z = 0``), which broadcast.
    """
    if isinstance(values, tuple | list):
        columns = [np.broadcast_to(np.asarray(c, dtype=float), (count,)) for c in values]
        if len(columns) == 2:
            columns.append(np.zeros(count))
        if len(columns) != 3:
            raise ValueError(f"Expected 2 or 3 coordinates, got {len(columns)}.")
        return np.column_stack(columns)
    array = np.asarray(values, dtype=float)
    if array.ndim == 1 and count == 1 and array.shape[0] in (2, 3):
        array = array[None, :]
    if array.ndim != 2 or array.shape[0] != count or array.shape[1] not in (2, 3):
        raise ValueError(
            f"Expected {count} points of 2 or 3 coordinates, got an array of shape {array.shape}."
        )
    if array.shape[1] == 2:
        array = np.column_stack([array, np.zeros(count)])
    return array


class ParametricCurve(Curve):
    """The curve ``C(u) = function(u)`` for u in ``domain = (a, b)``, reparameterised to t.

    Args:
        function: vectorised: an array of u values → ``(n, 3)`` points (or ``(n, 2)``,
            or a tuple ``(x, y, z)`` of arrays or scalars).
        domain: ``(a, b)`` with ``a < b``; ``t = (u − a) / (b − a)``.
        derivatives: optional callables for ``dC/du``, ``d²C/du²``, ... in that order,
            same calling convention. Orders not given are computed by finite differences.
        closed: whether the curve is closed; ``None`` decides by comparing its ends.

    Finite-difference accuracy (9-point stencils, step chosen per curve; see
    :mod:`..finite_differences`), measured on a 3-turn helix as error relative to the
    derivative's magnitude: inside the domain about 1e-13, 1e-12 and 1e-10 for the
    first, second and third derivatives; at the two ends, where the stencils are
    one-sided, about 3e-12, 6e-11 and 5e-9. Curvature is then good to ~1e-10 and
    torsion to ~1e-8. Give analytic derivatives where that is not enough.

    >>> import numpy as np
    >>> c = ParametricCurve(lambda u: (np.cos(u), np.sin(u), 0.0), (0.0, np.pi))
    >>> np.round(c.point_at(0.5), 12).tolist()
    [0.0, 1.0, 0.0]
    """

    def __init__(
        self,
        function: CurveFunction,
        domain: tuple[float, float] = (0.0, 1.0),
        derivatives: Sequence[CurveFunction] = (),
        closed: bool | None = None,
    ) -> None:
        a, b = (float(x) for x in domain)
        if not (np.isfinite(a) and np.isfinite(b) and a < b):
            raise ValueError(f"The domain must be an interval a < b; got ({a}, {b}).")
        self.function = function
        self.domain = (a, b)
        self._derivative_functions = tuple(derivatives)
        self._steps: dict[int, float] = {}
        probe = self._evaluate(function, np.linspace(0.0, 1.0, 9))
        if not np.all(np.isfinite(probe)):
            raise ValueError("The curve's function gives a non-finite point inside its domain.")
        if closed is None:
            size = max(float(np.ptp(probe, axis=0).max()), 1.0)
            closed = bool(np.linalg.norm(probe[0] - probe[-1]) <= 1e-10 * size)
        self.closed = closed

    @property
    def exact_derivatives(self) -> bool:
        """Whether its first derivative is a given function, not differences of positions
        (:func:`~torsal.nodes.geometry.vec_ops.differenced`)."""
        return bool(self._derivative_functions)

    def _evaluate(self, function: CurveFunction, t: FloatArray) -> FloatArray:
        a, b = self.domain
        return _as_points_of(function(a + (b - a) * t), len(t))

    def _position(self, t: FloatArray) -> FloatArray:
        return self._evaluate(self.function, t)

    def derivatives(self, t: ArrayLike, order: int = 1) -> list[FloatArray]:
        t = np.atleast_1d(np.asarray(t, dtype=float)).reshape(-1)
        scale = self.domain[1] - self.domain[0]
        result = [self._position(t)]
        for k in range(1, order + 1):
            if k <= len(self._derivative_functions):
                result.append(self._evaluate(self._derivative_functions[k - 1], t) * scale**k)
            else:
                if k not in self._steps:
                    self._steps[k] = finite_differences.best_step(self._position, k)
                result.append(finite_differences.derivative(self._position, t, k, self._steps[k]))
        return result

    def __repr__(self) -> str:
        return f"ParametricCurve(domain={self.domain}, closed={self.closed})"
