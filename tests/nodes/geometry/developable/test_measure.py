"""The validity rule's one home, :func:`torsal.nodes.geometry.developable.measure.within_tolerance`:
a warp within the tolerance plus its ends' rounding over the ruling's length, never NaN.
Expected values are the rule's closed form: the rounding of a position near coordinate c is
16 ulps of c (16 · 2⁻⁵² · c), over a ruling of length L."""

from __future__ import annotations

import numpy as np

from torsal.nodes.geometry.developable.measure import within_tolerance

EPS = 2.0**-52


def test_at_the_origin_the_tolerance_alone_decides_and_nan_is_never_valid():
    starts = np.array([[0.0, 0, 0], [1, 0, 0], [2, 0, 0], [3, 0, 0]])
    ends = starts + np.array([0.0, 1.0, 0.0])
    warp = np.array([0.01, 0.0100000001, np.nan, 0.0])
    assert within_tolerance(warp, 0.01, starts, ends).tolist() == [True, False, False, True]


def test_far_from_the_origin_a_warp_may_exceed_the_tolerance_by_the_rounding_over_the_length():
    site = 1e9
    starts = np.array([[site, 0.0, 0.0], [site + 2.0, 0.0, 0.0]])
    ends = starts + np.array([0.0, 2.0, 0.0])  # rulings 2 m long: the allowance is 16 ulps of 1e9 over 2 m
    allowance = 16 * EPS * (site + 2.0) / 2.0
    tolerance = 1e-7
    inside, outside = tolerance + 0.9 * allowance, tolerance + 1.1 * allowance
    warp = np.array([inside, outside])
    assert within_tolerance(warp, tolerance, starts, ends).tolist() == [True, False]


def test_a_zero_length_ruling_gets_no_allowance_and_per_ruling_rounding_is_taken_as_given():
    starts = np.zeros((2, 3))
    ends = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]])
    warp = np.array([0.5, 0.5])
    assert within_tolerance(warp, 0.4, starts, ends, rounding=np.array([1.0, 0.2])).tolist() == [False, True]
