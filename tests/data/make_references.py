"""Independent reference values for the tests, computed once and stored.

Run ``python tests/data/make_references.py`` (mpmath needed) to regenerate
``tests/data/references.json``.  Every value is an integral computed by mpmath's
adaptive tanh-sinh quadrature at the precision stated, independently of the
package's moment rules; the package supplies only the points' coordinates, which
are stored with the values so that a test uses exactly these inputs.

Entries
-------
graded_moments/<kernel>
    Moments of a kernel against the edge-graded bases,
    ``integral_0^pi K(s - cos T(tau)) W(tau) cos(j tau) dtau`` with
    ``T = tau - sin(2 tau)/2`` and ``W = sin^2 T T'`` ("b") or ``T'`` ("s"), for
    ``sgn``, ``N(cu) H(u)`` and ``c M(cu) - 1/u`` (c = 50), at points inside, next
    to and outside the contact; breakpoints at ``tau_s`` and on the kernel's scale
    around it.  30 digits (20 for the Bessel-K kernel, whose mpmath evaluation is
    slow); accurate to far below the tests' 1e-12.
graded_edge_row
    The moment against ``cos(63 tau) T'`` of ``c M(cu) - 1/u`` at c = 1e5 on the
    Galerkin point nearest an edge (n = 64), breakpoints graded toward ``tau_s``;
    20 digits.
graded_cauchy_edge_row
    The principal value against ``cos(127 tau) T'`` on the Galerkin point nearest
    an edge (n = 128) by subtraction of the pole; 30 digits.
graded_cauchy
    ``(1/pi) PV integral p(r)/(s - r) dr`` for the bounded graded bases
    ``p = sin T cos(j tau)`` (in ``tau``: ``sin^2 T T' cos(j tau)``), by subtraction
    of the pole in ``tau``, at points inside and 1e-6 from the edges; 30 digits.
chebyshev_moments/<kernel>
    ``integral_0^pi K(s - cos t) sin t sin((j + 1) t) dt`` ("b") and
    ``integral_0^pi K(s - cos t) cos(j t) dt`` ("s") for ``N(cu) H(u)`` (c = 5 and
    1000) and ``c M(cu) - 1/u`` (c = 5), breakpoints at ``t_s`` and on the kernel's
    scale around it; 25 digits.
"""

from __future__ import annotations

import json
import pathlib

import mpmath as mp
import numpy as np

HERE = pathlib.Path(__file__).parent
C = 50.0


def T(x):
    return x - mp.sin(2 * x) / 2


def graded_moment(kernel, s, j, weight, ts, c):
    """``integral_0^pi K(s - cos T) W cos(j tau) dtau`` with breakpoints at ``ts``."""
    w = (lambda x: mp.sin(T(x)) ** 2 * 2 * mp.sin(x) ** 2) if weight == "b" else (
        lambda x: 2 * mp.sin(x) ** 2)
    f = lambda x: kernel(s - mp.cos(T(x))) * w(x) * mp.cos(j * x)  # noqa: E731
    pts = [0, ts, mp.pi] if 0 < ts < mp.pi else [0, mp.mpf("1e-3"), mp.mpf("0.1"), mp.pi]
    if c and 0 < ts < mp.pi:  # the kernels' structure on the scale 1/c around ts
        pts = sorted(set([0, ts, mp.pi] + [ts + k * 10.0 ** -e for k in (-1, 1)
                                           for e in (1, 2, 3) if 0 < ts + k * 10.0 ** -e < mp.pi]))
    return mp.quad(f, pts)


def mp_kernels(c):
    return {
        "sgn": mp.sign,
        "NH": lambda u: (mp.exp(-c * u) * (mp.besseli(0, c * u) - mp.besseli(1, c * u))
                         if u > 0 else mp.mpf(0)),
        "mr": lambda u: c * mp.exp(-c * u) * (mp.besselk(0, abs(c * u))
                                              + mp.sign(u) * mp.besselk(1, abs(c * u))) - 1 / u,
    }


def graded_moments():
    from thermocontact.numerics import moment_engine as graded

    out = {}
    for name, kernel in mp_kernels(C).items():
        dps = 20 if name == "mr" else 30
        s = [-0.3, 0.9999] if name == "mr" else [-0.999999, -0.3, 0.7, 0.9999, 1.3]
        js = [0, 11] if name == "mr" else [0, 5, 11]
        tau_s = [float(t) for t in graded.tau_of(np.array(s))]
        values = []
        with mp.workdps(dps):
            for sk, tk in zip(s, tau_s):
                for j in js:
                    for weight in ("b", "s"):
                        ref = graded_moment(kernel, mp.mpf(sk), j, weight, mp.mpf(tk),
                                            C if name != "sgn" else 0)
                        values.append([sk, j, weight, float(ref)])
        out[name] = {"c": C, "s": s, "tau_s": tau_s, "values": values, "digits": dps}
    return out


def graded_edge_row():
    from thermocontact.discretisation.representations import range_projections

    c, n, j = 1e5, 64, 63
    tau, _, _ = range_projections(n)
    k = int(np.argmin(tau))
    with mp.workdps(20):
        ts = mp.mpf(float(tau[k]))
        sk = mp.cos(T(ts))

        def mr(x):
            u = sk - mp.cos(T(x))
            a = abs(c * u)
            return c * mp.exp(-c * u) * (mp.besselk(0, a) + mp.sign(u) * mp.besselk(1, a)) - 1 / u

        pts = sorted({mp.mpf(0), ts, mp.pi} | {ts - ts * mp.mpf(2) ** -e for e in range(1, 50, 6)}
                     | {ts + mp.mpf(2) ** -e for e in range(1, 50, 6)}
                     | {mp.mpf(0.1) * i for i in range(1, 10)})
        ref = mp.quad(lambda x: 2 * mp.sin(x) ** 2 * mp.cos(j * x) * mr(x), pts)
    return {"c": c, "n": n, "j": j, "tau_s": float(tau[k]), "value": float(ref), "digits": 20}


def principal_value(f, ts, extra_points=()):
    """``PV integral_0^pi f(x) / (cos T(ts) - cos T(x)) dx`` by subtracting the pole.

    Near ``ts`` the denominator is ``D (x - ts)`` with ``D = sin T(ts) T'(ts)``; it is
    formed as ``2 sin(T(ts) + dT/2) sin(dT/2)``, ``dT = T(x) - T(ts)``, without
    cancellation, and the subtracted ``f(ts)/(D (x - ts))`` is integrated in closed form.
    """
    D = mp.sin(T(ts)) * 2 * mp.sin(ts) ** 2
    g0 = f(ts) / D

    def subtracted(x):
        dx = x - ts
        if dx == 0:
            return mp.mpf(0)
        dT = dx - mp.cos(x + ts) * mp.sin(dx)
        return f(x) / (2 * mp.sin(T(ts) + dT / 2) * mp.sin(dT / 2)) - g0 / dx

    pts = sorted({mp.mpf(0), ts, mp.pi} | {ts + g * mp.mpf(2) ** -e for e in range(1, 60, 3)
                                           for g in (-1, 1) if 0 < ts + g * mp.mpf(2) ** -e < mp.pi}
                 | set(extra_points))
    return mp.quad(subtracted, pts) + g0 * mp.log((mp.pi - ts) / ts)


def graded_cauchy_edge_row():
    from thermocontact.discretisation.representations import range_projections

    n, j = 128, 127
    tau, _, _ = range_projections(n)
    k = int(np.argmin(tau))
    with mp.workdps(30):
        ts = mp.mpf(float(tau[k]))
        ref = principal_value(lambda x: 2 * mp.sin(x) ** 2 * mp.cos(j * x), ts,
                              [mp.pi * i / 32 for i in range(1, 32)])
    return {"n": n, "j": j, "tau_s": float(tau[k]), "value": float(ref), "digits": 30}


def graded_cauchy():
    from thermocontact.numerics import moment_engine as graded

    s = [-0.999999, -0.4, 0.1, 0.95, 0.999999]
    js = [0, 3, 9]
    tau_s = [float(t) for t in graded.tau_of(np.array(s))]
    values = []
    with mp.workdps(30):
        for sk, tk in zip(s, tau_s):
            ts = mp.mpf(tk)
            for j in js:
                ref = principal_value(
                    lambda x, j=j: mp.sin(T(x)) ** 2 * 2 * mp.sin(x) ** 2 * mp.cos(j * x), ts) / mp.pi
                values.append([sk, j, float(ref)])
    return {"s": s, "tau_s": tau_s, "values": values, "digits": 30}


CHEB_S = [-0.999, -0.3, 0.0, 0.5, 0.99999, 1.0, 1.001, -1.2]


def chebyshev_moments():
    out = {}
    cases = {"NH_5": ("NH", 5.0, (0, 1, 3, 4, 6)), "NH_1000": ("NH", 1000.0, (0, 1, 3, 4, 6)),
             "mr_5": ("mr", 5.0, (0, 1, 3, 4, 7))}
    for key, (name, c, rows) in cases.items():
        kernel = mp_kernels(c)[name]
        values = []
        with mp.workdps(25):
            for k in rows:
                sk = mp.mpf(CHEB_S[k])
                ts = mp.acos(max(min(sk, 1), -1))
                for j in (0, 5, 63):
                    for weight in ("b", "s"):
                        def f(t, j=j, weight=weight):
                            u = sk - mp.cos(t)
                            if u == 0:
                                return mp.mpf(0)
                            base = mp.sin(t) * mp.sin((j + 1) * t) if weight == "b" else mp.cos(j * t)
                            return kernel(u) * base
                        pts = sorted({mp.mpf(0), ts, mp.pi} | {ts + g * mp.mpf(10) ** -e
                                     for e in range(1, 8) for g in (-1, 1)
                                     if 0 < ts + g * mp.mpf(10) ** -e < mp.pi}
                                     | {mp.pi * i / 16 for i in range(1, 16)})
                        values.append([k, j, weight, float(mp.quad(f, pts))])
        out[key] = {"c": c, "s": CHEB_S, "values": values, "digits": 25}
    return out


def main():
    refs = {
        "graded_moments": graded_moments(),
        "graded_edge_row": graded_edge_row(),
        "graded_cauchy_edge_row": graded_cauchy_edge_row(),
        "graded_cauchy": graded_cauchy(),
        "chebyshev_moments": chebyshev_moments(),
    }
    path = HERE / "references.json"
    path.write_text(json.dumps(refs, indent=1) + "\n")
    print(f"wrote {path.name}")


if __name__ == "__main__":
    main()
