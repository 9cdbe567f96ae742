"""Green's functions of a surface line source whose strength varies as ``exp(b t)``.

One half-plane, conductivity ``K``, diffusivity ``k``, distortivity ``delta``, whose
material moves through the contact toward ``-x`` at speed ``v`` (``v < 0``: toward
``+x``; ``v = 0``: the stationary half-plane), carries a surface line source
``Q exp(b t)`` at ``x = xi``.  After transients the surface temperature and the
outward thermoelastic displacement are ``exp(b t)`` times the kernels here
(derivation, section "Transient kernels: a perturbation e^{bt}", eqs. T1-T12).

Every kernel is written in contact coordinates, as the steady kernels with a
``scale`` are: ``u = (x - xi)/Delta``, the signed Peclet number of the body
``c = v Delta/(2 k)`` (``c = Pe k2/k1`` for the cylinder, ``0`` for the stationary
half-plane) and the body's own dimensionless rate ``b = b_phys Delta^2 / k``, complex
(``B`` in the derivation, eq. T1).  With the project's rate ``b_hat = b_phys Delta^2/k2``
the stationary half-plane has ``b = b_hat`` and the cylinder ``b = b_hat k2/k1``.

* temperature ``T = Q/(pi K) * exp(-c u) K0(mu |u|)``, ``mu = sqrt(c^2 + b)`` (T3);
* its gradient ``dT/dx = -Q/(pi K Delta) * G(u)`` (T4), Cauchy part ``1/u``;
* displacement ``w = delta Q Delta * W(u)`` and slope ``dw/dx = -delta Q * S(u)``
  (T9, T10), each a quadrature over ``phi`` in ``[0, pi/2]``.

For ``b -> 0`` they tend to the steady kernels of
:mod:`thermocontact.physics.green_functions` (the stationary half-plane's temperature
and displacement up to constants that diverge like ``ln sqrt(b)`` and
``1/sqrt(b)``; derivation eqs. T6, T11).  The elastic (Flamant) part of the contact
problem is quasi-static and does not depend on ``b``.  Real ``b >= 0`` gives real kernels;
complex ``b`` complex ones, with ``K(conj b) = conj K(b)``.  The kernels are the
principal branch, analytic in ``b`` off the cut ``b <= 0``; ``b`` on the negative
real axis is refused, and so is ``b = 0`` for the stationary half-plane
(``c = 0``), whose steady kernels are logarithmic.
"""

from __future__ import annotations

import numpy as np
from scipy.special import kve

from thermocontact.problem.validation import InputError

__all__ = [
    "transient_displacement",
    "transient_displacement_and_slope",
    "transient_slope",
    "transient_temperature",
    "transient_temperature_and_gradient_regular",
    "transient_temperature_gradient",
    "transient_temperature_gradient_regular",
]

#: Gauss-Legendre rule of each panel of the ``phi`` quadrature.
_GL_X, _GL_W = np.polynomial.legendre.leggauss(16)
#: Largest change of the exponent ``|u| s D`` over one panel (the rule is exact to
#: rounding for ``exp`` of a linear function varying by this much: the 16-point rule's
#: error for ``exp(zeta t)`` on ``[-1, 1]``, ``|zeta| = 4``, is below
#: ``2^33 (16!)^4 / (33 (32!)^3) 4^32 e^4 = 3e-24`` of the integral of its modulus).
_PANEL_VARIATION = 8.0
#: The integral is cut where the exponent's real part exceeds its smallest value by
#: this for good: the integrand there is below ``exp(-45)`` of its largest values.
_NEGLIGIBLE = 45.0
#: Points per block (bounds the memory of the ``(points, nodes)`` arrays).
_BLOCK = 4096
#: Points sharing one rule in ``phi`` (sorted by side and ``|u|``: four panels of the
#: stability tables' nodes, ``|u|`` within a factor of 4).
_GROUP = 64
#: Points with ``lam <= _SERIES_REACH``, ``lam = |u| (sqrt|b| + 2|c|)`` (in the wake
#: ``|u| min(sqrt|b| + 2|c|, |b|/|c|)``), take the series in ``|u|``
#: (:func:`_phi_series`): ``|u s D| <= lam`` on the whole interval, so its terms fall like
#: ``lam^k/k!`` and the rounding of their sum is at most ``exp(2 lam) < 3`` times that of
#: the quadrature.
_SERIES_REACH = 0.5
#: Terms of that series: the first left out is below ``0.5^21/21! < 1e-25`` of the
#: integral of ``|integrand|``.
_SERIES_TERMS = 21


def _parameters(c, b):
    """``(c, b)`` checked; ``b`` real (float) when its imaginary part is zero."""
    try:
        c = float(c)
    except (TypeError, ValueError):
        raise InputError(f"c must be a real number, got {c!r}", parameters=("c",)) from None
    try:
        b = complex(b)
    except (TypeError, ValueError):
        raise InputError(f"b must be a complex number off the cut b <= 0 "
                         f"(or 0 with c != 0), got {b!r}", parameters=("b",)) from None
    if not (np.isfinite(c) and np.isfinite(b.real) and np.isfinite(b.imag)):
        raise InputError(f"c and b must be finite, got c={c!r}, b={b!r}", parameters=("c", "b"))
    if b.imag == 0.0:
        b = b.real + 0.0
        if b < 0.0 or (b == 0.0 and c == 0.0):
            raise InputError(f"b must be off the negative real axis, and non-zero for "
                             f"c = 0 (the steady kernels are logarithmic), got {b!r}",
                             parameters=("b",))
    return c, b


def _sqrt(x):
    """Principal square root, real for real non-negative input."""
    return np.sqrt(x) if np.isrealobj(x) else np.sqrt(x.astype(complex))


def _convective_rate(mu, c, b, sg):
    """``D = mu + sgn(u) c``, formed as ``b / (mu + |c|)`` in the wake (eq. T3)."""
    up = sg * c >= 0.0
    return np.where(up, mu + np.abs(c), b / (mu + np.abs(c)))


def transient_temperature(u, c, b):
    """Surface temperature ``exp(-c u) K0(sqrt(c^2 + b) |u|)`` (derivation eq. T3).

    In units of ``Q/(pi K)``: the temperature of the half-plane at ``u`` per unit
    strength of the line source ``Q exp(b t)`` at ``u = 0``.  Logarithmically
    singular at ``u = 0``; for ``c > 0`` the wake is at ``u < 0``.

    Parameters
    ----------
    u : array_like
        ``(x - xi)/Delta``, non-zero.
    c : float
        Signed ``v Delta/(2 k)``; 0 for the stationary half-plane.
    b : complex
        ``b_phys Delta^2/k``, off the cut ``b <= 0`` (``b = 0`` allowed for
        ``c != 0``).

    Returns
    -------
    ndarray
        Real for real ``b``, complex otherwise.
    """
    c, b = _parameters(c, b)
    u = np.asarray(u, dtype=float)
    return _bessel_form(u, c, b, _sqrt(np.asarray(c * c + b)), gradient=False)


def transient_temperature_gradient(u, c, b):
    """Gradient kernel ``G(u) = exp(-c u) [c K0(mu|u|) + mu sgn(u) K1(mu|u|)]`` (eq. T4).

    ``dT/dx = -(Q/(pi K Delta)) G(u)``; ``mu = sqrt(c^2 + b)``.  ``G(u) = 1/u + O(ln|u|)``
    at ``u = 0``.  For ``b = 0``, ``c > 0`` it is ``c M(c u)`` (derivation eq. D10).

    Parameters
    ----------
    u : array_like
        ``(x - xi)/Delta``, non-zero.
    c, b
        As in :func:`transient_temperature`.

    Returns
    -------
    ndarray
    """
    c, b = _parameters(c, b)
    u = np.asarray(u, dtype=float)
    return _bessel_form(u, c, b, _sqrt(np.asarray(c * c + b)))[1]


def _bessel_form(u, c, b, mu, gradient=True):
    """``T(u)`` (eq. T3) and, with ``gradient``, ``G(u)`` (eq. T4) from the scaled
    Bessel functions: ``exp(-c u) K_k(mu|u|) = kve(k, mu|u|) exp(-|u| D)``,
    ``D = mu + sgn(u) c`` (:func:`_convective_rate`)."""
    a, sg = np.abs(u), np.sign(u)
    z = mu * a
    k0 = kve(0, z)
    e = np.exp(-a * _convective_rate(mu, c, b, sg))
    if not gradient:
        return k0 * e
    return k0 * e, e * (c * k0 + mu * sg * kve(1, z))


def transient_temperature_gradient_regular(u, c, b):
    """The Cauchy-free part ``G(u) - 1/u`` of :func:`transient_temperature_gradient`.

    Only logarithmically singular at ``u = 0``.  For ``|mu u| < 1e-2`` it is formed
    from the ascending series of ``K0``, ``K1`` to ``z^4``, ``z^5`` (Abramowitz and
    Stegun 9.6.11, 9.6.13; eq. T5; the neglected terms are below 1e-15 of the
    result), without the cancellation of ``1/u`` against ``mu K1``, which costs about
    ``eps/(z^2 |ln z|)`` beyond (3e-13 relative observed at ``|mu u| = 2e-2``).  For
    ``b = 0``, ``c > 0`` it is ``c M(c u) - 1/u`` (eq. D16).

    Parameters
    ----------
    u : array_like
        ``(x - xi)/Delta``, non-zero.
    c, b
        As in :func:`transient_temperature`.

    Returns
    -------
    ndarray
    """
    return transient_temperature_and_gradient_regular(u, c, b)[1]


def transient_temperature_and_gradient_regular(u, c, b):
    """The pair ``(T(u), G(u) - 1/u)`` of :func:`transient_temperature` and
    :func:`transient_temperature_gradient_regular` (the same arguments) in one pass,
    ``K0`` and ``K1`` formed once (eqs. T3-T5).  For ``|mu u| < 1e-2`` the temperature
    too is ``exp(-c u)`` times the ascending series of ``K0`` (A&S 9.6.13 to ``z^4``:
    the first term left out, ``z^6/2304 (H_3 - ln(z/2) - gamma)``, is at most 3e-15,
    6e-16 of ``K0``), without a modified Bessel function of complex argument at each
    such point."""
    c, b = _parameters(c, b)
    u = np.asarray(u, dtype=float)
    mu = _sqrt(np.asarray(c * c + b))
    z = np.abs(mu * u)
    small = z < 1e-2
    temperature = np.empty(u.shape, dtype=np.result_type(mu, float))
    out = np.empty(u.shape, dtype=np.result_type(mu, float))
    big = ~small
    if np.any(big):
        x = u[big]
        temperature[big], gradient = _bessel_form(x, c, b, mu)
        out[big] = gradient - 1.0 / x
    if np.any(small):
        x = u[small]
        sg = np.sign(x)
        zz = mu * np.abs(x)
        lg = np.log(zz / 2.0) + np.euler_gamma
        z2 = zz * zz
        k0 = -lg + 0.25 * z2 * (1.0 - lg) + z2 * z2 / 64.0 * (1.5 - lg)
        # K1(z) - 1/z
        k1_rest = zz * (0.5 * (lg - 0.5) + z2 / 16.0 * (lg - 1.25)
                        + z2 * z2 / 384.0 * (lg - 5.0 / 3.0))
        e = np.exp(-c * x)
        temperature[small] = e * k0
        # exp(-c x) mu sgn(x) K1 - 1/x = (exp(-c x) - 1)/x + exp(-c x) mu sgn(x) k1_rest
        out[small] = e * c * k0 + np.expm1(-c * x) / x + e * mu * sg * k1_rest
    return temperature, out


def _phi_quadrature(u, c, b, integrand):
    """``(2/pi) integral_0^(pi/2) integrand(s, rho, D, sgn u) exp(-|u| s D) dphi`` per point.

    ``s = sin(phi)``, ``rho = sqrt(b + c^2 s^2)``, ``D = rho + sgn(u) c s`` (formed as
    ``b/(rho + |c| s)`` in the wake, free of cancellation).  The integral is cut
    where the exponent's real part exceeds its smallest value by ``_NEGLIGIBLE``
    for good (the integrand is below ``exp(-45)`` of its largest values beyond),
    and the rest is integrated by composite 16-point Gauss-Legendre on panels
    graded geometrically toward ``phi = 0`` (ratio 2, down to ``1/(2 lam)``,
    ``lam = |u| (|sqrt b| + 2|c|)`` bounding the exponent's rate there, and to a
    quarter of ``sqrt|b|/|c|``, where ``rho`` turns from ``sqrt b`` to ``|c| s``), each cut
    into equal parts over which the exponent changes by at most
    ``_PANEL_VARIATION`` (derivation, "Transient kernels", *Evaluation*).
    """
    u = np.asarray(u, dtype=float)
    shape = u.shape
    u = u.ravel()
    dtype = np.result_type(np.asarray(b), float)
    # An integrand may return several at once (one pass over the panels for all).
    count = getattr(integrand, "count", None)
    out = np.empty((count or 1,) + u.shape, dtype=dtype)
    # The stationary half-plane's points by |u|: a point and its mirror image in one
    # block, where they share their quadrature (_phi_graded).
    order = np.argsort(np.abs(u), kind="stable") if c == 0.0 else None
    for i in range(0, u.size, _BLOCK):
        at = slice(i, i + _BLOCK) if order is None else order[i:i + _BLOCK]
        out[:, at] = _phi_block(u[at], c, b, integrand)
    if count is None:
        return out[0].reshape(shape)
    return tuple(o.reshape(shape) for o in out)


def _phi_block(u, c, b, integrand):
    """The quadrature of :func:`_phi_quadrature` for a block of points: the series in
    ``|u|`` next to the source (:func:`_phi_series`), the graded rule beyond."""
    # A bound of |s D| on the interval: |rho| + |c| <= sqrt|b| + 2|c|, and in the wake
    # (D = b/(rho + |c| s), Re rho >= 0) also |b|/|c|.
    reach = np.full(u.shape, np.sqrt(abs(b)) + 2.0 * abs(c))
    if c != 0.0:
        reach[np.sign(u) * c < 0.0] = min(reach[0], abs(b) / abs(c))
    near = np.abs(u) * reach <= _SERIES_REACH
    if not np.any(near):
        return _phi_graded(u, c, b, integrand)
    out = np.empty((getattr(integrand, "count", None) or 1, u.size),
                   dtype=np.result_type(np.asarray(b), float))
    out[:, near] = _phi_series(u[near], c, b, integrand)
    if not np.all(near):
        out[:, ~near] = _phi_graded(u[~near], c, b, integrand)
    return out


def _phi_series(u, c, b, integrand):
    """``(2/pi) int f exp(-|u| s D) dphi`` as ``sum_k (-|u|)^k/k! m_k``, the moments
    ``m_k = (2/pi) int f (s D)^k dphi`` of each side ``sgn u`` by the graded rule of
    :func:`_phi_rule` at ``u = 0`` (the same panels as its points next to the source:
    toward the scale of ``rho``, a quarter of ``sqrt|b|/|c|``).  The integral over a
    bounded interval of an entire function of ``|u|``: for ``|u s D| <= lam <=``
    :data:`_SERIES_REACH` the terms after :data:`_SERIES_TERMS` are below ``1e-25`` of
    ``int |f|``, and no cancellation beyond a factor ``exp(2 lam)``."""
    a, sg = np.abs(u), np.sign(u)
    count = getattr(integrand, "count", None) or 1
    out = np.empty((count, u.size), dtype=np.result_type(np.asarray(b), float))
    small = 0.5 / _SERIES_REACH
    if c != 0.0 and b != 0.0:
        small = min(small, 0.25 * np.sqrt(abs(b)) / abs(c))
    small = max(small, 1e-15)
    # The terms' factors x^k/k!, x = -|u|, by their running product (one row a term).
    terms = np.empty((_SERIES_TERMS, u.size))
    terms[0] = 1.0
    for k in range(1, _SERIES_TERMS):
        np.multiply(terms[k - 1], -a / k, out=terms[k])
    rule = None
    for side in np.unique(sg):
        at = sg == side
        if rule is None or c != 0.0:
            # The stationary half-plane's rule is that of either side (D = rho).
            w, (s_, rho, d, e) = rule = _phi_rule(np.zeros(1), side, np.array([0.5 * np.pi]),
                                                  np.array([small]), c, b)
            # The powers (s D)^k times the weights.
            powers = np.empty((_SERIES_TERMS, e.size), dtype=e.dtype)
            powers[0] = w
            for k in range(1, _SERIES_TERMS):
                powers[k] = powers[k - 1] * e
        f = integrand(s_, rho, d, side)
        # The moments of each kernel, then the series at every point, by one product each
        # (real: on the moments' real and imaginary parts side by side).
        m = powers @ np.stack([np.broadcast_to(v, e.shape)
                               for v in (f if isinstance(f, tuple) else (f,))], axis=1)
        out[:, at] = _real_product(m, terms[:, at])
    return (2.0 / np.pi) * out


def _real_product(m, terms):
    """``m.T @ terms`` for real ``terms``, ``m`` real or complex, by one real product
    (a complex one would first make ``terms`` complex, many times the cost)."""
    if not np.iscomplexobj(m):
        return m.T @ terms
    k = m.shape[1]
    r = np.concatenate([m.real, m.imag], axis=1).T @ terms
    return r[:k] + 1j * r[k:]


def _phi_graded(u, c, b, integrand):
    a = np.abs(u)[:, None]
    sg = np.sign(u)[:, None]
    sides = None
    if c == 0.0:
        # D = rho on either side: the rule and the exponentials of each |u| serve both
        # sides (the integrand of each on them), each |u| once.
        sides = np.unique(sg)
        at_side = np.searchsorted(sides, sg[:, 0])
        a, at_a = np.unique(a[:, 0], return_inverse=True)
        a = a[:, None]
        sg = np.ones_like(a)
    size = a.shape[0]
    half_pi = 0.5 * np.pi

    def exponent(phi):
        s = np.sin(phi)
        rho = _sqrt(b + (c * s) ** 2)
        with np.errstate(invalid="ignore", divide="ignore"):  # 0/0 only at phi = 0, b = 0
            d = np.where(sg * c >= 0.0, rho + abs(c) * s, b / (rho + abs(c) * s))
        return s, rho, d, np.where(s == 0.0, 0.0, a * s * d)

    # Where the integrand becomes negligible for good: coarse geometric edges, then
    # bisection on the first interval after which Re(exponent) stays above the cut.
    lam = a[:, 0] * (np.sqrt(abs(b)) + 2.0 * abs(c))
    first = np.minimum(half_pi, 0.5 / np.maximum(lam, 1e-300))
    levels = max(1, int(np.ceil(np.log2(half_pi / first.min()))) + 1)
    coarse = np.minimum(half_pi, first[:, None] * 2.0 ** np.arange(levels)[None, :])
    coarse = np.concatenate([np.zeros((size, 1)), coarse, np.full((size, 1), half_pi)], axis=1)
    re = exponent(coarse)[3].real
    cut = np.min(re, axis=1, keepdims=True) + _NEGLIGIBLE
    above = np.flip(np.logical_and.accumulate(np.flip(re >= cut, axis=1), axis=1), axis=1)
    end = np.full(size, half_pi)
    has = above.any(axis=1) & ~above[:, 0]
    if np.any(has):
        k = np.argmax(above[has], axis=1)
        rows = np.flatnonzero(has)
        lo, hi = coarse[rows, k - 1], coarse[rows, k]
        sub_a, sub_sg, sub_cut = a[rows, 0], sg[rows, 0], cut[rows, 0]
        # Both sides at once (each point's own D).
        for _ in range(40):
            mid = 0.5 * (lo + hi)
            s = np.sin(mid)
            over = (sub_a * s * _rho_and_rate(s, c, b, sub_sg)[1]).real >= sub_cut
            hi = np.where(over, mid, hi)
            lo = np.where(over, lo, mid)
        end[rows] = hi
    # Panels graded toward 0 from the end: [0, end 2^-J], ..., [end/2, end], down to
    # the exponent's scale 1/(2 lam) and to rho's transition at s = sqrt|b|/|c|; not
    # below 1e-15, where the omitted part is below 1e-15 of the integral.
    small = 0.5 / np.maximum(lam, 1e-300)
    if c != 0.0 and b != 0.0:
        small = np.minimum(small, 0.25 * np.sqrt(abs(b)) / abs(c))
    small = np.maximum(small, 1e-15)
    total = np.zeros((getattr(integrand, "count", None) or 1,
                      1 if sides is None else sides.size, a.shape[0]),
                     dtype=np.result_type(np.asarray(b), float))
    # Points of one side and similar |u| share the rule in phi: the integrand's
    # factors are formed once per node, the exponential once per point and node.
    order = np.lexsort((a[:, 0], sg[:, 0]))
    cuts = np.flatnonzero(np.diff(sg[order, 0]) != 0) + 1
    for run in np.split(order, cuts):
        for i in range(0, run.size, _GROUP):
            idx = run[i:i + _GROUP]
            total[..., idx] = _phi_group(a[idx, 0], sg[idx[0], 0], end[idx], small[idx],
                                         c, b, integrand, sides)
    total = total[:, 0] if sides is None else total[:, at_side, at_a]
    return (2.0 / np.pi) * total


def _rho_and_rate(s, c, b, side):
    """``rho = sqrt(b + c^2 s^2)`` and ``D = rho + side c s`` at ``s`` of one side, or
    of each point's ``side`` (an array like ``s``) (in the wake ``b/(rho + |c| s)``,
    free of cancellation); for ``c = 0`` both are ``sqrt(b)``, without a square root per
    node."""
    if c == 0.0:
        rho = np.full(np.shape(s), _sqrt(np.asarray(b))[()])
        return rho, rho
    rho = _sqrt(b + (c * s) ** 2)
    up = side * c >= 0.0
    with np.errstate(invalid="ignore", divide="ignore"):  # 0/0 only at phi = 0, b = 0
        if np.ndim(up) == 0:
            return rho, (rho + abs(c) * s if up else b / (rho + abs(c) * s))
        return rho, np.where(up, rho + abs(c) * s, b / (rho + abs(c) * s))


def _phi_rule(a, sg, end, small, c, b):
    """The rule in ``phi`` shared by points ``a = |u|`` of one side ``sg``: from the
    largest end, graded to the smallest scale, each level in parts over which the
    exponent changes by at most ``_PANEL_VARIATION`` for every point whose own end lies
    beyond the level's start (beyond it the integrand is negligible).  Returns the
    weights and ``(s, rho, D, s D)`` at the nodes."""
    def sd(phi):
        s = np.sin(phi)
        rho, d = _rho_and_rate(s, c, b, sg)
        return s, rho, d, np.where(s == 0.0, 0.0, s * d)

    top = float(np.max(end))
    depth = max(1, int(np.ceil(np.log2(max(1.0, top / float(np.min(small))))))) + 1
    edges = np.concatenate([[0.0], top * 2.0 ** np.arange(-depth, 1)])
    step = np.abs(np.diff(sd(edges)[3]))
    live = end[:, None] > edges[None, :-1]
    change = np.max(np.where(live, a[:, None] * step[None, :], 0.0), axis=0)
    parts = np.maximum(1, np.ceil(change / _PANEL_VARIATION).astype(int))
    level = np.repeat(np.arange(parts.size), parts)
    within = np.arange(level.size) - np.repeat(np.cumsum(parts) - parts, parts)
    half = 0.5 * np.diff(edges)[level] / parts[level]
    centre = edges[level] + (2 * within + 1) * half
    phi = (centre[:, None] + half[:, None] * _GL_X).ravel()
    w = (half[:, None] * _GL_W).ravel()
    return w, sd(phi)


def _phi_group(a, sg, end, small, c, b, integrand, sides=None):
    """The integrals of :func:`_phi_block` for points ``a = |u|`` of one side ``sg`` on
    their shared rule (:func:`_phi_rule`), shape ``(kernels, 1, points)``; with
    ``sides`` (``c = 0``, where the rule is that of either side) those of each side,
    ``(kernels, sides, points)``."""
    w, (s, rho, d, e) = _phi_rule(a, sg, end, small, c, b)
    weighted = np.exp(-np.multiply.outer(a, e)) * w
    out = []
    for side in (sg,) if sides is None else sides:
        f = integrand(s, rho, d, side)
        # Each kernel by its own sum (the same rounding alone or with the other; no
        # threaded BLAS for these small products).
        out.append([np.einsum("pn,n->p", weighted, np.broadcast_to(v, e.shape))
                    for v in (f if isinstance(f, tuple) else (f,))])
    return np.array(out).transpose(1, 0, 2)


def transient_displacement(u, c, b):
    """Displacement kernel ``W(u) = (2/pi) int_0^(pi/2) (s/rho) exp(-|u| s D) dphi`` (eq. T9).

    The outward surface displacement is ``w = delta Q Delta W(u)``; ``s = sin phi``,
    ``rho = sqrt(b + c^2 s^2)``, ``D = rho + sgn(u) c s``.  For ``b = 0``,
    ``c > 0`` it is ``E(c u)/c`` (derivation eq. D5); for ``c = 0`` it is
    ``2/(pi sqrt b) - |u|/2 + O(sqrt(b) u^2)`` (eq. T11).

    Parameters
    ----------
    u : array_like
        ``(x - xi)/Delta``.
    c, b
        As in :func:`transient_temperature`.

    Returns
    -------
    ndarray
    """
    c, b = _parameters(c, b)
    return _phi_quadrature(u, c, b, lambda s, rho, d, sg: s / rho)


def transient_displacement_and_slope(u, c, b):
    """``(W(u), S(u))`` of :func:`transient_displacement` and :func:`transient_slope`
    in one pass of their common quadrature (eqs. T9, T10)."""
    c, b = _parameters(c, b)

    def integrand(s, rho, d, sg):
        return s / rho, s * s * np.where(sg == 0.0, c * s / rho, sg * d / rho)
    integrand.count = 2
    return _phi_quadrature(u, c, b, integrand)


def transient_slope(u, c, b):
    """Slope kernel ``S(u) = (2/pi) sgn(u) int_0^(pi/2) s^2 (D/rho) exp(-|u| s D) dphi`` (eq. T10).

    The outward slope is ``dw/dx = -delta Q S(u)``; ``S`` jumps by 1 at ``u = 0``,
    where it takes its mean value ``(2/pi) int s^3 c/rho dphi``.  For ``b = 0``,
    ``c != 0`` it is ``sgn(c) N(c u) H(c u)`` (derivation eq. D7,
    :func:`~thermocontact.physics.green_functions.moving_slope`); for ``c = 0`` it
    tends to ``sgn(u)/2`` (eq. D4) as ``b -> 0``.

    Parameters
    ----------
    u : array_like
        ``(x - xi)/Delta``.
    c, b
        As in :func:`transient_temperature`.

    Returns
    -------
    ndarray
    """
    c, b = _parameters(c, b)

    def integrand(s, rho, d, sg):
        # sgn(u) D/rho = c s/rho + sgn(u); at u = 0 the mean of both sides, c s/rho.
        return s * s * np.where(sg == 0.0, c * s / rho, sg * d / rho)

    return _phi_quadrature(u, c, b, integrand)
