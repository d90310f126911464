"""Every input that sets how much a node makes is bounded before anything is made.

The sweep (tools/fuzz_inputs.py) builds, for every node type in the registry and each of
its numeric inputs and settings, a graph of that one node with small valid values wired
into its other inputs, sets the input to 0, -1, 1e-9, 1e12, 1e308, NaN and ∞, and solves
it in a guarded worker process (tools/fuzz_pool.py: address space capped, an alarm per
case). Per node type: no exception the node did not mean, no case past its alarm, no case
near the memory guard. The sweep runs once per session (about 15 s on two workers).

Then the cap that started it: SurfacePatching with Scale 1e-9 tried to allocate 23.8 GiB.
"""

from __future__ import annotations

import math
import os
import tracemalloc
from collections import defaultdict

import pytest

from tests.support.direct_graphs import Chain
from tools.fuzz_inputs import HOSTILE, InputCase, sweep
from torsal.engine.values import Vector
from torsal.nodes.analysis.iso_mapping import IsoMapping
from torsal.nodes.catalogue import default_registry
from torsal.nodes.curves.primitives import Circle
from torsal.nodes.developable.cylindrical import CylindricalSurface
from torsal.nodes.geometry.patching import TooManyPanels, staggered_pattern, tile_pattern
from torsal.nodes.limits import MAX_PANELS
from torsal.nodes.patching.staggered import StaggeredPattern
from torsal.nodes.patching.surface_patching import SurfacePatching

# Guards, not benchmarks: the slowest case takes about 1.2 s (a Plot drawn with
# matplotlib on a loaded machine) and the largest about 31 MB (the same Plot).
CASE_SECONDS = 10.0
CASE_BYTES = 512 << 20
WORKERS = min(2, os.cpu_count() or 1)

TYPE_IDS = sorted(cls.type_id for cls in default_registry(plugins=False))


@pytest.fixture(scope="module")
def swept() -> dict[str, list]:
    """Every case of the sweep, by node type: ``(case, CaseResult)``."""
    by_type: dict[str, list] = defaultdict(list)
    for case, result in sweep(workers=WORKERS, seconds=CASE_SECONDS, memory_bytes=2 * CASE_BYTES):
        by_type[case.type_id].append((case, result))
    return by_type


def _numeric_inputs(type_id: str) -> bool:
    cls = default_registry(plugins=False).get(type_id)
    return any(p.type.name in ("Number", "Integer", "Domain") for p in cls.inputs) or any(
        s.kind in (int, float) for s in cls.settings_spec)


SWEPT_TYPES = [t for t in TYPE_IDS if _numeric_inputs(t)]


def test_the_sweep_covers_every_numeric_input_of_every_node_type(swept):
    registry = default_registry(plugins=False)
    expected = {(cls.type_id, p.name) for cls in registry for p in cls.inputs
                if p.type.name in ("Number", "Integer", "Domain")}
    seen = {(case.type_id, case.name) for results in swept.values() for case, _ in results
            if not case.setting}
    assert seen == expected
    assert all(len(results) % len(HOSTILE) == 0 for results in swept.values())


#: Cases that fail in code other engineers own, reported to them: each is expected to fail
#: until fixed (strict: a fix shows as XPASS and the entry must go).
KNOWN: dict[InputCase, str] = {}


@pytest.mark.parametrize("type_id", SWEPT_TYPES)
def test_hostile_numbers_give_messages_not_exceptions(swept, type_id):
    failures = [f"{case}: {line}" for case, result in swept[type_id] if case not in KNOWN
                for line in result.unexpected]
    assert not failures, "\n".join(failures)


@pytest.mark.parametrize("case", [
    pytest.param(case, marks=pytest.mark.xfail(strict=True, reason=why), id=str(case))
    for case, why in KNOWN.items()
])
def test_known_findings_are_fixed(swept, case):
    (result,) = [r for c, r in swept[case.type_id] if c == case]
    assert not result.unexpected


@pytest.mark.parametrize("type_id", SWEPT_TYPES)
def test_hostile_numbers_never_stall_a_solve(swept, type_id):
    slow = [f"{case}: {result.seconds:.1f} s" for case, result in swept[type_id]
            if result.stalled or result.seconds > CASE_SECONDS]
    assert not slow


@pytest.mark.parametrize("type_id", SWEPT_TYPES)
def test_hostile_numbers_never_make_a_huge_allocation(swept, type_id):
    large = [f"{case}: {result.peak_bytes / 2**20:.0f} MiB" for case, result in swept[type_id]
             if result.peak_bytes > CASE_BYTES]
    assert not large


SEGMENT_TYPES = sorted(cls.type_id for cls in default_registry(plugins=False)
                       if any(p.name == "Segments" for p in cls.inputs))


@pytest.mark.parametrize("type_id", SEGMENT_TYPES)
@pytest.mark.parametrize("value", [0.0, 1e12])
def test_segments_of_0_or_1e12_is_refused_naming_segments(swept, type_id, value):
    (result,) = [r for case, r in swept[type_id] if case == InputCase(type_id, "Segments", value)]
    assert result.info["state"] in ("warning", "error")
    assert any(text.startswith("Segments is") or "Segments must" in text for text in result.info["messages"])


# --------------------------------------------------------------------------- SurfacePatching

RADIUS, HEIGHT, SEGMENTS = 1.0, 2.0, 48
BOND = {"Width": 0.3, "Height": 0.2, "Offset": 0.15}  # a tile of two 0.3 × 0.2 panels, 0.3 × 0.4


def patched(scale: float) -> Chain:
    """A cylinder (radius 1, height 2, 48 rulings) unrolled and panelled at ``scale``."""
    chain = Chain()
    chain.add("curve", Circle(), Radius=RADIUS)
    chain.add("surface", CylindricalSurface(), Direction=Vector(0, 0, 1), Height=HEIGHT, Segments=SEGMENTS)
    chain.wire("curve", "Circle", "surface", "Curve")
    chain.add("iso", IsoMapping(), Segments=SEGMENTS)
    chain.wire("surface", "Surface", "iso", "Surface")
    chain.add("bond", StaggeredPattern(), **BOND)
    chain.add("patch", SurfacePatching(), Scale=scale)
    chain.wire("iso", "Map", "patch", "Development")
    chain.wire("bond", "Pattern", "patch", "Pattern")
    chain.wire("bond", "Tile", "patch", "Tile")
    return chain.solve()


def test_a_scale_of_1e_9_is_refused_naming_scale_and_the_cap_before_anything_is_made():
    tracemalloc.start()
    try:
        chain = patched(1e-9)
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    (text,) = [m.text for m in chain.result("patch").messages]
    assert text.startswith("Scale is 1e-09: the pattern would be laid ")
    assert f"at most {MAX_PANELS:,} panels" in text
    assert chain.items("patch", "PanelsFlat") == []
    assert peak < 64 << 20  # the graph's own nodes; no tiling was attempted


def extent(chain: Chain) -> tuple[float, float]:
    """Width and height of the development's bounding rectangle (what the pattern is laid over)."""
    xmin, ymin, xmax, ymax = chain.item("iso", "Map").bounds
    return xmax - xmin, ymax - ymin


def test_the_unrolled_cylinder_is_its_circumference_wide_and_its_height_tall():
    width, height = extent(patched(1.0))
    assert width == pytest.approx(2 * math.pi * RADIUS, rel=1e-4)
    assert height == pytest.approx(HEIGHT, rel=1e-12)


def test_a_pattern_far_larger_than_the_development_gives_one_panel_covering_it():
    chain = patched(1e12)
    (area,) = chain.items("patch", "PanelAreas")
    assert area == pytest.approx(chain.item("iso", "AreaDevelopment"), rel=1e-9)


def test_a_scale_that_overflows_the_pattern_is_refused_naming_scale():
    chain = patched(1e308)
    (text,) = [m.text for m in chain.result("patch").messages]
    assert text.startswith("Scale is 1e+308: the scaled pattern would be larger than any number can hold")


@pytest.mark.parametrize("scale", [0.01, 1e-5])
def test_tile_pattern_counts_the_copies_it_would_make_before_making_them(scale):
    chain = patched(1.0)
    development = chain.item("iso", "Map")
    pattern = staggered_pattern(BOND["Width"], BOND["Height"], BOND["Offset"])
    with pytest.raises(TooManyPanels) as raised:
        tile_pattern(pattern, development, scale, max_panels=MAX_PANELS)
    # every tile reaching the W × H rectangle: at least the tiles covering it, at most one more per side
    width, height = extent(chain)
    tiles_x, tiles_y = width / (0.3 * scale), height / (0.4 * scale)
    assert 2 * tiles_x * tiles_y <= raised.value.count <= 2 * (tiles_x + 3) * (tiles_y + 3)


def test_a_scale_under_the_cap_still_panels_the_development():
    chain = patched(0.2)
    areas = chain.items("patch", "PanelAreas")
    width, height = extent(chain)
    assert 2 * (width / 0.06) * (height / 0.08) <= len(areas) <= MAX_PANELS
    assert sum(areas) == pytest.approx(chain.item("iso", "AreaDevelopment"), rel=1e-9)
