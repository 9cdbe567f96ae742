"""The operators of the contact equation (D14) and the heat equation (D18), once.

Every discretisation method builds its blocks here; the methods differ only in
how a :class:`~.representations.Representation` integrates a kernel and at which
points (or by which projections) the equations are enforced.  Nothing here
depends on ``F = fHPe``, ``lam`` or ``sigma``.
"""

from __future__ import annotations

import numpy as np

from ..physics.green_functions import (cylinder_displacement_drop, cylinder_slope,
                                       cylinder_temperature, cylinder_temperature_gradient_regular,
                                       moving_slope)
from ..problem.parameters import Parameters

__all__ = ["contact_operators", "distortion_operators", "heat_operators", "outside_operators",
           "temperature_kernels", "temperature_operators"]


def distortion_operators(par: Parameters, rep, s, aux=None):
    """Each body's thermal-distortion term of (D14) at points ``s``, on ``(phi, psi)``.

    The cylinder's ``d integral N(c u) H(u) (p + q) dr`` and the half-plane's
    ``integral S2(u) (p - q) dr`` (``p + q`` and ``p - q`` are twice the heat each
    receives), with ``q = q' + eta p``; ``S2 = sgn(u)/2`` for the stationary
    half-plane and ``sgn(c2) N(c2 u) H(c2 u)`` for one moving through the contact
    (``c2 = R Pe != 0``, derivation section 5b).  Their sum times ``F`` is the
    thermal part of the contact equation.

    Returns
    -------
    cylinder, half_plane : pair of ndarray, shape (k, n)
        Each ``(on phi, on psi)``.
    """
    eta = par.eta
    c = par.cylinder_scale
    d = par.delta1_over_delta2
    c2 = par.half_plane_scale
    if c2:
        s2_b, s2_s = rep.integrate(lambda u: moving_slope(u, c2), s, scale=abs(c2), aux=aux)
    else:
        sg_b, sg_s = rep.sign(s, aux)
        s2_b, s2_s = 0.5 * sg_b, 0.5 * sg_s
    half_plane = ((1.0 - eta) * s2_b, -s2_s)
    if d:
        nh_b, nh_s = rep.integrate(lambda u: cylinder_slope(c * u), s, scale=c, aux=aux)
        cylinder = (d * (1.0 + eta) * nh_b, d * nh_s)
    else:
        cylinder = (np.zeros_like(s2_b), np.zeros_like(s2_s))
    return cylinder, half_plane


def contact_operators(par: Parameters, rep, s, aux=None, *, own=True):
    """Operators of the contact equation (D14) at points ``s``.

    ``(C - F Tp) phi - F Tq psi = (2/pi) (L sigma + L s)`` with

    * ``C = (1/pi) PV integral p(r)/(s - r) dr`` on ``phi``;
    * ``Tp``, ``Tq``: the thermal distortion, ``F`` times
      ``integral K_p(s - r) p(r) dr + integral K_q(s - r) q(r) dr`` with
      ``K_p = d N(c u) H(u) + sgn(u)/2`` and ``K_q = d N(c u) H(u) - sgn(u)/2``;
      with ``q = q' + eta p``:
      ``Tp = d (1 + eta) NH_p + (1 - eta) sgn_p / 2`` and ``Tq = d NH_q - sgn_q / 2``,
      where ``d = delta1/delta2`` and ``c = Pe k2/k1``.  ``C`` also carries the
    Dundurs term ``-b p(s)``, ``b = (B/2) sgn(v1 - v2)`` (D14d).  A half-plane moving
      through the contact (``c2 = R Pe != 0``, derivation section 5b) replaces
      ``sgn(u)/2`` by ``sgn(c2) N(c2 u) H(c2 u)``.

    Parameters
    ----------
    par : Parameters
        Only ``pe``, the ratios and ``eta`` are used.
    rep : Representation
    s : ndarray, shape (k,)
    aux : ndarray, optional
        The representation's own coordinate of the points (``tau``).
    own : bool, optional
        Whether the points lie in this contact (default): the Dundurs term is
        local, so it is left out for points of another zone.

    Returns
    -------
    C, Tp : ndarray, shape (k, n)
        On ``phi``.
    Tq : ndarray, shape (k, n)
        On ``psi``.
    """
    cb, _ = rep.cauchy(s, aux)
    (cyl_b, cyl_s), (hp_b, hp_s) = distortion_operators(par, rep, s, aux)
    C = cb / np.pi
    b = par.free_term
    if b and own:
        # The Dundurs term -b p(s) (D14d): with it, the operator on phi is of the
        # second kind, and the representation carries the edge exponents it makes.
        C = C - b * rep.pressure_rows(s, aux)
    Tp = cyl_b + hp_b
    Tq = cyl_s + hp_s
    return C, Tp, Tq


def heat_operators(par: Parameters, rep, s, aux=None):
    """Operators of the heat equation (D18), divided by ``pi (1 + rho)``, at points ``s``.

    ``Hp phi + Hq psi = 0`` with
    ``Hq = (PV integral q'/(s - r) + rho/(1 + rho) integral q' M_c) / pi`` and
    ``Hp = 2 rho/(1 + rho)^2 integral p M_c / pi``, where
    ``M_c(u) = c M(c u) - 1/u`` is the regular part of the cylinder's temperature
    gradient (a logarithm at ``u = 0``) and ``rho = K2/K1``.  A half-plane moving
    through the contact (``c2 = R Pe != 0``) adds its own regular part ``M_c2``:
    ``rho M_c`` becomes ``rho M_c + M_c2`` on ``q'`` and ``M_c`` becomes
    ``M_c - M_c2`` on ``p`` (derivation eq. D18b).

    Returns
    -------
    Hp, Hq : ndarray, shape (k, n)
    """
    rho = par.K2_over_K1
    c = par.cylinder_scale
    _, cs = rep.cauchy(s, aux)
    mr_b, mr_s = rep.integrate(lambda u: cylinder_temperature_gradient_regular(u, c), s,
                               scale=c, logarithmic=True, aux=aux)
    Hq = (cs + (rho / (1.0 + rho)) * mr_s) / np.pi
    c2 = par.half_plane_scale
    if c2:
        m2_b, m2_s = rep.integrate(lambda u: cylinder_temperature_gradient_regular(u, c2), s,
                                   scale=abs(c2), logarithmic=True, aux=aux)
        Hq = Hq + m2_s / ((1.0 + rho) * np.pi)
        mr_b = mr_b - m2_b
    # 2 rho/(1 + rho)^2 written so that no power overflows for extreme ratios.
    Hp = (2.0 / ((1.0 + rho) * (1.0 + 1.0 / rho))) * mr_b / np.pi
    return Hp, Hq


def outside_operators(par: Parameters, rep, side: float, tt):
    """The left sides of (D14) and (D18) integrated from an edge outward.

    ``I(tt) = integral from e to e + side tt`` of each left side over ``s``, for the
    edge ``e = side`` (``+1`` leading, ``-1`` trailing) and distances ``tt >= 0``
    past it: the gap's slope mismatch (D20-D21) and the temperature difference's
    change, both from the undifferentiated Green's functions (derivation section
    14).  The Cauchy kernels integrate to ``ln|(s - r)/(e - r)|``, the cylinder's
    slope kernel to ``[E(c(e - r)) - E(c(s - r))]/c`` (D5), the stationary
    half-plane's ``sgn(u)/2`` to ``tt/2`` on either side, and the regular part of
    the cylinder's temperature gradient ``c M(c u) - 1/u`` to
    ``-[exp(-c u) K0(c|u|) + ln|u|]`` (D8-D10).  A half-plane moving through the
    contact (``c2 = R Pe != 0``) replaces ``sgn(u)/2`` by its slope kernel, whose
    integral is the cylinder's drop with ``|c2|`` at the distance ``|e - r|`` on the
    side where ``c2 u > 0`` (the right for ``c2 > 0``, the left for ``c2 < 0``) and
    zero on the other, and
    adds its regular gradient part ``M_c2``, integrated as the cylinder's (D32b).
    Every kernel is a function of the distance ``e - r`` to the edge, formed without
    cancellation.

    Parameters
    ----------
    par : Parameters
    rep : Representation
        One that integrates kernels of the distance to an edge (``from_edge``).
    side : {-1.0, 1.0}
    tt : array_like, shape (k,)

    Returns
    -------
    C, Tp, Tq : ndarray, shape (k, n)
        ``I`` of the contact equation's left side is ``(C - F Tp) phi - F Tq psi``.
    Hp, Hq : ndarray, shape (k, n)
        ``I`` of the heat equation's (D18) is ``Hp phi + Hq psi``.
    """
    tt = np.atleast_1d(np.asarray(tt, dtype=float))
    points = side * (1.0 + tt)
    col = tt[:, None]
    eta, rho, c, d = par.eta, par.K2_over_K1, par.cylinder_scale, par.delta1_over_delta2

    def edge_integral(name, kernel, scale=1.0):
        # The kernels depend on tt row by row: cached by the points and the scale.
        return rep.rows(("outside " + name, side, scale, points.tobytes()),
                        lambda: rep.integrate(kernel, points, scale=scale, from_edge=True))

    # ln|(s - r)/(e - r)| with e - r = e_r (the argument): log1p(side tt / e_r).
    lb, lq = edge_integral("log", lambda e: np.log1p(side * col / e))
    C = lb / np.pi
    c2 = par.half_plane_scale
    if not c2:
        half = 0.5 * tt[:, None]
        Tp = (1.0 - eta) * half * rep.pressure_rule.weights[None, :]
        Tq = -half * rep.flux_rule.weights[None, :]
    elif c2 * side > 0.0:
        # The moving half-plane's slope kernel lives where c2 u > 0: the cylinder's
        # drop with |c2| at the distance |e - r| (section 16).
        a2 = abs(c2)
        hb, hq = edge_integral(f"drop2 {c2!r}", lambda e: cylinder_displacement_drop(
            a2 * side * e, a2 * col), a2)
        Tp, Tq = (1.0 - eta) * hb / a2, -hq / a2
    else:
        Tp = np.zeros((tt.size, rep.n))
        Tq = np.zeros((tt.size, rep.n))
    if d and side > 0.0:
        # Only downstream of the cylinder's material, which enters at s = +1.
        db, dq = edge_integral("drop", lambda e: cylinder_displacement_drop(c * e, c * col), c)
        Tp = Tp + d * (1.0 + eta) * db / c
        Tq = Tq + d * dq / c

    def temperature_change(e, c=c):
        # -[T(c(e + side tt)) + ln|e + side tt|] + [T(c e) + ln|e|], T = exp(-u) K0(|u|).
        far = e + side * col
        return (cylinder_temperature(c * e) - cylinder_temperature(c * far)
                - np.log1p(side * col / e))
    mb, mq = edge_integral("temperature", temperature_change, c)
    Hq = (lq + (rho / (1.0 + rho)) * mq) / np.pi
    if c2:
        # (D18b): the half-plane's regular part on q' and, subtracted, on p.
        m2b, m2q = edge_integral(f"temperature2 {c2!r}",
                                 lambda e: temperature_change(e, c2), abs(c2))
        Hq = Hq + m2q / ((1.0 + rho) * np.pi)
        mb = mb - m2b
    Hp = (2.0 / ((1.0 + rho) * (1.0 + 1.0 / rho))) * mb / np.pi
    return C, Tp, Tq, Hp, Hq


def temperature_operators(par: Parameters, rep, s, aux=None):
    """The surface temperature difference ``T1 - T2`` at points ``s`` (D33).

    ``pi K2 (T1 - T2)/(f v P)`` up to a constant is
    ``rho integral q1 T(c u) dr + integral q2 ln|u| dr`` with ``T(u) = exp(-u) K0(|u|)``
    (D8) and the stationary half-plane's logarithm (D12), ``u = s - r``, in units of
    the contact's half-width (a length unit ``Delta`` adds ``ln(Delta)`` times the heat
    into the half-plane); ``q1 = ((1 + eta) p + q')/2``, ``q2 = ((1 - eta) p - q')/2``.
    The undifferentiated form of the heat equation, for contact with an interface
    conductance (derivation section 15).  A half-plane moving through the contact
    (``c2 = R Pe != 0``, section 5b) has Carslaw and Jaeger's temperature with its own
    signed argument: ``ln|u|`` becomes ``-T(c2 u)`` (D33b), scale-free, so that a
    length unit adds no logarithm.

    Returns
    -------
    Up, Uq : ndarray, shape (k, n)
        On ``phi`` and ``psi``.
    """
    rho, eta = par.K2_over_K1, par.eta
    (tb, tq), (hb, hq) = temperature_kernels(par, rep, s, aux)
    # ln|u| of a stationary half-plane; -T(c2 u) of a moving one (D33b).
    lb, lq = (-hb, -hq) if par.half_plane_scale else (hb, hq)
    Up = 0.5 * rho * (1.0 + eta) * tb + 0.5 * (1.0 - eta) * lb
    Uq = 0.5 * rho * tq - 0.5 * lq
    return Up, Uq


def temperature_kernels(par: Parameters, rep, s, aux=None, half_plane=True):
    """Each body's surface temperature kernel integrated against ``(p, q')`` at ``s``.

    The cylinder's ``T(c u) = exp(-c u) K0(c |u|)`` (D8); the half-plane's ``ln|u|``
    when stationary (D12), or ``T(c2 u)`` with its own signed scale ``c2 = R Pe`` when
    moving through the contact (section 5b); ``u = s - r`` in units of the contact's
    half-width.  Each body's rise over its incoming temperature is, in units of
    ``f |v1 - v2| P/(pi K_i)``, ``(1/2)((1 + eta) Tb phi + Tq psi)`` for the cylinder,
    ``(1/2)((1 - eta) Hb phi - Hq psi)`` for a moving half-plane and minus that for a
    stationary one (up to its free level).  The one quadrature of these kernels: of
    the temperature equation (D33) and of the surfaces' temperatures alike.

    ``half_plane=False`` leaves the half-plane's out (None): where only the cylinder's
    temperature is wanted.  A stationary half-plane's ``ln|u|`` does not depend on
    ``Pe``; the representation keeps it per set of points
    (:meth:`~.representations.Representation.logarithm`).

    Returns
    -------
    cylinder, half_plane : pair of ndarray, shape (k, n)
        Each ``(on phi, on psi)``.
    """
    c, c2 = par.cylinder_scale, par.half_plane_scale
    cylinder = rep.integrate(lambda u: cylinder_temperature(c * u), s, scale=c,
                             logarithmic=True, aux=aux)
    if not half_plane:
        return cylinder, None
    if c2:
        return cylinder, rep.integrate(lambda u: cylinder_temperature(c2 * u), s,
                                       scale=abs(c2), logarithmic=True, aux=aux)
    return cylinder, rep.logarithm(s, aux)
