"""The caps on inputs that set how much a node makes: one place for every such limit.

A count typed one digit too long (Segments 1e6 for 1e5), a Scale of 1e-9 where 1 was
meant, a number pasted from the wrong cell — each asks a node for billions of rulings,
points or panels, and would stall the solve or exhaust memory before anything could say
why. So every input that sets the length of an array or a loop is compared with one of
these caps *before* anything is made, and the node says which input, what it asked for
and the cap ("Segments is 1,000,000,000,000; at most 100,000 can be made at once").

Each cap is set where a solve at the cap still takes seconds, not minutes, and well
under 1 GB, measured by ``python -m tools.fuzz_inputs --at-caps`` on small valid inputs
on a shared two-core machine (the ranges beside each cap go from quiet to loaded). They
are guards against typos, not statements about what is useful: a job that needs more
splits the work (more strips, more curves) rather than raising a cap.

``tests/nodes/test_input_caps.py`` feeds every numeric input of every node 0, -1, 1e-9, 1e12,
1e308, NaN and ∞ and checks that each gives a message or a result in bounded time and
memory.
"""

from __future__ import annotations

from torsal.engine.bounds import (
    shown as shown,  # how a count is written in a message (one home: the engine's)
)

#: Segments (rulings minus one) of one developable strip built directly (Cylindrical,
#: Conical, Tangent, PaperStrip, ParametricRuled, RulingDevelopable): 0.7–3.7 s and
#: 20–210 MB at the cap.
MAX_SEGMENTS = 100_000

#: Segments of IsoMapping and CurveOfRegression (each segment is unrolled or traced):
#: 0.8–1.5 s and < 90 MB at the cap.
MAX_ANALYSIS_SEGMENTS = 10_000

#: Segments of SurfaceCoupling: 0.3–1 s at the cap (100,000 took 20 s and 820 MB).
MAX_COUPLING_SEGMENTS = 10_000

#: Segments of SplineApproximation, whose fit solves a dense (n + 1)² system: at the cap
#: 0.5–5 s and 120–215 MB (4,000: 3 s and 490 MB; 10,000: 760 MB for one matrix).
MAX_SPLINE_SEGMENTS = 2_000

#: Points of DivideCurve: 2–4.5 s and 125 MB at the cap (1,000,000 passed 1 GB).
MAX_DIVISIONS = 100_000

#: Numbers one call of Series, Range or Random makes: 0.4 s and 45 MB at the cap
#: (10,000,000 took 4 s and 450 MB as a list of Python numbers).
MAX_NUMBERS = 1_000_000

#: Copies one call of Array or PolarArray makes: 1.3–6 s at the cap (100,000 took > 30 s).
MAX_COPIES = 10_000

#: Samples per direction of SurfaceAnalysis' grid (the grid is its square: 250,000):
#: 2.4–5.7 s and 216 MB at the cap.
MAX_DENSITY = 500

#: Pattern copies SurfacePatching lays over one development (tiles × panels in a tile,
#: before clipping): about 6 s at the cap (11,700 panels kept of 19,900 copies on the
#: development-and-panels example), each panel clipped and mapped onto the surface; a
#: Scale of 1e-9 asked for 3.3 billion (23.8 GiB).
MAX_PANELS = 20_000

#: Bytes of a mesh file ImportMesh reads, and of each file it names (an OBJ's material
#: library, a glTF's buffers): 200 MB is about 4 million triangles of binary STL. A
#: larger file is refused before it is read (a 1 GB mesh took 2.1–3.2 GB and 21 s).
MAX_MESH_FILE_BYTES = 200 * 2**20

#: Strips RulingDevelopable (also ConicalSurface, SplineApproximation: 12–37 ms a call in
#: the examples) solves in one solve of the node, when a list of values (a Series into
#: WarpTolerance, a list of curves) multiplies its calls: one strip at the default 24
#: segments takes 5–25 ms, so 10–50 s at the cap (1,000,000 would take hours).
MAX_STRIP_SOLVES = 2_000
#: Rulings RulingDevelopable makes in one solve of the node, all its strips together:
#: four strips at MAX_SEGMENTS (3–15 s).
MAX_STRIP_RULINGS = 4 * MAX_SEGMENTS
#: Designs Rationalise splits into strips in one solve of the node, when a list of values
#: (surfaces, tolerances) multiplies its calls: one design took 5.5 s (the
#: rationalise-roof example), so about 5 min at the cap.
MAX_RATIONALISE_CALLS = 50
