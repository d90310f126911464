"""Spline approximation: turning a double-curved ruled surface towards a developable by
rotating its rulings about one fixed edge (the thesis's SplineApproximation, 6.2.1).

Construction (as in the thesis, Fig. 6.10)
------------------------------------------
1. *Stations*: ``Segments + 1`` points A_i on the fixed edge curve, evenly spaced in arc
   length (Grasshopper's Divide Curve), with the curve's unit tangents k_i there.
2. *Original rulings*: the surface's straight ruling through each A_i, pointing away
   from the fixed edge to the opposite edge: unit direction e⁰_i and length L_i.
3. *Rotation*: ruling i is turned by its angle θ_i about the edge tangent k_i
   (right-hand rule: thumb along the curve's direction) — Rodrigues' formula
   e_i = e⁰_i cos θ + (k × e⁰_i) sin θ + k (k·e⁰_i)(1 − cos θ). Rulings keep their
   length, so the new free end is B_i = A_i + L_i e_i: the thesis rotates the extracted
   rulings rigidly and lofts them, and the free edge is the spline through the new ends.
4. *Loft and warp*: the surface is the loft of the rotated rulings (the rails are the
   cubic not-a-knot splines through A_i and through B_i at u_i = i/n, see
   :meth:`~.ruled.RuledSurface.from_rulings`). The warp of ruling i is the angle between
   N1 = R × k_i (the fixed edge's exact tangent) and N2 = R × B'(u_i) (the free edge
   spline's tangent), R = B_i − A_i, in [0, π] (the turn of the tangent plane along the
   ruling; NaN where a normal has no direction). *Fitness* is the sum of the warp
   angles, the value the thesis feeds to Galapagos.

Optimisation (beyond the thesis)
--------------------------------
Instead of an evolutionary search over 0.01 rad steps, the angles solve the bounded
nonlinear least-squares problem

    minimise  Σ_i w_i(θ)²  +  μ² Σ_free (θ_j − θ⁰_j)²,     |θ_j| ≤ π/2,

with w_i the *signed* warp (smooth where the normals exist), by scipy's
Levenberg–Marquardt (MINPACK) with an analytic Jacobian; the bound holds through
θ = (π/2)·sin φ. The spline's tangents at its nodes are a fixed linear map of the node
values, B'(u_i) = Σ_j D_ij B_j, so the Jacobian is one diagonal plus one dense ``n × n``
term. MINPACK factors it with its own QR, not multithreaded LAPACK, which stalls when
the machine is busy.

The torsal conditions alone leave (in the smooth limit) a one-parameter family of
developables through the fixed edge, some rotated far from the input (unpulled, the
solver drifts to rulings turned a quarter turn); the faint pull μ = 1e-3 towards the
starting angles θ⁰ (zero: the input's rulings, as the thesis advises starting
Galapagos) picks the one nearest the input without measurably raising the warp. Same
input, same answer: the method is deterministic. Along that family the summed squares
are flat to rounding, so MINPACK's stopping point there depends on the input's last
bits; a few Gauss–Newton steps then settle on the optimum itself (:func:`_polished`), so
the same strip moved anywhere gets the same angles to ~1e-14 rad.

Minimising squared warps spreads what cannot be removed thinly instead of piling it
onto a few rulings (the thesis's fitness, the plain sum, would favour a few sharply
warped rulings). That matters with ``fix_ends``: the first and last rulings keep their
starting angles (the thesis's option of keeping the input's straight edges), which
over-constrains the strip — the family above has one free parameter, not two — so it
stays warped, as the thesis observed.
"""

from __future__ import annotations

from collections.abc import Callable
from contextlib import AbstractContextManager
from dataclasses import dataclass
from functools import cache

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.interpolate import make_interp_spline
from scipy.linalg import cho_factor, cho_solve
from scipy.optimize import least_squares
from threadpoolctl import ThreadpoolController

from .array_types import FloatArray
from .counts import segment_count
from .curve_base import Curve
from .developable.stations import station_parameters
from .developable.warp import end_normals
from .surface_base import IsoCurve, Surface
from .vec_ops import anchor, cross, dot, norm, unit

#: Largest rotation (rad) either way the optimiser may give a ruling: beyond a quarter
#: turn a ruling folds back over the fixed edge.
ANGLE_LIMIT = 0.5 * np.pi
#: Weight of the pull towards the starting angles (rad of warp per rad of rotation).
PULL = 1e-3
#: How far (relative to the surface's size) the fixed curve may stray from a surface edge.
EDGE_TOLERANCE = 1e-3
#: Most rulings the optimiser takes on (its Jacobian is dense, n × n: 300 rulings take
#: about half a second).
MAX_OPTIMISED = 300
#: Most residual evaluations per optimisation (it usually needs 7 to 15).
MAX_EVALUATIONS = 200
#: The evaluations a progress estimate counts as half the work.
TYPICAL_EVALUATIONS = 10


@dataclass(frozen=True)
class StationRulings:
    """The input surface's rulings at the stations of the fixed edge."""

    parameters: FloatArray  #: (n,) stations t on the fixed curve
    starts: FloatArray  #: (n, 3) points A_i on the fixed curve
    axes: FloatArray  #: (n, 3) unit tangents k_i of the fixed curve (rotation axes)
    directions: FloatArray  #: (n, 3) unit directions e⁰_i of the input rulings
    lengths: FloatArray  #: (n,) ruling lengths L_i
    edge: int  #: the surface edge (numbered as :meth:`Surface.edges`) the curve lies on
    distance: float  #: largest distance of the curve from that edge


@dataclass(frozen=True)
class Approximation:
    """Rotated rulings, their loft's edge tangents, normals and warp angles."""

    angles: FloatArray  #: (n,) rotation of each ruling about the edge tangent, rad
    starts: FloatArray  #: (n, 3) on the fixed edge
    ends: FloatArray  #: (n, 3) the free ends
    tangents_a: FloatArray  #: (n, 3) unit tangents of the fixed edge
    tangents_b: FloatArray  #: (n, 3) unit tangents of the free edge spline at the ends
    normals_a: FloatArray  #: (n, 3) unit N1 = R × T1
    normals_b: FloatArray  #: (n, 3) unit N2 = R × T2
    warp: FloatArray  #: (n,) warp angle, rad, in [0, π]: angle between N1 and N2 (NaN: undefined)
    signed_warp: FloatArray  #: (n,) angle from N1 to N2 about R, rad
    initial_fitness: float  #: summed warp at the starting angles
    evaluations: int  #: residual evaluations the optimiser used (0 without optimising)

    @property
    def fitness(self) -> float:
        """Sum of the warp angles, rad (the thesis's fitness; NaN if any warp is undefined)."""
        return float(self.warp.sum())


# -- the input surface's rulings along the fixed edge ------------------------------------


def _curved_edges(surface: Surface) -> list[tuple[int, IsoCurve, str, float]]:
    """The two edges that run across the rulings: (edge number, the edge as a curve run in
    the increasing parameter, the ruling parameter's name, the side the edge is on)."""
    direction = surface.ruling_direction
    if direction == "v":  # rulings u = const run in v: the curved edges are v = 0 and v = 1
        return [(0, IsoCurve(surface, "u", 0.0), "v", 0.0), (2, IsoCurve(surface, "u", 1.0), "v", 1.0)]
    if direction == "u":
        return [(3, IsoCurve(surface, "v", 0.0), "u", 0.0), (1, IsoCurve(surface, "v", 1.0), "u", 1.0)]
    raise ValueError(
        "The surface has no straight rulings: SplineApproximation needs a ruled surface, "
        "such as a loft between two curves."
    )


def station_rulings(surface: Surface, curve: Curve, segments: int) -> StationRulings:
    """The surface's rulings through ``segments + 1`` stations of ``curve`` (one of its
    curved edges, or a piece of one), each pointing away from that edge."""
    segments = segment_count(segments)
    if getattr(curve, "closed", False):
        raise ValueError(
            "The curve is closed: SplineApproximation needs an open edge (split a closed "
            "edge into two and approximate each)."
        )
    grid = np.linspace(0.0, 1.0, 9)
    uu, vv = np.meshgrid(grid, grid, indexing="ij")
    sample = surface.point_at(uu.ravel(), vv.ravel())
    size = float(norm(np.ptp(sample, axis=0)))
    if not np.isfinite(size) or size == 0.0:
        raise ValueError("The surface has no extent (all its points coincide or are not finite).")
    probe = curve.point_at(np.linspace(0.0, 1.0, 17))
    best: tuple[float, int, IsoCurve, str, float] | None = None
    for number, edge, name, side in _curved_edges(surface):
        distance = float(edge.closest_point(probe).distances.max())
        if best is None or distance < best[0]:
            best = (distance, number, edge, name, side)
    assert best is not None
    distance, number, edge, name, side = best
    if distance > EDGE_TOLERANCE * size:
        raise ValueError(
            f"The curve is not on a curved edge of the surface: it strays {distance:.3g} from "
            f"the nearest one (edge {number}); use edge 0 or 2 (v = 0, v = 1) of a surface ruled in "
            "v, edge 1 or 3 of one ruled in u."
        )
    t = station_parameters(curve, int(segments) + 1)
    starts, d1 = curve.derivatives(t, 1)
    if np.any(norm(d1) == 0.0):
        raise ValueError("The curve stops (zero tangent) at a station: rebuild it without stationary points.")
    along = edge.closest_point(starts).parameters
    other = 1.0 - side
    sides = np.full_like(along, side), np.full_like(along, other)
    if name == "v":
        (near, *d_near), far = surface.derivatives(along, sides[0], 1), surface.point_at(along, sides[1])
    else:
        (near, *d_near), far = surface.derivatives(sides[0], along, 1), surface.point_at(sides[1], along)
    lengths = norm(far - near)
    if np.any(lengths <= 1e-12 * size):
        i = int(np.argmin(lengths))
        raise ValueError(f"The surface's ruling at station {i} has zero length: the surface collapses there.")
    # along a straight ruling the surface's derivative is the ruling's direction; taken
    # from it rather than from far - near, it is not rounded to the ends' coordinates (at
    # site coordinates those are known to an ulp of 1e6 m, and the optimiser turns the
    # directions' rounding into ~70x as much in its angles)
    chords = far - near
    across = d_near[1] if name == "v" else d_near[0]
    along_ruling = np.einsum("ij,ij->i", across, chords)
    signed = np.where((along_ruling < 0.0)[:, None], -across, chords)
    across = np.where((along_ruling > 0.0)[:, None], across, signed)
    directions = unit(across)
    return StationRulings(t, starts, unit(d1), directions, lengths, number, distance)


# -- rotated rulings, their warp and its derivatives --------------------------------------


def node_derivative_matrix(count: int) -> FloatArray:
    """D with B'(u_i) = Σ_j D_ij B_j for the interpolating spline the loft uses (cubic
    not-a-knot, u_i = i/(n − 1); quadratic/linear for 3/2 points)."""
    u = np.linspace(0.0, 1.0, count)
    spline = make_interp_spline(u, np.eye(count), k=min(3, count - 1))
    return np.asarray(spline.derivative()(u), dtype=float)


class RotatedStrip:
    """The strip of rulings turned by given angles about the fixed edge's tangents."""

    def __init__(self, stations: StationRulings) -> None:
        self.stations = stations
        self.k = stations.axes
        self.e0 = stations.directions
        self.k_cross_e0 = cross(self.k, self.e0)
        self.k_dot_e0 = dot(self.k, self.e0)[:, None]
        self.lengths = stations.lengths[:, None]
        self.derivative = node_derivative_matrix(len(stations.lengths))
        # the free edge's tangents D @ B are differences of the ends: taken about the
        # stations' anchor, they round relative to the strip's size, not its position
        self.origin = anchor(stations.starts)
        self.local_starts = stations.starts - self.origin

    def directions(self, angles: FloatArray) -> FloatArray:
        c, s = np.cos(angles)[:, None], np.sin(angles)[:, None]
        return self.e0 * c + self.k_cross_e0 * s + self.k * self.k_dot_e0 * (1.0 - c)

    def geometry(self, angles: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray]:
        """Rulings R_i, free ends B_i and the free edge's (unscaled) tangents there."""
        rulings = self.lengths * self.directions(angles)
        local_ends = self.local_starts + rulings
        return rulings, self.origin + local_ends, self.derivative @ local_ends

    def signed_warp(self, angles: FloatArray, jacobian: bool = False) -> tuple[FloatArray, FloatArray | None]:
        """Signed warp w_i = atan2(det[R, k, b]·|R|, (R × k)·(R × b)) and, optionally, dw/dθ.

        (R × k) × (R × b) = det[R, k, b]·R, so the first argument is the normals' cross
        product along R̂ scaled by |R|², like the second.
        """
        rulings, _, b = self.geometry(angles)
        k = self.k
        length = norm(rulings)
        triple = dot(rulings, cross(k, b))
        x = triple * length
        rb, rk = dot(rulings, b), dot(rulings, k)
        y = dot(rulings, rulings) * dot(k, b) - rk * rb
        warp = np.arctan2(x, y)
        if not jacobian:
            return warp, None
        q = x * x + y * y
        q = np.where(q > 0.0, q, np.inf)  # no plane, no warp, no gradient
        dx_r = length[:, None] * cross(k, b) + (triple / np.where(length > 0, length, 1.0))[:, None] * rulings
        dx_b = length[:, None] * cross(rulings, k)
        dy_r = 2.0 * rulings * dot(k, b)[:, None] - k * rb[:, None] - b * rk[:, None]
        dy_b = dot(rulings, rulings)[:, None] * k - rk[:, None] * rulings
        w_r = (y[:, None] * dx_r - x[:, None] * dy_r) / q[:, None]
        w_b = (y[:, None] * dx_b - x[:, None] * dy_b) / q[:, None]
        g = self.lengths * cross(k, rulings / np.where(length > 0, length, 1.0)[:, None])  # dR_i/dθ_i
        jac = self.derivative * (w_b @ g.T)
        jac[np.diag_indices_from(jac)] += dot(w_r, g)
        return warp, jac

    def result(self, angles: FloatArray, initial_fitness: float, evaluations: int) -> Approximation:
        rulings, ends, b = self.geometry(angles)
        tb = unit(b)
        n1, n2 = unit(cross(rulings, self.k)), unit(cross(rulings, tb))
        signed = self.signed_warp(angles)[0]
        undefined = ~_has_plane(rulings, self.k, tb)
        signed[undefined] = np.nan
        warp = np.abs(signed)
        return Approximation(
            angles.copy(), self.stations.starts.copy(), ends, self.k.copy(), tb, n1, n2, warp, signed,
            initial_fitness, evaluations,
        )


def _has_plane(rulings: FloatArray, ta: FloatArray, tb: FloatArray) -> NDArray[np.bool_]:
    """Where both end normals R × T have a direction (:mod:`.developable.warp`'s rule)."""
    n1, n2, _ = end_normals(np.zeros_like(rulings), rulings, ta, tb)
    return np.isfinite(n1).all(axis=1) & np.isfinite(n2).all(axis=1)


def approximate(
    stations: StationRulings,
    angles: ArrayLike | None = None,
    optimise: bool = False,
    fix_ends: bool = False,
    check: Callable[[], None] | None = None,
    progress: Callable[[float], None] | None = None,
) -> Approximation:
    """Rotate the rulings by ``angles`` (rad, one per ruling; None for all 0) or, with
    ``optimise``, by the angles of least summed warp starting from them.

    ``check`` is called at every evaluation (a node passes its cancellation check);
    ``progress`` gets an estimate of the fraction done after each: e / (e + 10) after
    e evaluations (the optimisation usually needs 7 to 15; how many is not known
    beforehand), and 1 when it ends.
    """
    strip = RotatedStrip(stations)
    n = len(stations.lengths)
    start = np.zeros(n) if angles is None else np.asarray(angles, dtype=float).reshape(-1).copy()
    if start.shape != (n,):
        raise ValueError(f"Give one angle per ruling: {n} rulings, {start.size} angles.")
    if not np.all(np.isfinite(start)):
        raise ValueError("An angle is not a finite number.")
    initial = strip.signed_warp(start)[0]
    rulings, _, b = strip.geometry(start)
    initial[~_has_plane(rulings, strip.k, unit(b))] = np.nan
    initial_fitness = float(np.abs(initial).sum())
    if not optimise:
        return strip.result(start, initial_fitness, 0)
    if n > MAX_OPTIMISED:
        raise ValueError(
            f"Optimising takes at most {MAX_OPTIMISED} rulings; lower Segments to {MAX_OPTIMISED - 1}."
        )
    free = np.arange(1, n - 1) if fix_ends else np.arange(n)
    if len(free) == 0:
        return strip.result(start, initial_fitness, 0)
    # bounded through θ = limit·sin(φ), so MINPACK's Levenberg–Marquardt (deterministic,
    # self-contained QR: no multithreaded LAPACK, which stalls on a busy machine) can run
    # unconstrained in φ
    x0 = np.clip(start[free], -ANGLE_LIMIT, ANGLE_LIMIT)
    evaluations = 0

    def full(phi: FloatArray) -> FloatArray:
        theta = start.copy()
        theta[free] = ANGLE_LIMIT * np.sin(phi)
        return theta

    def residuals(phi: FloatArray) -> FloatArray:
        nonlocal evaluations
        evaluations += 1
        if check is not None:
            check()
        if progress is not None:
            progress(evaluations / (evaluations + TYPICAL_EVALUATIONS))
        return np.concatenate([strip.signed_warp(full(phi))[0], PULL * (ANGLE_LIMIT * np.sin(phi) - x0)])

    def jacobian(phi: FloatArray) -> FloatArray:
        jac = strip.signed_warp(full(phi), jacobian=True)[1]
        assert jac is not None
        slope = ANGLE_LIMIT * np.cos(phi)
        return np.vstack([jac[:, free] * slope[None, :], np.diag(PULL * slope)])

    fit = least_squares(
        residuals, np.arcsin(x0 / ANGLE_LIMIT), jac=jacobian, method="lm",
        xtol=1e-12, ftol=1e-12, gtol=1e-12, max_nfev=MAX_EVALUATIONS,
    )
    theta, steps = _polished(strip, full(fit.x), free, x0, check)
    if progress is not None:
        progress(1.0)
    return strip.result(theta, initial_fitness, evaluations + steps)


@cache
def _blas() -> ThreadpoolController:
    """The BLAS libraries loaded (numpy's and scipy's OpenBLAS), found once."""
    return ThreadpoolController()


def _one_blas_thread() -> AbstractContextManager[object]:
    """A context in which BLAS and LAPACK run on one thread (:mod:`threadpoolctl`)."""
    return _blas().limit(limits=1, user_api="blas")


#: Most Gauss–Newton steps that finish an optimisation (each gains about a digit: 2 to 8
#: from where MINPACK stops to rounding).
POLISH_STEPS = 12


def _polished(
    strip: RotatedStrip, theta: FloatArray, free: NDArray[np.intp], x0: FloatArray,
    check: Callable[[], None] | None = None,
) -> tuple[FloatArray, int]:
    """The optimum itself from where Levenberg–Marquardt stopped, and the steps taken.

    Along the one-parameter family of near-developables only the faint pull μ holds the
    angles, so the summed squares are flat there to rounding and MINPACK stops anywhere
    within ~5e-8 rad of the optimum — where exactly depends on the last bits of its
    input: the same strip moved by 16 m turned its rulings' ends by 1e-8 of its size.
    Gauss–Newton steps on the optimum's condition g = Jᵀw + μ²(θ − θ⁰) = 0 (free angles)
    settle on it to ~1e-14 rad wherever the strip sits. The matrix JᵀJ + μ²I is factored
    once, where MINPACK stopped (it hardly changes over the last 5e-8 rad), by Cholesky
    (:func:`scipy.linalg.cho_factor`) on one BLAS thread: OpenBLAS's threads gain nothing
    on a matrix this small and, on a busy machine, stalled a 200-ruling solve 4× (0.39 s
    against 1.78 s). The steps stop when one no longer shrinks, and never leave the angle
    limit."""
    theta = theta.copy()
    factor: tuple[FloatArray, bool] | None = None
    previous = np.inf
    for step in range(POLISH_STEPS):
        if check is not None:
            check()
        warp, jac = strip.signed_warp(theta, jacobian=True)
        assert jac is not None
        if not (np.isfinite(warp).all() and np.isfinite(jac).all()):
            return theta, step
        j = jac[:, free]
        gradient = np.einsum("ki,k->i", j, warp) + PULL**2 * (theta[free] - x0)
        if factor is None:
            normal = np.einsum("ki,kj->ij", j, j)
            normal[np.diag_indices_from(normal)] += PULL**2
            try:
                with _one_blas_thread():
                    factor = cho_factor(normal, lower=True)
            except np.linalg.LinAlgError:  # not positive definite to rounding (huge entries)
                return theta, step
        with _one_blas_thread():
            delta = -cho_solve(factor, gradient)
        size = float(np.abs(delta).max(initial=0.0))
        moved = theta[free] + delta
        if not (size < previous and np.isfinite(size) and np.abs(moved).max(initial=0.0) <= ANGLE_LIMIT):
            return theta, step + 1
        theta[free] = moved
        previous = size
        if size <= 4.0 * np.finfo(float).eps:
            return theta, step + 1
    return theta, POLISH_STEPS
