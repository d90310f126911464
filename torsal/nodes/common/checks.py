"""The input checks every node shares: where to check that Segments is a whole number from 1 up.

The rule for errors and warnings
--------------------------------
- **A value a check refuses is a warning.** Every check here raises
  :class:`~torsal.engine.node.NodeWarning` with one sentence that names the input and says what
  to give instead ("Segments must be at least 1, not 0"; "CurveA has zero length, so no
  rulings can be spaced along it"). The solver skips that call of ``solve``: the node's
  other items still solve, and the node shows the warning. This holds whatever is wrong
  with the value — empty, not a number, infinite, out of range, the wrong kind of
  geometry, a curve that is a single point.
- **A value the node can still use after changing it is not refused**: the node clamps,
  rounds or ignores it, goes on and says what it did with :meth:`~torsal.engine.node.Node.warn`
  (a slider set past its max gives its max and warns).
- **An error** (:class:`~torsal.engine.node.NodeError`: the node makes nothing at all) is for what
  no item can get past — a node's own settings that are wrong (a slider's min above its
  max), a file that cannot be written, a list too long for one solve — never for one
  input value.
- **A bound that is the same for every call** is declared on the port,
  ``In("Segments", INTEGER, ..., min=1, max=MAX_SEGMENTS)``: the solver refuses a value
  outside it with the sentences :func:`count` uses, before any call, so the node warns
  and makes nothing (:mod:`torsal.engine.bounds`); the inspector and the slider dialog show it.

Every check takes the input's name first and the value second, except :func:`segments`
(the input is always called Segments). The checks of curves and surfaces, which need the
kernel, are in :mod:`torsal.nodes.common.geometry_checks`; these need numpy only, so a graph of
sliders and expressions loads no geometry library.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np

from torsal.engine.node import NodeWarning
from torsal.nodes.limits import MAX_ANALYSIS_SEGMENTS, MAX_NUMBERS, MAX_SEGMENTS, shown

#: Below this length (model units) a direction counts as zero.
ZERO_LENGTH = 1e-12

#: The highest degree of a spline, a NURBS curve or a NURBS surface (Rhino's limit, and more
#: than enough).
MAX_DEGREE = 11

#: How far outside [0, 1] a (u, v) may stray (rounding) before it is refused; it is clamped.
UV_SLACK = 1e-12



# -- any value --------------------------------------------------------------------------

def given(name: str, value: Any) -> Any:
    """``value``, or a warning that the input ``name`` is empty (null)."""
    if value is None:
        raise NodeWarning(f"{name} is empty (null)")
    return value


# -- numbers ----------------------------------------------------------------------------

def finite(name: str, value: Any) -> float:
    """``value`` as a float, or a warning saying it is empty, not a number or infinite."""
    number = float(given(name, value))
    if math.isnan(number):
        raise NodeWarning(f"{name} is not a number (NaN)")
    if math.isinf(number):
        raise NodeWarning(f"{name} is infinite")
    return number


number = finite
"""A finite number (the same check as :func:`finite`, by the name the geometry nodes use)."""


def whole(name: str, value: Any) -> int:
    """``value`` as an int, or a warning saying it is empty."""
    return int(given(name, value))


def count(name: str, value: Any, least: int = 0, limit: int = MAX_NUMBERS) -> int:
    """A count of things to make: a whole number from ``least`` to ``limit``."""
    n = whole(name, value)
    if n < least:
        raise NodeWarning(f"{name} must be at least {least}, not {shown(n)}")
    if n > limit:
        raise NodeWarning(f"{name} is {shown(n)}; at most {limit:,} can be made at once")
    return n


def segments(value: Any, limit: int = MAX_SEGMENTS, name: str = "Segments") -> int:
    """Segments, the number of rulings (or strips) minus one: a whole number from 1 to ``limit``."""
    return count(name, value, least=1, limit=limit)


def analysis_segments(value: Any, name: str = "Segments") -> int:
    """Segments of a node that unrolls or traces each strip: 1 to MAX_ANALYSIS_SEGMENTS."""
    return segments(value, MAX_ANALYSIS_SEGMENTS, name)


def degree(name: str, value: Any) -> int:
    """A curve's or surface's degree: a whole number from 1 to :data:`MAX_DEGREE`."""
    n = whole(name, value)
    if not 1 <= n <= MAX_DEGREE:
        raise NodeWarning(f"{name} must be from 1 to {MAX_DEGREE}, not {n}")
    return n


def positive(name: str, value: Any) -> float:
    """A finite, positive length in model units (a radius, a width)."""
    x = number(name, value)
    if x <= 0:
        raise NodeWarning(f"{name} must be a positive length, not {x:g}")
    return x


def length(name: str, value: Any) -> float:
    """A finite, non-zero ruling length in model units (negative reverses the rulings)."""
    x = number(name, value)
    if x == 0:
        raise NodeWarning(f"{name} is 0, so the rulings would have no length: give a length")
    return x


def angle(name: str, value: Any, example: str = "0.01", largest: float | None = math.pi / 2,
          exact: bool = False) -> float:
    """A tolerance angle in radians: positive, or with ``exact`` 0 too (0 asks for an exact
    result); at most ``largest`` (π/2 unless told; None: no greatest)."""
    if value is None:
        raise NodeWarning(f"{name} is empty: give an angle in rad, such as {example}")
    x = float(value)
    if not (math.isfinite(x) and (x >= 0 if exact else x > 0)):
        least = "an angle of 0 rad or more" if exact else "a positive angle in radians"
        raise NodeWarning(f"{name} must be {least}, such as {example}, not {x:g}")
    if largest is not None and x > largest:
        quarter = " (π/2)" if largest == math.pi / 2 else ""
        raise NodeWarning(f"{name} is {x:g} rad; it is an angle in radians, at most {largest:.4g}{quarter}")
    return x


def tolerance(name: str, value: Any) -> float:
    """An angle tolerance in rad, 0 (exact) or more, of any size: :func:`angle` with ``exact``."""
    return angle(name, value, largest=None, exact=True)


def edge(name: str, value: Any) -> int:
    """A surface edge number, 0 to 3 (0: v = 0, 1: u = 1, 2: v = 1, 3: u = 0)."""
    if value is None:
        raise NodeWarning(f"{name} is empty: give an edge number from 0 to 3")
    n = int(value)
    if not 0 <= n <= 3:
        raise NodeWarning(f"{name} is {n}: edges are numbered 0 (v = 0), 1 (u = 1), 2 (v = 1) and 3 (u = 0)")
    return n


def interval(name: str, value: Any, variable: str) -> tuple[float, float]:
    """A domain's (start, end): finite and not empty; start > end is allowed (reversed)."""
    given(name, value)
    a, b = number(f"{name} start", value.min), number(f"{name} end", value.max)
    if a == b:
        raise NodeWarning(f"The {name} is empty ({a:g} to {b:g}): {variable} must run over an interval")
    return a, b


# -- points and vectors -------------------------------------------------------------------

def xyz(name: str, value: Any) -> np.ndarray:
    """A point or vector as a ``(3,)`` array with finite coordinates."""
    array = np.asarray(given(name, value), dtype=float)
    if not np.all(np.isfinite(array)):
        raise NodeWarning(f"{name} has a coordinate that is not a finite number")
    return array


def direction(name: str, value: Any) -> np.ndarray:
    """A vector that must have a direction: not (almost) zero length."""
    array = xyz(name, value)
    if float(np.linalg.norm(array)) <= ZERO_LENGTH:
        raise NodeWarning(f"{name} has zero length, so it has no direction")
    return array


def point_list(name: str, values: Sequence[Any]) -> np.ndarray:
    """A list of points as an ``(n, 3)`` array; empty (null) or non-finite items are refused."""
    if any(v is None for v in values):
        raise NodeWarning(f"{name} contains empty (null) items: remove them or fix what made them")
    array = np.asarray(values, dtype=float).reshape(-1, 3)
    if not np.all(np.isfinite(array)):
        raise NodeWarning(f"{name} contains a point with a coordinate that is not a finite number")
    return array


def uv(name: str, value: Any) -> tuple[float, float]:
    """The (u, v) a point stands for: its x and y, each from 0 to 1 (rounding past them is clamped).

    Every surface in Torsal is parameterised on (u, v) in [0, 1]², so a place on a surface
    is given as a point whose x is u and y is v (its z is ignored), as in Grasshopper.
    """
    u, v, _ = xyz(name, value)
    if not (-UV_SLACK <= u <= 1 + UV_SLACK and -UV_SLACK <= v <= 1 + UV_SLACK):
        raise NodeWarning(
            f"{name} must have x (u) and y (v) from 0 to 1, not ({u:g}, {v:g}): every surface "
            "is parameterised on [0, 1]²"
        )
    return min(max(u, 0.0), 1.0), min(max(v, 0.0), 1.0)
