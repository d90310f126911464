"""Curve pairs cut from known developables, with the true ruling partner of every point.

Each pair is built from a surface S(u, w) whose rulings are the lines u = const: curve A
is S(u_A(s), w_A(s)) and curve B is S(u_B(τ), w_B(τ)) with τ a *warped* function of B's
own parameter t, so B is re-parameterised non-uniformly. The true ruling through A(s)
is the line u = u_A(s); its partner on B is the t where u_B(τ(t)) = u_A(s), known in
closed form. All derivatives are analytic, so the errors measured are the solver's.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from torsal.nodes.geometry.curves import NurbsCurve, ParametricCurve

Array = np.ndarray

#: τ(t) = (e^{kt} − 1)/(e^k − 1): a smooth, strongly non-uniform re-parameterisation.
WARP_K = 1.5


def warp(t: Array) -> tuple[Array, Array, Array]:
    """τ, dτ/dt, d²τ/dt² of the warped parameter."""
    e = math.expm1(WARP_K)
    g = np.exp(WARP_K * t)
    return (g - 1.0) / e, WARP_K * g / e, WARP_K**2 * g / e


def unwarp(tau: Array) -> Array:
    """t with τ(t) = tau."""
    return np.log1p(tau * math.expm1(WARP_K)) / WARP_K


@dataclass
class Pair:
    """Two curves on one developable and the true partner map s → t."""

    a: ParametricCurve
    b: ParametricCurve
    partner: Callable[[Array], Array]  #: true t on B for s on A
    size: float  #: bounding-box diagonal of the pair


def _curve(surface, u_of, w_of, warped: bool) -> ParametricCurve:
    """The curve x ↦ S(u(τ), w(τ)) with τ = x (or warp(x)), and its first two derivatives.

    ``surface(u, w)`` returns (S, S_u, S_w, S_uu, S_uw, S_ww); ``u_of``/``w_of`` return
    (value, first, second derivative) in τ.
    """

    def parts(x):
        if warped:
            tau, dtau, ddtau = warp(x)
        else:
            tau, dtau, ddtau = x, np.ones_like(x), np.zeros_like(x)
        u, du, ddu = u_of(tau)
        w, dw, ddw = w_of(tau)
        p, su, sw, suu, suw, sww = surface(u, w)
        # chain rule in τ, then in x
        d1_tau = su * du[:, None] + sw * dw[:, None]
        d2_tau = (
            suu * (du**2)[:, None]
            + 2 * suw * (du * dw)[:, None]
            + sww * (dw**2)[:, None]
            + su * ddu[:, None]
            + sw * ddw[:, None]
        )
        d1 = d1_tau * dtau[:, None]
        d2 = d2_tau * (dtau**2)[:, None] + d1_tau * ddtau[:, None]
        return p, d1, d2

    return ParametricCurve(
        lambda x: parts(np.asarray(x, float))[0],
        (0.0, 1.0),
        derivatives=(lambda x: parts(np.asarray(x, float))[1], lambda x: parts(np.asarray(x, float))[2]),
    )


def _size(a: ParametricCurve, b: ParametricCurve) -> float:
    x = np.linspace(0, 1, 200)
    p = np.concatenate([a.point_at(x), b.point_at(x)])
    return float(np.linalg.norm(p.max(axis=0) - p.min(axis=0)))


def _lin(a: float, b: float):
    return lambda x: (a + (b - a) * x, np.full_like(x, b - a), np.zeros_like(x))


def _wave(base: float, amp: float, freq: float, phase: float = 0.0):
    return lambda x: (
        base + amp * np.sin(freq * x + phase),
        amp * freq * np.cos(freq * x + phase),
        -amp * freq**2 * np.sin(freq * x + phase),
    )


# -- cone: apex at the origin, axis z, half-angle α; S(u, w) = w·(sin α cos u, sin α sin u, cos α)

CONE_ALPHA = 0.5


def cone_surface(u, w):
    sa, ca = math.sin(CONE_ALPHA), math.cos(CONE_ALPHA)
    e = np.column_stack([sa * np.cos(u), sa * np.sin(u), np.full_like(u, ca)])
    eu = np.column_stack([-sa * np.sin(u), sa * np.cos(u), np.zeros_like(u)])
    euu = np.column_stack([-sa * np.cos(u), -sa * np.sin(u), np.zeros_like(u)])
    z = np.zeros_like(e)
    return w[:, None] * e, w[:, None] * eu, e, w[:, None] * euu, eu, z


def cone_pair() -> Pair:
    """Two wavy, non-planar curves on a cone over 2.5 rad of its generators."""
    span = 2.5
    a = _curve(cone_surface, _lin(0.0, span), _wave(2.0, 0.3, 7.0), warped=False)
    b = _curve(cone_surface, _lin(0.0, span), _wave(4.0, 0.5, 5.0, 1.0), warped=True)
    return Pair(a, b, lambda s: unwarp(np.asarray(s, float)), _size(a, b))


# -- cylinder: S(u, w) = (R cos u, R sin u, w)

CYL_R = 3.0


def cylinder_surface(u, w):
    p = np.column_stack([CYL_R * np.cos(u), CYL_R * np.sin(u), w])
    pu = np.column_stack([-CYL_R * np.sin(u), CYL_R * np.cos(u), np.zeros_like(u)])
    pw = np.column_stack([np.zeros_like(u), np.zeros_like(u), np.ones_like(u)])
    puu = np.column_stack([-CYL_R * np.cos(u), -CYL_R * np.sin(u), np.zeros_like(u)])
    z = np.zeros_like(p)
    return p, pu, pw, puu, z, z


def cylinder_pair() -> Pair:
    """A low wavy curve and a high wavy curve on a cylinder, over 3 rad."""
    span = 3.0
    a = _curve(cylinder_surface, _lin(0.0, span), _wave(0.0, 0.4, 4.0), warped=False)
    b = _curve(cylinder_surface, _lin(0.0, span), _wave(2.5, 0.3, 3.0, 0.5), warped=True)
    return Pair(a, b, lambda s: unwarp(np.asarray(s, float)), _size(a, b))


# -- tangent developable of the helix H(u) = (R cos u, R sin u, h u): S(u, w) = H(u) + w·T(u)

HELIX_R, HELIX_H = 2.0, 0.8


def helix_developable_surface(u, w):
    c = math.hypot(HELIX_R, HELIX_H)
    h = np.column_stack([HELIX_R * np.cos(u), HELIX_R * np.sin(u), HELIX_H * u])
    h1 = np.column_stack([-HELIX_R * np.sin(u), HELIX_R * np.cos(u), np.full_like(u, HELIX_H)])
    h2 = np.column_stack([-HELIX_R * np.cos(u), -HELIX_R * np.sin(u), np.zeros_like(u)])
    h3 = np.column_stack([HELIX_R * np.sin(u), -HELIX_R * np.cos(u), np.zeros_like(u)])
    t, t1, t2 = h1 / c, h2 / c, h3 / c
    z = np.zeros_like(h)
    wc = w[:, None]
    return h + wc * t, h1 + wc * t1, t, h2 + wc * t2, t1, z


def helix_developable_pair() -> Pair:
    """Two curves on one sheet of the helix's tangent developable, over 3 rad."""
    span = 3.0
    a = _curve(helix_developable_surface, _lin(0.0, span), _wave(0.6, 0.15, 5.0), warped=False)
    b = _curve(helix_developable_surface, _lin(0.0, span), _wave(2.5, 0.4, 4.0, 0.3), warped=True)
    return Pair(a, b, lambda s: unwarp(np.asarray(s, float)), _size(a, b))


PAIRS = {"cone": cone_pair, "cylinder": cylinder_pair, "helix_developable": helix_developable_pair}


# -- NURBS curves exactly on a cone: re-weighted rational arcs ------------------------------
#
# A rational curve is X(t)/w(t) in homogeneous coordinates. Keeping X (the weighted control
# points) and changing only the weights moves every point along its ray from the origin,
# so a circular arc on a cone with apex at the origin stays on that cone, but becomes a
# wavy, non-planar curve whose parameter runs non-uniformly in angle.


def _arc_nurbs(radius: float, height: float, sweep: float, spans: int, reweight: Array) -> NurbsCurve:
    half = sweep / spans / 2
    k = np.arange(2 * spans + 1)
    angles = half * k
    distance = np.where(k % 2 == 1, radius / math.cos(half), radius)
    points = np.column_stack([distance * np.cos(angles), distance * np.sin(angles), np.full(len(k), height)])
    weights = np.where(k % 2 == 1, math.cos(half), 1.0)
    knots = np.concatenate([[0.0] * 3, np.repeat(np.arange(1, spans) / spans, 2), [1.0] * 3])
    new_weights = weights * reweight
    return NurbsCurve(points * (weights / new_weights)[:, None], degree=2, knots=knots, weights=new_weights)


def _angle(curve: NurbsCurve, t: Array) -> Array:
    p = curve.point_at(t)
    return np.arctan2(p[:, 1], p[:, 0])


def _same_angle(a, b) -> Callable[[Array], Array]:
    """The partner on B of each A(s): the point at the same angle round the cone's axis
    (B's angle increases along it), by bisection."""

    def partner(s: Array) -> Array:
        target = _angle(a, np.atleast_1d(np.asarray(s, float)))
        low, high = np.zeros_like(target), np.ones_like(target)
        for _ in range(60):
            mid = 0.5 * (low + high)
            below = _angle(b, mid) < target
            low, high = np.where(below, mid, low), np.where(below, high, mid)
        return 0.5 * (low + high)

    return partner


def nurbs_cone_pair(sweep: float = 2.4) -> Pair:
    """Rational quadratic curves on the cone of half-angle CONE_ALPHA (apex at the origin):
    A from 4 arc spans, B from 7, both re-weighted; partners share their angle."""
    tan = math.tan(CONE_ALPHA)
    a = _arc_nurbs(1.0 * tan, 1.0, sweep, 4, 1.0 + 0.25 * np.sin(1.7 * np.arange(9)))
    b = _arc_nurbs(2.2 * tan, 2.2, sweep, 7, 1.0 + 0.3 * np.cos(1.3 * np.arange(15)))

    return Pair(a, b, _same_angle(a, b), _size(a, b))


PAIRS["nurbs_cone"] = nurbs_cone_pair


# -- smooth NURBS on a cone: tilted plane sections (exact rational conics) ------------------
#
# The central projection from the apex (the origin) onto the plane n·x = d, x ↦ d·x/(n·x),
# is the projective map [[d·I, 0], [nᵀ, 0]]. It keeps every point on its ray from the apex,
# so it carries a circle on the cone to the conic where the tilted plane cuts the cone:
# smooth, exact, with a parameter that runs non-uniformly in angle.


def _projection(normal, offset: float) -> Array:
    m = np.zeros((4, 4))
    m[:3, :3] = offset * np.eye(3)
    m[3, :3] = normal
    return m


def conic_sections_pair(sweep: float = 2.4) -> Pair:
    """Two tilted plane sections of the cone of half-angle CONE_ALPHA over ``sweep``."""
    from torsal.nodes.geometry.curves import Arc
    from torsal.nodes.geometry.vectors import Plane

    tan = math.tan(CONE_ALPHA)
    circle_a = Arc(Plane.from_normal([0, 0, 1], [0, 0, 1]), tan, 0.0, sweep)
    circle_b = Arc(Plane.from_normal([0, 0, 1], [0, 0, 1]), tan, -0.0, sweep)
    a = circle_a.transformed(_projection([0.15, 0.1, 1.0], 1.0))
    b = circle_b.transformed(_projection([-0.1, 0.2, 1.0], 2.4))

    return Pair(a, b, _same_angle(a, b), _size(a, b))


PAIRS["conic_sections"] = conic_sections_pair


# -- plane sections of a cylinder and of a cone over a directrix with inflection points ------
#
# The directrix d(u) = (u, Y·sin(ω·u)), u in [0, U], turns its bending direction at every
# zero of sin(ω·u): ω·U/π − 1 inflection points in all. Each curve of a pair is where a
# plane meets the cylinder (generators parallel to z) or the cone (generators through the
# origin) over that directrix; the two planes are not parallel. Plane sections keep the
# inflections, and the true partner of A(s) is the point of B on the same generator.

DIRECTRIX_Y, DIRECTRIX_OMEGA, DIRECTRIX_U = 0.6, 3.0 * math.pi / 4.0, 4.0  # 2 inflections


def _directrix(u: Array) -> tuple[Array, Array, Array]:
    """d, d', d'' of the wavy planar directrix, each ``(n, 3)``."""
    y, w = DIRECTRIX_Y, DIRECTRIX_OMEGA
    zero, one = np.zeros_like(u), np.ones_like(u)
    return (
        np.column_stack([u, y * np.sin(w * u), zero]),
        np.column_stack([one, y * w * np.cos(w * u), zero]),
        np.column_stack([zero, -y * w * w * np.sin(w * u), zero]),
    )


def _section_curve(section, warped: bool) -> ParametricCurve:
    """x ↦ section(U·τ(x)) with τ = x or :func:`warp`, given ``section(u) -> (P, P_u, P_uu)``."""

    def parts(x):
        x = np.asarray(x, float)
        tau, dtau, ddtau = warp(x) if warped else (x, np.ones_like(x), np.zeros_like(x))
        p, pu, puu = section(DIRECTRIX_U * tau)
        du, ddu = DIRECTRIX_U * dtau, DIRECTRIX_U * ddtau
        return p, pu * du[:, None], puu * (du**2)[:, None] + pu * ddu[:, None]

    return ParametricCurve(
        lambda x: parts(x)[0], (0.0, 1.0), derivatives=(lambda x: parts(x)[1], lambda x: parts(x)[2])
    )


def _cylinder_section(slope: tuple[float, float], height: float):
    """The cut of the cylinder over the directrix by the plane z = slope·(x, y) + height."""
    k = np.array([slope[0], slope[1], 0.0])

    def section(u):
        d, d1, d2 = _directrix(u)
        lift = np.zeros_like(d)
        return (
            d + np.outer(d @ k + height, [0, 0, 1]),
            d1 + np.outer(d1 @ k, [0, 0, 1]) + lift,
            d2 + np.outer(d2 @ k, [0, 0, 1]),
        )

    return section


def cylinder_sections_pair() -> Pair:
    """Two non-parallel plane cuts of the cylinder over the inflected directrix; B warped."""
    a = _section_curve(_cylinder_section((0.15, -0.1), 0.0), warped=False)
    b = _section_curve(_cylinder_section((-0.2, 0.25), 2.5), warped=True)
    return Pair(a, b, lambda s: unwarp(np.asarray(s, float)), _size(a, b))


def _cone_section(normal: tuple[float, float, float], offset: float):
    """The cut of the cone from the origin over the directrix lifted to z = 1 by the plane
    normal·x = offset: the central projection P = offset·c/(normal·c) of c = d + (0, 0, 1)."""
    n = np.asarray(normal, float)

    def section(u):
        d, d1, d2 = _directrix(u)
        c = d + np.array([0.0, 0.0, 1.0])
        g, g1, g2 = c @ n, d1 @ n, d2 @ n
        q = (offset / g)[:, None]
        # P = q·c with q = offset/g: q' = −q·g'/g, q'' = q·(2g'² − g·g'')/g²
        q1 = -q * (g1 / g)[:, None]
        q2 = q * ((2 * g1 * g1 - g * g2) / (g * g))[:, None]
        return q * c, q1 * c + q * d1, q2 * c + 2 * q1 * d1 + q * d2

    return section


def cone_sections_pair() -> Pair:
    """Two non-parallel plane cuts of the cone over the inflected directrix; B warped."""
    a = _section_curve(_cone_section((0.05, 0.1, 1.0), 1.0), warped=False)
    b = _section_curve(_cone_section((-0.08, 0.12, 1.0), 2.2), warped=True)
    return Pair(a, b, lambda s: unwarp(np.asarray(s, float)), _size(a, b))


PAIRS["cylinder_sections"] = cylinder_sections_pair
PAIRS["cone_sections"] = cone_sections_pair


# -- a pair with a stretch that admits no developable -----------------------------------------
#
# Curve A is the low cut of the cylinder pair above, except that over s in [0.4, 0.6] it is
# the straight chord between A(0.4) and A(0.6) (blended in smoothly over [0.3, 0.4] and
# [0.6, 0.7]). From a straight piece of A a torsal ruling can only reach a point of B where
# B's angle about that line is stationary; B winds round the chord monotonically, so the
# chord's stations have no torsal partner at all.

CHORD = (0.4, 0.6)
BLEND = 0.1


def _smoothstep(x: Array) -> tuple[Array, Array, Array]:
    """The quintic ramp 0 → 1 on [0, 1] (C² at both ends) and its first two derivatives."""
    x = np.clip(x, 0.0, 1.0)
    return (
        x**3 * (10 - 15 * x + 6 * x * x),
        30 * x * x * (1 - x) ** 2,
        60 * x * (1 - x) * (1 - 2 * x),
    )


def chorded_pair() -> tuple[ParametricCurve, ParametricCurve]:
    """A (the low cylinder cut with a straight chord in its middle) and B (the high cut)."""
    section = cylinder_sections_pair().a
    b = cylinder_sections_pair().b
    (s0, s1), w = CHORD, BLEND
    p0, p1 = section.point_at(np.array([s0, s1]))

    def parts(x):
        x = np.asarray(x, float)
        c, c1, c2 = section.derivatives(x, 2)
        chord = p0 + ((x - s0) / (s1 - s0))[:, None] * (p1 - p0)
        chord1 = np.broadcast_to((p1 - p0) / (s1 - s0), c.shape)
        up, up1, up2 = _smoothstep((x - (s0 - w)) / w)
        down, down1, down2 = _smoothstep(((s1 + w) - x) / w)
        weight = up * down
        weight1 = (up1 * down - up * down1) / w
        weight2 = (up2 * down - 2 * up1 * down1 + up * down2) / (w * w)
        gap, gap1, gap2 = chord - c, chord1 - c1, -c2
        return (
            c + weight[:, None] * gap,
            c1 + weight1[:, None] * gap + weight[:, None] * gap1,
            c2 + weight2[:, None] * gap + 2 * weight1[:, None] * gap1 + weight[:, None] * gap2,
        )

    a = ParametricCurve(
        lambda x: parts(x)[0], (0.0, 1.0), derivatives=(lambda x: parts(x)[1], lambda x: parts(x)[2])
    )
    return a, b


def folded_cone_pair() -> tuple[ParametricCurve, ParametricCurve]:
    """Two curves on the cone; B's generator angle runs forward, back and forward again
    about τ = 0.5 (a Z fold). The generators meet the fold three times; the oriented
    strip takes the first and the last, so t jumps over the fold's stretch of B, which
    no torsal ruling reaches."""
    k, c, w = 0.35, 0.5, 0.08

    def angle(x):
        g = np.exp(-(((x - c) / w) ** 2))
        q = (x - c) / w**2
        return (
            2.5 * x - 7.5 * k * (x - c) * g,
            2.5 - 7.5 * k * (g - 2 * (x - c) * q * g),
            -7.5 * k * (-2 * q * g - (4 * q - 4 * (x - c) ** 2 * q / w**2) * g),
        )

    a = _curve(cone_surface, _lin(0.0, 2.5), _wave(2.0, 0.3, 7.0), False)
    b = _curve(cone_surface, angle, _wave(4.0, 0.5, 5.0, 1.0), False)
    return a, b

