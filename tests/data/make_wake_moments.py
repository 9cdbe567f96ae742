"""Moments of a moving body's transient temperature kernel across its wake, computed once
by adaptive quadrature in ``tau`` and stored.

Run ``python tests/data/make_wake_moments.py`` to regenerate
``tests/data/wake_moments.json`` (about five minutes).  The kernel table of the linearised
contact (``numerics.tabulated_moments``, derivation S9) interpolates each kernel on
panels graded toward ``u = 0``; a moving body's wake at large ``|b|`` is a barely damped
oscillation of wavenumber about ``|b|/(2c)`` (``D = b/(rho + |c| s)``), which those panels
resolve only to their stated accuracy.  Stored here, for ``(c, b)`` in :data:`CASES` and
the points ``tau_k`` of the linearisation's projections at ``n = N``, the cosine moments

    C_w[k, j] = integral_0^pi T(s_k - cos T(tau)) W_w(tau) cos(j tau) dtau,
    T(u) = exp(-c u) K0(sqrt(c^2 + b) |u|)         (derivation eq. T3),

``T(tau) = tau - sin(2 tau)/2``, ``s_k = cos T(tau_k)``, ``W_0 = sin^2 T(tau) T'(tau)`` (the
pressure's weight) and ``W_1 = T'(tau) = 2 sin^2 tau`` (the flux's).  Independently of the
table and of the package's kernels: the kernel is SciPy's ``kv`` times the exponential
(not the scaled ``kve`` of the package, nor its wake formula), checked here against
mpmath at a few points of the wake; the integral is ``scipy.integrate.quad_vec`` on
either side of ``tau_k``, broken at offsets halving toward ``tau_k`` (the logarithm and
the upstream boundary layer of width ``1/(2c)``), each piece adaptive (Gauss-Kronrod
21).  The quadrature's own accuracy is measured by a second run on other breakpoints
(offsets shrinking by 3 instead of 2, at every fourth point) and stored as
``reference_change``.
"""

from __future__ import annotations

import json
import pathlib

import numpy as np
from scipy.integrate import quad_vec
from scipy.special import kv

from thermocontact.io.files import atomic_write

OUT = pathlib.Path(__file__).resolve().parent / "wake_moments.json"
#: The body's scale ``c = v Delta/(2k)`` and rate ``b = b_phys Delta^2/k`` (eq. T1).
CASES = ((50.0, 3000j), (200.0, 1e4j))
#: Basis functions; the points are the ``2 N`` projection points of the linearisation.
N = 8


def projection_tau(n):
    """``tau = pi (m - i + 1/2)/m``, ``m = 2n`` (``discretisation.linearised.projections``)."""
    m = 2 * n
    return np.pi * (np.arange(m, 0, -1) - 0.5) / m


def stretch(tau):
    return tau - 0.5 * np.sin(2.0 * tau)


def kernel(u, c, b):
    """``exp(-c u) K0(mu |u|)``, ``mu`` the principal root of ``c^2 + b``."""
    mu = np.sqrt(complex(c * c + b))
    return np.exp(-c * u) * kv(0, mu * abs(u)) if u != 0.0 else 0.0


def cosine_moments(c, b, tau_k, n, shrink):
    """``C_w[j]`` at one point, ``w = 0, 1``, ``j < n``: shape (2, n), complex, and the
    largest error estimate of ``quad_vec``."""
    t_k = stretch(tau_k)
    j = np.arange(n)

    def integrand(tau):
        t = stretch(tau)
        # s_k - cos t without cancellation next to tau_k.
        u = 2.0 * np.sin(0.5 * (t + t_k)) * np.sin(0.5 * (t - t_k))
        d_t = 2.0 * np.sin(tau) ** 2
        w = np.array([np.sin(t) ** 2 * d_t, d_t])
        f = kernel(u, c, b) * w[:, None] * np.cos(j * tau)[None, :]
        return np.concatenate([f.real.ravel(), f.imag.ravel()])

    total, worst = 0.0, 0.0
    for end in (0.0, np.pi):
        offsets = (end - tau_k) * shrink ** -np.arange(0.0, 45.0)
        edges = np.unique(np.concatenate([tau_k + offsets, [tau_k]]))
        for lo, hi in zip(edges[:-1], edges[1:]):
            part, err = quad_vec(integrand, lo, hi, epsabs=1e-15, epsrel=1e-13,
                                 norm="max", limit=2000)
            total = total + part
            worst = max(worst, err)
    out = np.asarray(total)
    half = out.size // 2
    return (out[:half] + 1j * out[half:]).reshape(2, n), worst


def check_kernel():
    """SciPy's ``kv`` product against 30-digit mpmath at a few points of the wake and
    upstream: the largest relative difference."""
    import mpmath

    mpmath.mp.dps = 30
    worst = 0.0
    for c, b in CASES:
        for u in (-1.7, -0.3, -1e-3, 1e-3, 0.02):
            mu = mpmath.sqrt(mpmath.mpc(c * c) + mpmath.mpc(b.real, b.imag))
            exact = complex(mpmath.exp(-c * mpmath.mpf(u)) * mpmath.besselk(0, mu * abs(u)))
            worst = max(worst, abs(kernel(u, c, b) - exact) / abs(exact))
    return worst


def main():
    kernel_error = check_kernel()
    print(f"kv product against mpmath: {kernel_error:.2e} relative", flush=True)
    assert kernel_error < 1e-12
    tau = projection_tau(N)
    cases = []
    for c, b in CASES:
        first = [cosine_moments(c, b, t, N, 2.0) for t in tau]
        moments = np.stack([m for m, _ in first], axis=1)           # (2, k, n)
        # The check on every fourth point (each takes seconds).
        again = np.stack([cosine_moments(c, b, t, N, 3.0)[0] for t in tau[::4]], axis=1)
        change = float(np.abs(moments[:, ::4] - again).max() / np.abs(moments).max())
        estimate = max(e for _, e in first) / float(np.abs(moments).max())
        print(f"c = {c}, b = {b}: reference change {change:.2e}, "
              f"quad_vec estimate {estimate:.2e}", flush=True)
        cases.append({"c": c, "b": [b.real, b.imag], "reference_change": change,
                      "real": moments.real.tolist(), "imag": moments.imag.tolist()})
    record = {"n": N, "tau": tau.tolist(), "kernel_against_mpmath": kernel_error,
              "cases": cases}
    with atomic_write(OUT) as fh:     # whole, or not at all
        fh.write(json.dumps(record, indent=1) + "\n")


if __name__ == "__main__":
    main()
