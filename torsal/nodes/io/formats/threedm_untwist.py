"""A fitted ruled face's rails moved, within the fit's tolerance, until the face is developable.

A ruled face between two cubic B-spline rails A(u), B(u) (degree 1 across) is developable
where det(A'(u), B'(u), B(u) − A(u)) = 0: its normals at the two ends of the line across,
n0 = A' × r and n1 = B' × r (r = B − A), are parallel, and the sine of the angle between
them is |det| · |r| / (|n0| |n1|). Rails fitted to a developable pairing of the strip's own
rails by least squares on their points are within the fit's tolerance but their tangents
are not exact, and the normals turn by up to a few 1e-6 rad along a line across: a fit to
a hundredth of that tolerance would cost several times the control points.

:func:`untwisted` keeps the knots and moves the free control points by Gauss–Newton steps
on two sets of residuals at once: the rails' distances from the samples they were fitted
to (over the fit's tolerance) and that sine at the same samples (over the twist allowed).
det is trilinear in A', B' and r, each linear in the control points, so each step is one
sparse linear least squares (the normal equations, solved by scipy's sparse LU); the
normalisation is held at the last step's value. A face that was already close (the
ordinary case) is developable within a few steps; one whose pairing admits no developable
face nearby stays twisted, and the caller judges it.
"""

from __future__ import annotations

import warnings

import numpy as np
import scipy.sparse as sp
from scipy.interpolate import BSpline
from scipy.sparse.linalg import MatrixRankWarning, spsolve

#: Gauss–Newton steps at most, per round.
STEPS = 6

#: Steps stop when one gains less than this factor on the best miss so far.
STALL = 0.9

#: Rounds of steps, each after knots are inserted where the face still twists.
ROUNDS = 8

#: Each round splits the spans that miss by at least this share of the worst miss.
WORST = 0.5

#: Samples a span keeps at least when a knot splits it.
PER_SPAN = 4

#: Levenberg–Marquardt damping, relative to the normal equations' diagonal.
DAMPING = 1e-6

#: The steps aim the distance and the twist at this share of what each is allowed.
AIM = 0.5


def derivative_basis(at: np.ndarray, knots: np.ndarray) -> sp.csr_matrix:
    """The cubic B-spline basis' first derivatives at ``at`` (rows) on ``knots``: the
    quadratic basis on the inner knots times the difference matrix (the derivative's
    control points are 3 (c_{j+1} − c_j) / (t_{j+4} − t_{j+1}))."""
    count = len(knots) - 4
    quadratic = BSpline.design_matrix(at, knots[1:-1], 2)
    spans = knots[4:count + 3] - knots[1:count]
    scale = np.divide(3.0, spans, out=np.zeros_like(spans), where=spans > 0)
    rows = np.arange(count - 1)
    entries = (np.tile(rows, 2), np.concatenate([rows, rows + 1]))
    difference = sp.csr_matrix((np.concatenate([-scale, scale]), entries), shape=(count - 1, count))
    return (quadratic @ difference).tocsr()


def twist_sines(points: np.ndarray, slopes: np.ndarray) -> np.ndarray:
    """The sine of the angle between a ruled face's normals at the two ends of its lines
    across, from its rails' points and slopes side by side (n, 6); 0 where undefined."""
    ruling = points[:, 3:] - points[:, :3]
    det = np.einsum("ij,ij->i", ruling, np.cross(slopes[:, :3], slopes[:, 3:]))
    scale = np.linalg.norm(np.cross(slopes[:, :3], ruling), axis=1) * \
        np.linalg.norm(np.cross(slopes[:, 3:], ruling), axis=1)
    with np.errstate(divide="ignore", invalid="ignore"):
        sines = det * np.linalg.norm(ruling, axis=1) / scale
    return np.where(np.isfinite(sines), sines, 0.0)


def untwisted(spline: BSpline, at: np.ndarray, data: np.ndarray, tolerance: float,
              twist: float, held: np.ndarray | None = None,
              bent: np.ndarray | None = None) -> tuple[BSpline, float, float]:
    """``spline`` (both rails side by side, (x, y, z) of A then of B) with its control points
    but the two at either end (the end rulings and the rails' end tangents) moved so that
    it stays within ``tolerance`` of ``data`` at ``at`` and its normals turn by less than
    ``twist`` (rad) along the lines across at ``at``, its points and slopes at ``held`` (the
    rulings inside the face) kept as they are, and where ``bent`` (end, rail) the rail's
    third control point from that end (its second derivative there: a rail that stands
    still at an end has its direction there from it): (spline, largest distance, largest
    angle at ``at``). Where the steps do not get there, a knot is inserted in the middle of
    each span that still twists (the same rails, more freedom; a span keeps at least
    :data:`PER_SPAN` samples) and the steps go on, :data:`ROUNDS` times at most; the best
    spline found (or ``spline`` itself) when they do not get there."""
    best = (spline, *_measure(spline, at, data))
    current = spline
    for _ in range(ROUNDS):
        current, distance, angle = _steps(current, at, data, tolerance, twist, held, bent)
        if _miss((distance, angle), tolerance, twist) < _miss(best[1:], tolerance, twist):
            best = (current, distance, angle)
        if distance <= tolerance and angle <= twist:
            break
        knots = np.unique(current.t)
        points = current(at)
        sines = np.abs(twist_sines(points, current.derivative()(at)))
        off = np.maximum(np.linalg.norm(points[:, :3] - data[:, :3], axis=1),
                         np.linalg.norm(points[:, 3:] - data[:, 3:], axis=1))
        span = np.clip(np.searchsorted(knots, at, side="right") - 1, 0, len(knots) - 2)
        samples = np.bincount(span, minlength=len(knots) - 1)
        # the spans that miss most (over what each is allowed): a knot in each
        miss = np.maximum(sines / np.sin(twist), off / tolerance)
        twisted = np.unique(span[(miss > 1.0) & (miss >= WORST * miss.max())])
        twisted = twisted[samples[twisted] >= 2 * PER_SPAN]
        if not len(twisted):
            break
        for middle in 0.5 * (knots[twisted] + knots[twisted + 1]):
            current = current.insert_knot(float(middle))
    return best


def _steps(spline: BSpline, at: np.ndarray, data: np.ndarray, tolerance: float,
           twist: float, held: np.ndarray | None = None,
           bent: np.ndarray | None = None) -> tuple[BSpline, float, float]:
    """Gauss–Newton steps on ``spline``'s free control points (:func:`untwisted`: but the
    two at either end, those not zero at ``held`` and the rails' ``bent`` ends' third), on
    its knots: the best spline found, its largest distance and angle."""
    knots = np.asarray(spline.t, dtype=float)
    count = len(knots) - 4
    controls = np.array(spline.c, dtype=float)[:count]
    best = (spline, *_measure(spline, at, data))
    if count <= 4:
        return best
    basis = BSpline.design_matrix(at, knots, 3).tocsr()
    slope_basis = derivative_basis(at, knots)
    free = np.arange(2, count - 2)
    if held is not None and len(held):
        touched = (BSpline.design_matrix(held, knots, 3) + abs(derivative_basis(held, knots))).tocsc()
        free = free[np.diff(touched.indptr)[free] == 0]
    frozen = np.zeros((count, 6), dtype=bool)  # coordinates of free control points held
    for end, rail in zip(*np.nonzero(bent if bent is not None else np.zeros((2, 2))), strict=True):
        frozen[(2, count - 3)[end], 3 * rail:3 * rail + 3] = True
    free = free[~frozen[free].all(axis=1)]
    if not len(free):
        return best
    moving = np.flatnonzero(~frozen[free].T.ravel())  # the variables (by coordinate) the steps move
    width = len(free)
    base_free, slope_free = basis[:, free].tocoo(), slope_basis[:, free].tocoo()
    # the distances' rows: one block per coordinate (constant), and their normal equations
    position = sp.block_diag([base_free.tocsr()] * 6, format="csr") / (AIM * tolerance)
    position_normal = (position.T @ position).tocsc()
    rows = np.concatenate([slope_free.row, base_free.row])
    columns = np.concatenate([slope_free.col, base_free.col])
    for _ in range(STEPS):
        points, slopes = basis @ controls, slope_basis @ controls
        ruling = points[:, 3:] - points[:, :3]
        tangent_a, tangent_b = slopes[:, :3], slopes[:, 3:]
        det = np.einsum("ij,ij->i", ruling, np.cross(tangent_a, tangent_b))
        norm = np.linalg.norm(np.cross(tangent_a, ruling), axis=1) * \
            np.linalg.norm(np.cross(tangent_b, ruling), axis=1)
        length = np.linalg.norm(ruling, axis=1)
        usable = (norm > 0) & np.isfinite(norm)
        weight = np.where(usable, length / np.where(usable, norm, 1.0), 0.0) / (AIM * twist)
        # d det = (B' × r) · dA' + (r × A') · dB' + (A' × B') · (dB − dA): the twist's
        # rows, one entry per basis function and coordinate of each rail
        by_slope = np.hstack([np.cross(tangent_b, ruling), np.cross(ruling, tangent_a)]) * weight[:, None]
        by_ruling = np.cross(tangent_a, tangent_b) * weight[:, None]
        by_point = np.hstack([-by_ruling, by_ruling])
        values = np.concatenate([by_slope[slope_free.row] * slope_free.data[:, None],
                                 by_point[base_free.row] * base_free.data[:, None]])  # (entries, 6)
        twist_rows = sp.csr_matrix((values.T.ravel(), (np.tile(rows, 6), (np.arange(6)[:, None] * width
                                                                          + columns[None, :]).ravel())),
                                   shape=(len(at), 6 * width))
        distance_residual = ((points - data) / (AIM * tolerance)).T.ravel()
        gradient = position.T @ distance_residual + twist_rows.T @ (weight * det)
        normal = (position_normal + twist_rows.T @ twist_rows).tocsc()
        if len(moving) < 6 * len(free):
            normal, gradient = normal[np.ix_(moving, moving)].tocsc(), gradient[moving]
        # damped (Levenberg–Marquardt): a control point no sample pins stays put
        diagonal = normal.diagonal()
        damping = sp.diags(DAMPING * diagonal + 1e-12 * max(float(diagonal.max()), 1.0))
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("error", MatrixRankWarning)
                step = spsolve((normal + damping).tocsc(), -gradient)
        except (MatrixRankWarning, RuntimeError):
            break
        if not np.all(np.isfinite(step)):
            break
        full = np.zeros(6 * width)
        full[moving] = step
        controls[free] += full.reshape(6, width).T
        trial = BSpline(knots, controls.copy(), 3)
        distance, angle = _measure(trial, at, data)
        before = _miss(best[1:], tolerance, twist)
        if _miss((distance, angle), tolerance, twist) < before:
            best = (trial, distance, angle)
        if (distance <= tolerance and angle <= twist) or _miss(best[1:], tolerance, twist) > STALL * before:
            break  # there, or the steps stall on these knots
    return best


def _measure(spline: BSpline, at: np.ndarray, data: np.ndarray) -> tuple[float, float]:
    points = spline(at)
    distance = np.maximum(np.linalg.norm(points[:, :3] - data[:, :3], axis=1),
                          np.linalg.norm(points[:, 3:] - data[:, 3:], axis=1))
    sines = np.abs(twist_sines(points, spline.derivative()(at)))
    return float(distance.max()), float(np.arcsin(np.clip(sines, 0.0, 1.0)).max())


def _miss(fit: tuple[float, float], tolerance: float, twist: float) -> float:
    """How far a fit (distance, angle) misses: each over what it is allowed, the worse."""
    return max(fit[0] / tolerance, fit[1] / twist)
