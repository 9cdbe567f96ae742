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
#: (Rate, point) pairs per block (bounds the memory of the ``(points, levels)`` arrays
#: of the ends' search: some 30 MB).
_BLOCK = 2**15
#: Points sharing one rule in ``phi`` (of one rate, sorted by side and ``|u|``: four
#: panels of the stability tables' nodes, ``|u|`` within a factor of 4).
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
    ``b/(rho + |c| s)`` in the wake, free of cancellation).  ``b`` is one rate, or a
    1-D array of rates (their values on a leading axis): all the rates' points in one
    pass, each rate with its own rules.  Next to the source the series in ``|u|``
    (:func:`_phi_series`); beyond it the integral is cut where the exponent's real part
    exceeds its smallest value by ``_NEGLIGIBLE`` for good (the integrand is below
    ``exp(-45)`` of its largest values beyond), and the rest is integrated by composite
    16-point Gauss-Legendre on panels graded geometrically toward ``phi = 0`` (ratio 2,
    down to ``1/(2 lam)``, ``lam = |u| (|sqrt b| + 2|c|)`` bounding the exponent's rate
    there, and to a quarter of ``sqrt|b|/|c|``, where ``rho`` turns from ``sqrt b`` to
    ``|c| s``), each cut into equal parts over which the exponent changes by at most
    ``_PANEL_VARIATION`` (:func:`_phi_graded`; derivation, "Transient kernels",
    *Evaluation*).
    """
    u = np.asarray(u, dtype=float)
    rates = np.atleast_1d(b)
    count = getattr(integrand, "count", None)
    out = np.empty(((count or 1), rates.size, u.size), dtype=np.result_type(rates, float))
    flat = u.ravel()
    # Blocks of whole rates, or of one rate's points (the stationary half-plane's by
    # |u|: a point and its mirror image in one block, where they share their quadrature).
    order = np.argsort(np.abs(flat), kind="stable") if c == 0.0 else np.arange(flat.size)
    per = max(1, _BLOCK // max(1, flat.size))
    for r in range(0, rates.size, per):
        for i in range(0, flat.size, _BLOCK):
            at = order[i:i + _BLOCK]
            part = _phi_points(flat[at], np.arange(r, min(r + per, rates.size)), rates, c,
                               integrand)
            out.reshape(out.shape[:2] + (-1,))[:, r:r + per, at] = part
    out = out.reshape(out.shape[:2] + u.shape)
    if np.ndim(b) == 0:
        out = out[:, 0]
    return out[0] if count is None else tuple(out)


def _phi_points(u, which, rates, c, integrand):
    """The integrals of :func:`_phi_quadrature` at points ``u`` for the rates
    ``rates[which]``, shape ``(kernels, len(which), len(u))``: the series in ``|u|``
    next to the source (:func:`_phi_series`), the graded rule beyond
    (:func:`_phi_graded`)."""
    # Every (rate, point) pair, the rate's index with it.
    rate = np.repeat(which, u.size)
    a, sg = np.tile(np.abs(u), which.size), np.tile(np.sign(u), which.size)
    # A bound of |s D| on the interval: |rho| + |c| <= sqrt|b| + 2|c|, and in the wake
    # (D = b/(rho + |c| s), Re rho >= 0) also |b|/|c|.
    modulus = np.abs(rates)[rate]
    reach = np.sqrt(modulus) + 2.0 * abs(c)
    if c != 0.0:
        wake = sg * c < 0.0
        reach[wake] = np.minimum(reach[wake], modulus[wake] / abs(c))
    near = a * reach <= _SERIES_REACH
    out = np.empty((getattr(integrand, "count", None) or 1, a.size),
                   dtype=np.result_type(rates, float))
    for part, method in ((near, _phi_series), (~near, _phi_graded)):
        if np.any(part):
            out[:, part] = method(a[part], sg[part], rate[part], rates, c, integrand)
    return out.reshape(out.shape[0], which.size, u.size)


def _ragged(counts):
    """For consecutive runs of ``counts`` items: each item's run and its place in it."""
    run = np.repeat(np.arange(counts.size), counts)
    return run, np.arange(run.size) - _starts(counts)[run]


def _starts(counts):
    """The first index of each of consecutive runs of ``counts`` items."""
    return np.cumsum(counts) - counts


def _integrand_rows(integrand, s, rho, d, side):
    """The integrand's kernels at the nodes, shape ``(kernels, nodes)``."""
    f = integrand(s, rho, d, side)
    return np.stack([np.broadcast_to(v, s.shape) for v in (f if isinstance(f, tuple) else (f,))])


def _phi_series(a, sg, rate, rates, c, integrand):
    """``(2/pi) int f exp(-|u| s D) dphi`` as ``sum_k (-|u|)^k/k! m_k``, the moments
    ``m_k = (2/pi) int f (s D)^k dphi`` of each rate and side ``sgn u`` by the graded rule
    of :func:`_phi_rules` at ``u = 0`` (the same panels as its points next to the source:
    toward the scale of ``rho``, a quarter of ``sqrt|b|/|c|``).  The integral over a
    bounded interval of an entire function of ``|u|``: for ``|u s D| <= lam <=``
    :data:`_SERIES_REACH` the terms after :data:`_SERIES_TERMS` are below ``1e-25`` of
    ``int |f|``, and no cancellation beyond a factor ``exp(2 lam)``."""
    # One rule per (rate, side).
    key = rate * 3 + (sg + 1).astype(int)
    pairs, at = np.unique(key, return_inverse=True)
    b, side = rates[pairs // 3], (pairs % 3 - 1).astype(float)
    small = np.full(pairs.size, 0.5 / _SERIES_REACH)
    if c != 0.0:
        small = np.where(b != 0.0, np.minimum(small, 0.25 * np.sqrt(np.abs(b)) / abs(c)),
                         small)
    small = np.maximum(small, 1e-15)
    nodes, w, (s, rho, d, e) = _phi_rules(np.zeros(pairs.size), np.arange(pairs.size),
                                          np.full(pairs.size, 0.5 * np.pi), small, b, side, c)
    f = _integrand_rows(integrand, s, rho, d, side[nodes])
    starts = _starts(np.bincount(nodes, minlength=pairs.size))
    # The moments of each rule and kernel, shape (rules, terms, kernels), and the terms'
    # factors x^k/k!, x = -|u|, by their running products.
    moments = np.empty((pairs.size, _SERIES_TERMS, f.shape[0]), dtype=np.result_type(e, f))
    terms = np.empty((_SERIES_TERMS, a.size))
    weighted, terms[0] = w * f, 1.0
    for k in range(_SERIES_TERMS):
        moments[:, k] = np.add.reduceat(weighted, starts, axis=1).T
        if k + 1 < _SERIES_TERMS:
            weighted = weighted * e
            np.multiply(terms[k], -a / (k + 1), out=terms[k + 1])
    # The series at each rule's points by one real product.
    out = np.empty((f.shape[0], a.size), dtype=moments.dtype)
    order = np.argsort(at, kind="stable")
    bounds = np.append(_starts(np.bincount(at, minlength=pairs.size)), a.size)
    for r in range(pairs.size):
        these = order[bounds[r]:bounds[r + 1]]
        out[:, these] = _real_product(moments[r], terms[:, these])
    return (2.0 / np.pi) * out


def _real_product(m, terms):
    """``m.T @ terms`` for real ``terms``, ``m`` real or complex, by one real product
    (a complex one would first make ``terms`` complex, many times the cost)."""
    if not np.iscomplexobj(m):
        return m.T @ terms
    k = m.shape[1]
    r = np.concatenate([m.real, m.imag], axis=1).T @ terms
    return r[:k] + 1j * r[k:]


def _rho_and_rate(s, c, b, side):
    """``rho = sqrt(b + c^2 s^2)`` and ``D = rho + side c s`` at ``s`` (``b`` and
    ``side`` scalars or arrays like ``s``; in the wake ``b/(rho + |c| s)``, free of
    cancellation); for ``c = 0`` both are ``sqrt(b)``."""
    if c == 0.0:
        rho = np.broadcast_to(_sqrt(np.asarray(b)), np.broadcast(s, b).shape)
        return rho, rho
    rho = _sqrt(b + (c * s) ** 2)
    with np.errstate(invalid="ignore", divide="ignore"):  # 0/0 only at phi = 0, b = 0
        return rho, np.where(side * c >= 0.0, rho + abs(c) * s, b / (rho + abs(c) * s))


def _sd(phi, c, b, side):
    """``(s, rho, D, s D)`` at ``phi`` (:func:`_rho_and_rate`), ``s D = 0`` at ``phi = 0``."""
    s = np.sin(phi)
    rho, d = _rho_and_rate(s, c, b, side)
    return s, rho, d, np.where(s == 0.0, 0.0, s * d)


def _phi_graded(a, sg, rate, rates, c, integrand):
    """The graded quadrature of :func:`_phi_quadrature` at points ``a = |u|`` of sides
    ``sg``, rates ``rates[rate]``: where each point's integrand becomes negligible for
    good, then the points of one rate and side and similar ``|u|`` (sorted, in runs of
    :data:`_GROUP`) on a shared rule (:func:`_phi_rules`): the ends and the rules of
    every point and rate at once, then each group's exponentials and sums (the work
    that grows with the rule)."""
    sides = None
    if c == 0.0:
        # D = rho on either side: the rule and the exponentials of each (rate, |u|) serve
        # both sides (the integrand of each on them), each (rate, |u|) once.
        sides = np.unique(sg)
        at_side = np.searchsorted(sides, sg)
        order = np.lexsort((a, rate))
        new = np.ones(a.size, dtype=bool)
        new[1:] = (np.diff(a[order]) != 0.0) | (np.diff(rate[order]) != 0)
        at_a = np.empty(a.size, dtype=int)
        at_a[order] = np.cumsum(new) - 1
        a, rate = a[order][new], rate[order][new]
        sg = np.ones_like(a)
    b = rates[rate]
    size = a.size
    half_pi = 0.5 * np.pi
    # Where the integrand becomes negligible for good: coarse geometric edges, then
    # bisection on the first interval after which Re(exponent) stays above the cut.
    lam = a * (np.sqrt(np.abs(b)) + 2.0 * abs(c))
    first = np.minimum(half_pi, 0.5 / np.maximum(lam, 1e-300))
    levels = max(1, int(np.ceil(np.log2(half_pi / first.min()))) + 1)
    coarse = np.minimum(half_pi, first[:, None] * 2.0 ** np.arange(levels)[None, :])
    coarse = np.concatenate([np.zeros((size, 1)), coarse, np.full((size, 1), half_pi)], axis=1)
    sc = np.sin(coarse)
    d = _rho_and_rate(sc, c, b[:, None], sg[:, None])[1]
    re = np.where(sc == 0.0, 0.0, a[:, None] * sc * d).real
    cut = np.min(re, axis=1, keepdims=True) + _NEGLIGIBLE
    above = np.flip(np.logical_and.accumulate(np.flip(re >= cut, axis=1), axis=1), axis=1)
    end = np.full(size, half_pi)
    has = above.any(axis=1) & ~above[:, 0]
    if np.any(has):
        k = np.argmax(above[has], axis=1)
        rows = np.flatnonzero(has)
        lo, hi = coarse[rows, k - 1], coarse[rows, k]
        sub_a, sub_sg, sub_cut, sub_b = a[rows], sg[rows], cut[rows, 0], b[rows]
        # Both sides at once (each point's own D).
        for _ in range(40):
            mid = 0.5 * (lo + hi)
            s = np.sin(mid)
            over = (sub_a * s * _rho_and_rate(s, c, sub_b, sub_sg)[1]).real >= sub_cut
            hi = np.where(over, mid, hi)
            lo = np.where(over, lo, mid)
        end[rows] = hi
    # Panels graded toward 0 from the end: [0, end 2^-J], ..., [end/2, end], down to
    # the exponent's scale 1/(2 lam) and to rho's transition at s = sqrt|b|/|c|; not
    # below 1e-15, where the omitted part is below 1e-15 of the integral.
    small = 0.5 / np.maximum(lam, 1e-300)
    if c != 0.0:
        small = np.where(b != 0.0, np.minimum(small, 0.25 * np.sqrt(np.abs(b)) / abs(c)),
                         small)
    small = np.maximum(small, 1e-15)
    # Points of one rate and side and similar |u| share the rule in phi: the integrand's
    # factors are formed once per node, the exponential once per point and node.
    order = np.lexsort((a, sg, rate))
    runs = np.flatnonzero((np.diff(sg[order]) != 0) | (np.diff(rate[order]) != 0)) + 1
    lengths = np.diff(np.concatenate([[0], runs, [size]]))
    group = np.cumsum(_ragged(lengths)[1] % _GROUP == 0) - 1
    groups = group[-1] + 1
    a, sg, end, small, rate = a[order], sg[order], end[order], small[order], rate[order]
    first_point = _starts(np.bincount(group, minlength=groups))
    nodes, w, (s, rho, d, e) = _phi_rules(a, group, end, small, rates[rate[first_point]],
                                          sg[first_point], c)
    fs = [_integrand_rows(integrand, s, rho, d, side)
          for side in ((sg[first_point][nodes],) if sides is None else sides)]
    total = np.empty((fs[0].shape[0], len(fs), size), dtype=np.result_type(e, fs[0], float))
    # Each group's points on its nodes (each kernel by its own sum: the same rounding
    # alone or with the other; no threaded BLAS for these small products).
    point_start = np.append(first_point, size)
    node_start = np.append(_starts(np.bincount(nodes, minlength=groups)), nodes.size)
    for g in range(groups):
        p, n = slice(point_start[g], point_start[g + 1]), slice(node_start[g], node_start[g + 1])
        weighted = np.exp(-np.multiply.outer(a[p], e[n])) * w[n]
        for i, f in enumerate(fs):
            for k, v in enumerate(f):
                total[k, i, p] = np.einsum("pn,n->p", weighted, v[n])
    # Back to the points' order (and for c = 0 each point's side).
    out = np.empty_like(total)
    out[..., order] = total
    out = out[:, 0] if sides is None else out[:, at_side, at_a]
    return (2.0 / np.pi) * out


def _phi_rules(a, group, end, small, b, sg, c):
    """The rules in ``phi`` of groups of points ``a = |u|`` (``group`` the group of each,
    ascending), each group of one rate ``b`` and side ``sg`` (per group): from the
    group's largest end, graded to its smallest scale, each level in parts over which
    the exponent changes by at most ``_PANEL_VARIATION`` for every point of the group
    whose own end lies beyond the level's start (beyond it the integrand is
    negligible).  Returns each node's group, the weights and ``(s, rho, D, s D)`` at
    the nodes, the groups' nodes consecutive."""
    groups = b.size
    count = np.bincount(group, minlength=groups)
    first = _starts(count)
    top = np.maximum.reduceat(end, first)
    bottom = np.minimum.reduceat(small, first)
    depth = np.maximum(1, np.ceil(np.log2(np.maximum(1.0, top / bottom))).astype(int)) + 1
    # Each group's levels [0, top 2^-depth], [top 2^-depth, top 2^(1-depth)], ...,
    # [top/2, top].
    level_group, level = _ragged(depth + 1)
    top_l, depth_l = top[level_group], depth[level_group]
    lo = np.where(level == 0, 0.0, top_l * 2.0 ** (level - 1 - depth_l))
    hi = top_l * 2.0 ** (level - depth_l)
    b_l, sg_l = b[level_group], sg[level_group]
    step = np.abs(_sd(hi, c, b_l, sg_l)[3] - _sd(lo, c, b_l, sg_l)[3])
    # The largest change over each level of its group's live points (level by level,
    # each group's points in a run).
    pair_level, place = _ragged(count[level_group])
    point = first[level_group][pair_level] + place
    change = np.where(end[point] > lo[pair_level], a[point] * step[pair_level], 0.0)
    change = np.maximum.reduceat(change, _starts(count[level_group]))
    parts = np.maximum(1, np.ceil(change / _PANEL_VARIATION).astype(int))
    panel_level, within = _ragged(parts)
    half = 0.5 * (hi - lo)[panel_level] / parts[panel_level]
    centre = lo[panel_level] + (2 * within + 1) * half
    phi = (centre[:, None] + half[:, None] * _GL_X).ravel()
    w = (half[:, None] * _GL_W).ravel()
    node_group = np.repeat(level_group[panel_level], _GL_X.size)
    return node_group, w, _sd(phi, c, b[node_group], sg[node_group])


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
    in one pass of their common quadrature (eqs. T9, T10).

    Parameters
    ----------
    u : array_like
        ``(x - xi)/Delta``.
    c : float
        As in :func:`transient_temperature`.
    b : complex or sequence of complex
        As in :func:`transient_temperature`; a sequence of rates gives each rate's
        kernels on a leading axis, all evaluated in one pass (each rate on its own
        rules: the values those of the rates one at a time).

    Returns
    -------
    tuple of ndarray
        ``W`` and ``S``, each shaped like ``u`` (``(len(b),) + u.shape`` for a
        sequence); complex where any rate is.
    """
    if np.ndim(b) == 0:
        c, b = _parameters(c, b)
    else:
        checked = [_parameters(c, rate) for rate in b]
        c = checked[0][0] if checked else float(c)
        b = np.array([rate for _, rate in checked])
        if b.size == 0:
            raise InputError("b must hold at least one rate", parameters=("b",))

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
