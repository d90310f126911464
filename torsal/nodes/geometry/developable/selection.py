"""Choosing one partner per station so that rulings never cross: a monotone dynamic programme.

Each station i on edge A has a few candidate partners ``t[i, k]`` on edge B (roots of
the coplanarity condition), each with the slope ``dt/ds`` of the branch of solutions it
lies on. A strip's rulings are one *branch* followed from station to station, with t
never decreasing (a decreasing t means crossing rulings). The cost of stepping from
candidate k at station i to candidate l at station i + 1 is how far the step misses
the branch's own prediction::

    | t[i+1, l] − t[i, k] − Δs·(slope[i, k] + slope[i+1, l]) / 2 |

which is O(Δs³) along one branch and about the size of the jump between branches. A
step backwards costs a large multiple of its size (so a path always exists; the caller
drops any station it still steps back at), and the two ends add ``end_weight`` times
``t_first + (1 − t_last)``, which prefers, between equally smooth branches, the one that
spans edge B from end to end.

The minimum-cost path is a (min, +) matrix product chain ``v0 ⊗ C0 ⊗ C1 ⊗ … ⊗ end``.
Matrix products are associative, so all prefix and suffix products are computed by a
parallel (Hillis–Steele) scan in ⌈log2 n⌉ vectorised steps instead of a loop over the
stations; the optimal candidate at every station is then the one minimising forward +
backward cost. A sequential back-trace is kept for exact ties only.
"""

from __future__ import annotations

import numpy as np

from torsal.nodes.geometry.array_types import IntArray

from ..curve_base import FloatArray

#: Cost per unit of t of stepping backwards (rulings crossing); large but finite.
BACKWARD_PENALTY = 1e3
#: The weight of a step's miss in :func:`longest_chain` where it skips stations that had
#: candidates (only to tell apart chains that would otherwise cost the same).
SKIP = 1e-6


def _minplus(x: FloatArray, y: FloatArray) -> FloatArray:
    """(min, +) product of stacks of square matrices: ``z[..., a, c] = min_b x[a, b] + y[b, c]``.

    Written as K whole-stack steps (K, the number of candidates, is small): numpy's
    reduction over a short middle axis is many times slower.
    """
    z = x[..., :, :1] + y[..., :1, :]
    for b in range(1, x.shape[-1]):
        np.minimum(z, x[..., :, b : b + 1] + y[..., b : b + 1, :], out=z)
    return z


def step_costs(t: FloatArray, slope: FloatArray, ds: FloatArray) -> FloatArray:
    """Costs ``(n−1, K, K)`` of stepping from candidate k at station i to l at station i + 1.

    ``t`` and ``slope`` are ``(n, K)`` with NaN for missing candidates; ``ds`` ``(n−1,)``.
    """
    step = t[1:, None, :] - t[:-1, :, None]
    predicted = 0.5 * ds[:, None, None] * (slope[:-1, :, None] + slope[1:, None, :])
    cost = np.abs(step - predicted)
    cost = np.where(step < -1e-12, BACKWARD_PENALTY * (1.0 - step), cost)
    return np.where(np.isnan(cost), np.inf, cost)


def monotone_path(t: FloatArray, slope: FloatArray, ds: FloatArray, end_weight: float = 0.1) -> IntArray:
    """Index of the chosen candidate at each station, minimising the summed step costs.

    Every station must have at least one candidate (a finite ``t[i, k]``); missing ones
    are NaN. Returns an ``(n,)`` array of column indices into ``t``.
    """
    n, k = t.shape
    start = np.where(np.isnan(t[0]), np.inf, end_weight * t[0])
    end = np.where(np.isnan(t[-1]), np.inf, end_weight * (1.0 - t[-1]))
    if n == 1:
        return np.array([int(np.argmin(start + end))])
    if k == 1:
        return np.zeros(n, dtype=np.int64)
    costs = step_costs(t, slope, ds)
    prefix = costs.copy()
    suffix = costs.copy()
    d = 1
    while d < n - 1:
        # prefix[i] becomes costs[i−2d+1 .. i] composed; suffix[i] costs[i .. i+2d−1]
        prefix[d:] = _minplus(prefix[:-d], prefix[d:])
        suffix[:-d] = _minplus(suffix[:-d], suffix[d:])
        d *= 2
    forward = np.vstack([start, np.min(start[None, :, None] + prefix, axis=1)])
    backward = np.vstack([np.min(suffix + end[None, None, :], axis=2), end])
    total = forward + backward
    choice = np.argmin(total, axis=1)
    # consistent unless two paths tie exactly: then trace back sequentially
    rows = np.arange(n - 1)
    along = forward[rows, choice[:-1]] + costs[rows, choice[:-1], choice[1:]] + backward[rows + 1, choice[1:]]
    best = total[0, choice[0]]
    if np.all(np.abs(along - best) <= 1e-9 * max(1.0, abs(best))):
        return choice
    return _trace_back(forward, costs, end)


def _trace_back(forward: FloatArray, costs: FloatArray, end: FloatArray) -> IntArray:
    """Classic Viterbi back-trace from the forward costs (used only on exact ties)."""
    n = len(forward)
    choice = np.empty(n, dtype=np.int64)
    choice[-1] = int(np.argmin(forward[-1] + end))
    for i in range(n - 2, -1, -1):  # ties only: rare, and each step is one small vector
        choice[i] = int(np.argmin(forward[i] + costs[i][:, choice[i + 1]]))
    return choice


def longest_chain(t: FloatArray, slope: FloatArray, s: FloatArray, end_weight: float = 0.1) -> IntArray:
    """The candidate chosen at each station (−1 where none) on a chain through the most
    stations with t never decreasing: what :func:`monotone_path` is for when its path
    had to step back (a station whose every candidate lies behind its neighbours'
    partners forces a step back on a path that must pass every station).

    A chain may skip stations; it takes as many as any chain can, and among the chains
    that long the one whose steps miss their branches' predictions least (the costs of
    :func:`step_costs` over the whole skip, with the same end weights as
    :func:`monotone_path`). So every station with a candidate between its chain
    neighbours' partners is on the chain: a torsal ruling consistent with the strip's
    order is never left out for a fan.

    ``t`` and ``slope`` are ``(n, K)`` with NaN for missing candidates, ``s`` the
    stations' parameters ``(n,)``. Each station is compared with every candidate before
    it at once (``n`` vectorised steps over at most ``n·K`` candidates: the fallback of a
    rare case, so no faster structure is kept for it).
    """
    n = len(t)
    rows, cols = np.nonzero(~np.isnan(t))  # (row-major: station by station)
    cand_t, cand_slope, cand_s = t[rows, cols], slope[rows, cols], s[rows]
    count = np.zeros(len(rows), dtype=np.int64)
    cost = np.zeros(len(rows))
    parent = np.full(len(rows), -1, dtype=np.int64)
    bounds = np.searchsorted(rows, np.arange(n + 1))
    previous = -1  # the last station with candidates
    for i in range(n):  # the chains ending at station i's candidates, from all before them
        low, high = bounds[i], bounds[i + 1]
        if low == high:
            continue
        here = slice(low, high)
        start = end_weight * cand_t[here]
        if low == 0:
            count[here], cost[here] = 1, start
            previous = i
            continue
        step = cand_t[here, None] - cand_t[None, :low]
        allowed = step >= -1e-12
        longest = np.where(allowed, count[None, :low], 0).max(axis=1)
        ds = cand_s[here, None] - cand_s[None, :low]
        predicted = 0.5 * ds * (cand_slope[here, None] + cand_slope[None, :low])
        # a step over a station that had candidates is a jump whatever the slopes say: its
        # miss counts only to part chains that tie (SKIP of it: a cost the chain read from
        # its other end gives alike, where the first of two equal ones was not)
        miss = np.abs(step - predicted)
        miss = np.where(rows[None, :low] == previous, miss, SKIP * np.nan_to_num(miss))
        through = np.where(allowed & (count[None, :low] == longest[:, None]), cost[None, :low] + miss, np.inf)
        best = np.argmin(through, axis=1)
        first = longest == 0
        count[here] = longest + 1
        previous = i
        cost[here] = np.where(first, start, through[np.arange(high - low), best])
        parent[here] = np.where(first, -1, best)
    if len(rows) == 0:
        return np.full(n, -1, dtype=np.int64)
    final = cost + end_weight * (1.0 - cand_t)
    last = int(np.lexsort((final, -count))[0])
    pick = np.full(n, -1, dtype=np.int64)
    while last >= 0:
        pick[rows[last]] = cols[last]
        last = int(parent[last])
    return pick
