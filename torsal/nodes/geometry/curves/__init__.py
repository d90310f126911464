"""Kernel curves, all parameterised on t in [0, 1] (see :class:`..curve_base.Curve`).

- :class:`Line`, :class:`Polyline` — straight pieces, parameterised by arc length.
- :class:`NurbsCurve` — any degree, rational, clamped/unclamped/periodic knots.
- :class:`InterpolatedCurve` — cubic spline through points (chord-length).
- :class:`Circle`, :class:`Arc` — exact rational quadratic NURBS.
- :class:`ParametricCurve` — from a vectorised function over a domain.
- :class:`ReversedCurve`, :class:`TransformedCurve` — generic views of any curve (defined
  in ``curve_base``, whose :meth:`~..curve_base.Curve.reversed` and ``transformed`` return them).
"""

from ..curve_base import ReversedCurve, TransformedCurve
from .conics import Arc, Circle
from .interpolated import InterpolatedCurve, chord_length_parameters
from .line import Line, Polyline
from .nurbs import NurbsCurve
from .parametric import ParametricCurve

__all__ = [
    "Arc",
    "Circle",
    "InterpolatedCurve",
    "Line",
    "NurbsCurve",
    "ParametricCurve",
    "Polyline",
    "ReversedCurve",
    "TransformedCurve",
    "chord_length_parameters",
]
