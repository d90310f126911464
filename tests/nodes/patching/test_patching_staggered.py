"""patching.StaggeredPattern, solved in real graphs."""

from __future__ import annotations

import numpy as np
import pytest
import shapely

from tests.support.direct_graphs import Chain
from torsal.nodes.patching.staggered import StaggeredPattern


def pattern(**values) -> Chain:
    chain = Chain()
    chain.add("bond", StaggeredPattern(), **values)
    return chain.solve()


def rings(chain: Chain) -> list[np.ndarray]:
    return [np.asarray(c.points) for c in chain.items("bond", "Pattern")]


def test_pattern_is_two_closed_panels_the_upper_one_shifted_by_offset():
    chain = pattern(Width=2.0, Height=0.5, Offset=0.75)
    lower, upper = rings(chain)
    assert all(c.closed for c in chain.items("bond", "Pattern"))
    assert np.array_equal(lower[:4], [[0, 0, 0], [2, 0, 0], [2, 0.5, 0], [0, 0.5, 0]])
    assert np.array_equal(upper, lower + np.array([0.75, 0.5, 0.0]))


def test_tile_is_width_by_two_heights():
    tile = pattern(Width=2.0, Height=0.5, Offset=0.75).item("bond", "Tile")
    assert tile.closed
    assert np.array_equal(tile.points[:4], [[0, 0, 0], [2, 0, 0], [2, 1, 0], [0, 1, 0]])


def test_repeated_tiles_cover_the_plane_without_gaps_or_overlaps():
    chain = pattern(Width=1.5, Height=0.4, Offset=0.5)
    panels = [shapely.Polygon(r[:, :2]) for r in rings(chain)]
    shifts = [(1.5 * i, 0.8 * j) for i in range(4) for j in range(4)]
    copies = [shapely.affinity.translate(p, dx, dy) for p in panels for dx, dy in shifts]
    union = shapely.union_all(copies)
    assert union.area == pytest.approx(sum(c.area for c in copies), rel=1e-14)  # no overlaps
    inner = shapely.box(1.5, 0.8, 4.5, 2.4)  # away from the block's ragged edges
    assert union.intersection(inner).area == pytest.approx(inner.area, rel=1e-14)  # no gaps


def test_offset_is_taken_modulo_width():
    a = rings(pattern(Width=2.0, Height=1.0, Offset=0.5))
    b = rings(pattern(Width=2.0, Height=1.0, Offset=4.5))
    assert np.allclose(a[1], b[1], atol=1e-15)


@pytest.mark.parametrize(
    ("values", "message"),
    [
        ({"Width": 0.0}, "Width must be a positive length, not 0"),
        ({"Height": -1.0}, "Height must be a positive length, not -1"),
    ],
)
def test_invalid_sizes_warn(values, message):
    chain = pattern(**values)
    assert chain.result("bond").state == "warning"
    assert chain.texts("bond") == [message]
