"""PaperStrip's kernel: a chain of planar quads, developable by construction."""

from __future__ import annotations

import math

import numpy as np
import pytest

from torsal.nodes.geometry.paper_strip import paper_strip, quad_planarity
from torsal.nodes.geometry.unroll import unroll_rulings

RNG = np.random.default_rng(11)


def random_strip(segments: int = 60):
    iso = RNG.uniform(1.35, 1.8, segments // 2)  # shorter than segments: the last one repeats
    curvature = RNG.uniform(-0.35, 0.35, segments)
    return paper_strip(12.0, 1.0, iso, curvature, segments)


def test_every_face_of_a_paper_strip_is_planar_to_1e_12():
    strip = random_strip()
    assert strip.valid
    assert strip.planarity.max() < 1e-12
    assert quad_planarity(strip.starts, strip.ends).max() < 1e-12
    # and it is really bent: neighbouring faces meet at the curvature angles
    assert np.abs(np.einsum("ij,ij->i", strip.normals[:-1], strip.normals[1:])).min() < math.cos(0.01)


def test_paper_strip_unrolls_with_zero_length_and_area_error():
    strip = random_strip()
    dev = unroll_rulings(strip.starts, strip.ends)
    assert dev.max_edge_length_error < 1e-12
    assert abs(dev.area_error) < 1e-12
    # and the unrolling is the strip's own development, laid down the same way
    assert np.abs(dev.starts2d - strip.starts2d).max() < 1e-12
    assert np.abs(dev.ends2d - strip.ends2d).max() < 1e-12


def test_rulings_keep_the_strip_width():
    strip = random_strip()
    assert np.abs(np.linalg.norm(strip.ends - strip.starts, axis=1) - 1.0).max() < 1e-14
    assert np.abs(np.linalg.norm(strip.ends2d - strip.starts2d, axis=1) - 1.0).max() < 1e-14


def test_square_iso_angle_and_constant_curvature_fold_a_prism_that_closes():
    segments, length = 12, 2.0 * math.pi
    strip = paper_strip(length, 0.5, [math.pi / 2], [2.0 * math.pi / segments], segments)
    step = length / segments
    # the rulings stay parallel to +y; the cross-section is a regular 12-gon
    assert np.abs(np.cross(strip.ends - strip.starts, [0.0, 1.0, 0.0])).max() < 1e-14
    assert np.linalg.norm(strip.starts[-1] - strip.starts[0]) < 1e-13
    section = strip.starts[:, [0, 2]]
    centre = section[:-1].mean(axis=0)
    radius = step / (2.0 * math.sin(math.pi / segments))
    assert np.abs(np.linalg.norm(section - centre, axis=1) - radius).max() < 1e-13
    # positive curvature folds the strip up (+z) from the XY plane
    assert centre[1] > 0


def test_flat_strip_with_a_constant_iso_angle_turns_on_a_circle():
    segments, length, iso = 24, 6.0, math.radians(80.0)
    strip = paper_strip(length, 0.4, [iso], [0.0], segments)
    assert np.abs(strip.starts[:, 2]).max() == 0.0 and np.abs(strip.ends[:, 2]).max() == 0.0
    middle = 0.5 * (strip.starts2d + strip.ends2d)
    steps = np.linalg.norm(np.diff(middle, axis=0), axis=1)
    assert np.abs(steps - length / segments).max() < 1e-14
    # equal steps, each turning by 90° − iso: a polygon inscribed in a circle
    theta = math.pi / 2 - iso
    radius = (length / segments) / (2.0 * math.sin(theta / 2.0))
    chords = np.linalg.norm(middle[2:] - middle[:-2], axis=1)
    assert np.allclose(chords, 2.0 * radius * math.sin(theta), rtol=1e-13)
    # leaning forward shortens the start edge: the strip turns towards it
    start_edge = np.linalg.norm(np.diff(strip.starts2d, axis=0), axis=1).sum()
    end_edge = np.linalg.norm(np.diff(strip.ends2d, axis=0), axis=1).sum()
    assert start_edge < end_edge


def test_short_lists_repeat_their_last_value():
    a = paper_strip(5.0, 1.0, [1.4, 1.5], [0.1, 0.2], 6)
    b = paper_strip(5.0, 1.0, [1.4, 1.5, 1.5, 1.5, 1.5, 1.5], [0.1, 0.2, 0.2, 0.2, 0.2, 0.2], 6)
    assert np.array_equal(a.starts, b.starts) and np.array_equal(a.ends, b.ends)


def test_too_steep_a_tilt_for_the_segment_is_flagged_as_crossing():
    # neighbouring rulings meet Δ·cot θ from the middle line: inside a strip this wide
    strip = paper_strip(1.0, 4.0, [math.radians(60.0)], [0.1], 10)
    assert not strip.valid and strip.crossing.all()
    assert paper_strip(1.0, 0.1, [math.radians(60.0)], [0.1], 10).valid


def test_invalid_inputs_are_refused():
    with pytest.raises(ValueError):
        paper_strip(1.0, 1.0, [math.pi / 2], [0.0], 0)
    with pytest.raises(ValueError):
        paper_strip(-1.0, 1.0, [math.pi / 2], [0.0], 4)


def test_a_thousand_segments_stay_planar():
    """How fast, against composing the folds one by one in the same run: bench_unroll.py."""
    strip = paper_strip(100.0, 0.5, RNG.uniform(1.5, 1.64, 1000), RNG.uniform(-0.1, 0.1, 1000), 1000)
    assert len(strip.starts) == 1001
    assert strip.planarity.max() < 1e-12
