"""The caps on inputs that set how much a node makes: one place for every such limit.

A count typed one digit too long (Segments 1e6 for 1e5), a Scale of 1e-9 where 1 was
meant, a number pasted from the wrong cell — each asks a node for billions of rulings,
points or panels, and would stall the solve or exhaust memory before anything could say
why. So every input that sets the length of an array or a loop is checked against a cap
here *before* anything is made, and the node says which input, what it asked for and
the cap ("Segments is 1e+12: at most 100,000 rulings").

Each cap is set where a solve at the cap still takes seconds, not minutes, and well
under 1 GB (measured on the shipped examples' geometry; the figures are beside each
cap). They are guards against typos, not statements about what is useful: a real job
that needs more splits the work (more strips, more curves) rather than raising a cap.

``tests/test_input_caps.py`` feeds every numeric input of every node 0, -1, 1e-9, 1e12,
1e308, NaN and ∞ and checks that each gives a message or a result in bounded time and
memory.
"""

from __future__ import annotations

import math

#: Rulings of one developable strip built directly (Cylindrical, Conical, Tangent,
#: PaperStrip, ParametricRuled, RulingDevelopable): 1.4–2.5 s and < 40 MB at the cap.
MAX_RULINGS = 100_000

#: Segments of IsoMapping and CurveOfRegression (each segment is unrolled or traced).
MAX_ANALYSIS_SEGMENTS = 10_000

#: Segments of SurfaceCoupling: 0.3 s at the cap (100,000 took 20 s and 820 MB).
MAX_COUPLING_SEGMENTS = 10_000

#: Segments of SplineApproximation, whose fit solves a dense (n + 1)² system: at the cap
#: 0.5 s and 120 MB (4,000: 3 s and 490 MB; 10,000: 760 MB for one matrix).
MAX_SPLINE_SEGMENTS = 2_000

#: Points of DivideCurve: 2.3 s and 120 MB at the cap (1,000,000 passed 1 GB).
MAX_DIVISIONS = 100_000

#: Numbers one call of Series, Range or Random makes: 0.4 s and 45 MB at the cap
#: (10,000,000 took 4 s and 450 MB as a list of Python numbers).
MAX_NUMBERS = 1_000_000

#: Copies one call of Array or PolarArray makes: 1.3 s at the cap (100,000 took > 30 s).
MAX_COPIES = 10_000

#: Samples per direction of SurfaceAnalysis' grid (the grid is its square: 250,000).
MAX_DENSITY = 500

#: Pattern copies SurfacePatching lays over one development (tiles × panels in a tile,
#: before clipping): about 10 s at the cap, each panel clipped and mapped onto the
#: surface; a Scale of 1e-9 asked for billions (23.8 GiB).
MAX_PANELS = 20_000


def too_many(name: str, value: float, limit: int, things: str) -> str:
    """The sentence for an input over its cap: ``Segments is 1e+12: at most 100,000 rulings``.

    ``value`` is what the input asked for (a count, or what a Scale would make), ``things``
    what is counted (plural).
    """
    shown = f"{value:,}" if isinstance(value, int) and abs(value) < 10**15 else f"{float(value):.3g}"
    return f"{name} is {shown}: at most {limit:,} {things}"


def whole_count(value: float) -> float:
    """A float count rounded up, with NaN and ∞ kept (for comparing with a cap before
    anything is allocated: ``np.arange`` of ∞ fails, of 1e12 exhausts memory)."""
    return value if not math.isfinite(value) else float(math.ceil(value))
