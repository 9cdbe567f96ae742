"""Write tests/data/tei_layer_reference.json: an independent reference for the
thermoelastic instability (TEI) of a brake disc between pads, by a derivation and a
code of its own (surface admittances, a Nyquist count, a scan of the growth rate).

Run from the repository's root (about twenty minutes on one core):

    python tests/data/make_tei_layer_reference.py

It shares nothing with the package but the material constants written below.

Derivation (plane strain, quasi-static, no Dundurs term; the pads' frame, the disc
moving at ``V`` in ``+x``; fields ``exp(b t + i m x)``, ``m = 2 pi/L``):

* Temperature.  Disc ``kappa1 (T'' - m^2 T) = (b + i m V) T``, pads
  ``kappa2 (T'' - m^2 T) = b T``; ``lam^2 = m^2 + beta``, ``beta1 = (b + i m V)/kappa1``,
  ``beta2 = b/kappa2``, ``Re lam >= 0``.  The thermal admittance ``Y`` (heat flux into
  the body per unit face temperature): disc ``K1 lam tanh(lam a)`` (family "sym": ``T``
  even about the mid-plane) or ``K1 lam coth(lam a)`` ("anti": ``T`` odd), ``a = d/2``;
  a half-plane pad ``K2 lam``; a pad layer of thickness ``h`` on an insulated backing
  ``K2 lam tanh(lam h)``.
* Thermoelastic displacement.  ``u = grad phi``, ``lap phi = k alpha T``,
  ``k = (1 + nu)/(1 - nu)``, so that ``sigma_ij = 2 mu (phi_,ij - delta_ij lap phi)``
  (equilibrium identically).  Homogeneous fields by Papkovich-Neuber:
  ``2 mu u = grad(Phi + y Psi) - 4 (1 - nu) Psi e_y``, ``Phi, Psi`` harmonic.
* Face responses: ``C`` the normal compliance (into the body per unit pressure, no
  temperature), ``g`` the thermal displacement (out of the body per unit face
  temperature, traction-free face).  Half-plane: ``C = 2/(E' m)``,
  ``g = 2 (1 + nu) alpha/(lam + m)``.  Layer ``|y| < a``, ``rho = m d/sinh(m d)``:

      C_s = (2/(E' m)) tanh(m a)/(1 + rho),   g_s = 2(1+nu)alpha tanh(lam a) Q_s/(1 + rho),
      C_a = (2/(E' m)) coth(m a)/(1 - rho),   g_a = 2(1+nu)alpha coth(lam a) Q_a/(1 - rho),
      Q_s,a = (1 +- X_s,a)/(lam + m),
      X_s = 4 m a e^{-2ma} phi1(2(lam - m)a)/((1 + e^{-2ma})(1 - e^{-2 lam a})),
      X_a = 4 m a e^{-2ma} phi1(2(lam - m)a)/((1 - e^{-2ma})(1 + e^{-2 lam a})),

  ``phi1(z) = (1 - e^{-z})/z``; a pad layer on a rigid, frictionless, insulated backing
  is the "sym" half of a free layer of thickness ``2 h``.
* Dispersion relation: heat ``(Y1 + Y2) T = f V p``, no change of gap
  ``(C1 + C2) p = (g1 + g2) T``, so

      Dt(b) = 1 - f V (g1 + g2)/((C1 + C2)(Y1 + Y2)) = 0.

  ``Dt`` has no pole in ``Re b >= 0`` and tends to 1 as ``|b| -> inf`` there, so the
  number of growing modes is minus the winding of ``Dt(i w)`` over the real ``w``.
  Between rigid non-conducting pads the neutral mode is at rest on the disc
  (``lam = m``) and ``V_c = m^2 C1/(f delta1)``, ``delta = alpha (1 + nu)/K``.
* Self-check: the closed forms against the determinant of the boundary conditions of
  the fields themselves (a half system with the mid-plane's conditions, and the whole
  disc, whose determinant is the product of the families'), recorded in the output.

Critical speed: a coarse scan of the Nyquist count (factor 1.3) up to the first
unstable speed, then a fine scan (factor 1.05) of ``R(V)``, the largest real part of
the roots next to the imaginary axis (Newton from the minima of ``|Dt(i w)|``): its
changes of sign are crossings, and every local maximum of ``R`` on the grid that
could reach 0 is refined by bounded maximisation (narrow windows of growth); each
crossing by Brent's method, then Newton's method on ``Dt(i w; V) = 0`` for real
``(w, V)``.  Every crossing up to three times the critical speed is recorded.
Minimum over the wavelength: the critical speed on 40 wavelengths in ``[d, 200 d]``
(the package's range), the least refined by bounded minimisation of the neutral speed
continued in ``ln L``; "boundary" where the least is an end of the range.
"""

import cmath
import json
import math
import os
import sys
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from scipy import optimize

OUT = Path(__file__).with_name("tei_layer_reference.json")


@dataclass(frozen=True)
class Material:
    E: float        # Young's modulus, Pa
    nu: float       # Poisson's ratio
    alpha: float    # thermal expansion, 1/K
    K: float        # conductivity, W/(m K); 0: a non-conductor
    kappa: float    # diffusivity, m^2/s

    @property
    def Ep(self):
        return self.E / (1.0 - self.nu ** 2)

    @property
    def delta(self):
        return self.alpha * (1.0 + self.nu) / self.K

    @property
    def mu(self):
        return self.E / (2.0 * (1.0 + self.nu))


DISC = Material(110e9, 0.26, 10.5e-6, 50.0, 50.0 / (7100.0 * 460.0))
PAD = Material(1e9, 0.25, 30e-6, 1.0, 1.0 / (2000.0 * 1000.0))
F = 0.4
D_DISC = 0.012


@dataclass(frozen=True)
class Pads:
    kind: str                 # "halfplane" | "layer" | "rigid_nonconducting"
    mat: Material = None
    h: float = None           # a pad layer's thickness, m


#: Every crossing below a speed, where a family grows in a window below another branch:
#: (case, L, family, V_high).
WINDOWS = [("A", 0.05, "sym", 1000.0), ("D", 1.15, "sym", 0.5)]

CASES = {
    "A": dict(d=D_DISC, pads=Pads("halfplane", PAD), L=[0.02, 0.05, 0.1, 0.2, 0.5, 1.0],
              description="disc 12 mm between organic half-plane pads"),
    "B": dict(d=D_DISC, pads=Pads("rigid_nonconducting"), L=[0.02, 0.05, 0.1, 0.2, 0.5, 1.0],
              description="disc 12 mm between rigid non-conducting pads"),
    "C": dict(d=1e3, pads=Pads("halfplane", PAD), L=[0.05],
              description="as A with d = 1e3 m (the half-planes' limit)"),
    "D": dict(d=D_DISC, pads=Pads("layer", PAD, 0.010), L=[0.05, 0.2],
              description="pads 10 mm thick on rigid, insulated, frictionless backings"),
}


# --- elementary functions, stable for Re z >= 0 -------------------------------------

def _phi1(z):
    """(1 - exp(-z))/z, 1 at 0."""
    z = complex(z)
    return 1 - z / 2 + z * z / 6 if abs(z) < 1e-6 else -complex(np.expm1(-z)) / z


def _rho(x):
    """(x/sinh x, 1 - x/sinh x), x = m d > 0."""
    if x < 0.1:
        x2 = x * x
        omr = x2 / 6 - 7 * x2 ** 2 / 360 + 31 * x2 ** 3 / 15120 - 127 * x2 ** 4 / 604800
        return 1.0 - omr, omr
    r = 2 * x * math.exp(-x) if x > 700 else x / math.sinh(x)
    return r, 1.0 - r


def layer_CYg(lam, m, a, mat, family):
    """C, Y, g of the face y = a of a layer |y| < a, family "sym" or "anti"."""
    rho, omr = _rho(2 * m * a)
    e = math.exp(-2 * m * a)
    T = -math.expm1(-2 * m * a) / (1 + e)          # tanh(m a)
    El = cmath.exp(-2 * lam * a)
    om = -complex(np.expm1(-2 * lam * a))
    tl = om / (1 + El)                             # tanh(lam a)
    ph = _phi1(2 * (lam - m) * a)
    two_ap = 2.0 * (1 + mat.nu) * mat.alpha
    if family == "sym":
        X = 4 * m * a * e * ph / ((1 + e) * om)
        Q = (1 + X) / (lam + m)
        return 2.0 / (mat.Ep * m) * T / (1 + rho), mat.K * lam * tl, two_ap * Q * tl / (1 + rho)
    X = 4 * m * a * e * ph / ((-math.expm1(-2 * m * a)) * (1 + El))
    Q = (1 - X) / (lam + m)
    return 2.0 / (mat.Ep * m) / (T * omr), mat.K * lam / tl, two_ap * Q / tl / omr


def dispersion(b, V, m, d, pads, family, f=F, disc=DISC):
    """Dt(b) of one family (scalar b)."""
    b = complex(b)
    lam1 = cmath.sqrt(m * m + (b + 1j * m * V) / disc.kappa)
    C1, Y1, g1 = layer_CYg(lam1, m, d / 2, disc, family)
    if pads.kind == "rigid_nonconducting":
        C2 = Y2 = g2 = 0.0
    else:
        lam2 = cmath.sqrt(m * m + b / pads.mat.kappa)
        if pads.kind == "halfplane":
            C2, Y2 = 2.0 / (pads.mat.Ep * m), pads.mat.K * lam2
            g2 = 2.0 * (1 + pads.mat.nu) * pads.mat.alpha / (lam2 + m)
        else:
            C2, Y2, g2 = layer_CYg(lam2, m, pads.h, pads.mat, "sym")
    return 1.0 - f * V * (g1 + g2) / ((C1 + C2) * (Y1 + Y2))


def closed_form_rigid_nonconducting(m, d, family, f=F, disc=DISC):
    """V_c = m^2 C1/(f delta1) between rigid non-conducting pads."""
    rho, omr = _rho(m * d)
    T = math.tanh(m * d / 2)
    if family == "sym":
        return 2 * m * T / (f * disc.Ep * disc.delta * (1 + rho))
    return 2 * m / (T * f * disc.Ep * disc.delta * omr)


# --- the boundary conditions of the fields themselves (a check of the closed forms) ---

def _body_fields(mat, b, Vc, m, y, sides):
    """Rows (T, K T', u_x, u_y, s_yy, s_xy) of each solution at y: per side (sign,
    reference plane), a temperature exp(s lam (y - y_r)) with its particular
    displacement, and Papkovich-Neuber's two solutions on exp(s m (y - y_r))."""
    lam = cmath.sqrt(m * m + (b + 1j * m * Vc) / mat.kappa)
    mu, nu = mat.mu, mat.nu
    k = (1 + nu) / (1 - nu)
    cols = []
    for sgn, yr in sides:
        Y = y - yr
        es, em = cmath.exp(sgn * lam * Y), cmath.exp(sgn * m * Y)
        z = sgn * (lam - m) * Y
        phz = complex(np.expm1(z)) / z if abs(z) > 1e-8 else 1 + z / 2
        Fp_ = em * sgn * Y * phz / (lam + m)         # (e^{s lam Y} - e^{s m Y})/(lam^2 - m^2)
        Fd = sgn * lam * Fp_ + sgn * em / (lam + m)
        cols.append([es, mat.K * sgn * lam * es, 1j * m * k * mat.alpha * Fp_, k * mat.alpha * Fd,
                     2 * mu * m * m * k * mat.alpha * Fp_, 2 * mu * 1j * m * k * mat.alpha * Fd])
        cols.append([0, 0, 1j * m * em / (2 * mu), sgn * m * em / (2 * mu), m * m * em,
                     1j * m * sgn * m * em])
        cols.append([0, 0, 1j * m * Y * em / (2 * mu), (Y * sgn * m - (3 - 4 * nu)) * em / (2 * mu),
                     m * m * Y * em - 2 * (1 - nu) * sgn * m * em,
                     1j * m * (Y * sgn * m - (1 - 2 * nu)) * em])
    return np.array(cols, dtype=complex).T


def dispersion_generic(b, V, m, d, pads, family, f=F, disc=DISC):
    """det M(f)/det M(0) of the boundary conditions: equals Dt of the family for a half
    system ("sym", "anti"), the product of both for the whole disc ("full")."""
    a = d / 2

    def assemble(fv):
        bodies = [(disc, V, [(1, a), (-1, -a if family == "full" else 0.0)])]
        if pads.kind == "halfplane":
            bodies.append((pads.mat, 0.0, [(-1, a)]))
            if family == "full":
                bodies.append((pads.mat, 0.0, [(1, -a)]))
        elif pads.kind == "layer":
            bodies.append((pads.mat, 0.0, [(1, a + pads.h), (-1, a)]))
            if family == "full":
                bodies.append((pads.mat, 0.0, [(1, -a), (-1, -a - pads.h)]))
        sizes = [3 * len(s) for _, _, s in bodies]
        off = np.cumsum([0] + sizes)
        rows = []

        def fields(j, y):
            mat, vc, sides = bodies[j]
            return _body_fields(mat, b, vc, m, y, sides)

        def row(*terms):
            r = np.zeros(off[-1], dtype=complex)
            for j, vec in terms:
                r[off[j]:off[j + 1]] += vec
            rows.append(r)

        def contact(y, j, upper):
            s = 1.0 if upper else -1.0
            Fd = fields(0, y)
            if j is None:
                row((0, s * Fd[1] + fv * Fd[4]))
                row((0, Fd[3]))
                row((0, Fd[5]))
                return
            Fp = fields(j, y)
            row((0, Fd[0]), (j, -Fp[0]))
            row((0, s * Fd[1] + fv * Fd[4]), (j, -s * Fp[1]))
            row((0, Fd[4]), (j, -Fp[4]))
            row((0, Fd[5]))
            row((j, Fp[5]))
            row((0, Fd[3]), (j, -Fp[3]))

        def backing(y, j):
            Fb = fields(j, y)
            row((j, Fb[1]))
            row((j, Fb[3]))
            row((j, Fb[5]))

        up = 1 if pads.kind != "rigid_nonconducting" else None
        contact(a, up, True)
        if pads.kind == "layer":
            backing(a + pads.h, 1)
        if family == "full":
            lo = 2 if pads.kind != "rigid_nonconducting" else None
            contact(-a, lo, False)
            if pads.kind == "layer":
                backing(-a - pads.h, 2)
        else:
            F0 = fields(0, 0.0)
            for q in ((1, 3, 5) if family == "sym" else (0, 2, 4)):
                row((0, F0[q]))
        return np.array(rows)

    M, M0 = assemble(f * V), assemble(0.0)
    r = 1.0 / np.max(np.abs(M0), axis=1)
    M, M0 = M * r[:, None], M0 * r[:, None]
    c = 1.0 / np.max(np.abs(M0), axis=0)
    M, M0 = M * c[None, :], M0 * c[None, :]
    s1, l1 = np.linalg.slogdet(M)
    s0, l0 = np.linalg.slogdet(M0)
    return s1 / s0 * np.exp(l1 - l0)


# --- roots, the Nyquist count, crossings ---------------------------------------------

def _freq_grid(V, m, d, pads, n=400):
    scales = [DISC.kappa * m * m, DISC.kappa / (d / 2) ** 2, m * V]
    if pads.kind != "rigid_nonconducting":
        scales.append(pads.mat.kappa * m * m)
        if pads.kind == "layer":
            scales.append(pads.mat.kappa / pads.h ** 2)
    lo, hi = min(scales) * 1e-4, max(scales) * 1e6
    s = np.geomspace(lo, hi, n)
    w = np.concatenate([-s[::-1], [0.0], s])
    w = np.concatenate([w, w - m * V, [-1e3 * hi, 1e3 * hi]])
    return np.unique(w)


def winding(V, m, d, pads, family):
    """(number of zeros of Dt in Re b > 0, the sampled axis, Dt there)."""
    fun = np.vectorize(lambda b: dispersion(b, V, m, d, pads, family))
    w = _freq_grid(V, m, d, pads)
    w = w + 1e-13 * np.abs(w)                 # never exactly b = -i m V
    D = fun(1j * w)
    for _ in range(60):
        D = np.where(D == 0, 1e-300, D)       # a root on the axis itself (a neutral point)
        dphi = np.angle(D[1:] / D[:-1])
        bad = np.abs(dphi) > 0.25
        if not bad.any():
            break
        idx = np.nonzero(bad)[0]
        wm = 0.5 * (w[idx] + w[idx + 1])
        w = np.insert(w, idx + 1, wm)
        D = np.insert(D, idx + 1, fun(1j * wm))
    D = np.where(D == 0, 1e-300, D)
    total = np.angle(D[1:] / D[:-1]).sum() + np.angle(D[0]) - np.angle(D[-1])
    n = -total / (2 * np.pi)
    if abs(n - round(n)) > 1e-6 and np.min(np.abs(D)) > 1e-12:
        raise RuntimeError(f"non-integer winding {n}")
    return int(round(n)), w, D


def _secant(fun, b0, tol=1e-14, maxit=40):
    h = 1e-7 * max(abs(b0), 1.0)
    x0, x1 = b0, b0 + h
    f0, f1 = fun(x0), fun(x1)
    for _ in range(maxit):
        if f1 == f0:
            break
        x0, f0, x1 = x1, f1, x1 - f1 * (x1 - x0) / (f1 - f0)
        f1 = fun(x1)
        if abs(x1 - x0) < tol * max(abs(x1), 1.0):
            break
    return x1


def least_stable_roots(V, m, d, pads, family, k=4, rest_frames=False):
    """(Nyquist count, the roots next to the imaginary axis): the secant method from
    the local minima of |Dt(i w)| on the sampled axis (and with ``rest_frames`` from
    next to the disc's and the pads' frames of rest too)."""
    n, w, D = winding(V, m, d, pads, family)
    fun = lambda b: dispersion(b, V, m, d, pads, family)  # noqa: E731
    a = np.abs(D)
    loc = np.nonzero((a[1:-1] <= a[:-2]) & (a[1:-1] <= a[2:]))[0] + 1
    roots = []
    starts = [1j * w[i] + 1e-9 * max(abs(w[i]), 1.0) for i in loc[np.argsort(a[loc])][:k]]
    if rest_frames:
        # A mode at rest on the disc (b = -i m V) or on the pads (b = 0): between rigid
        # non-conducting pads the growing one is at rest on the disc, where |Dt| on the
        # sampled axis has no minimum to start from.
        scale = DISC.kappa * m * m
        starts += [-1j * m * V + 1e-2 * scale, 1e-2 * scale]
    with np.errstate(all="ignore"):
        for b0 in starts:
            try:
                r = _secant(fun, b0)
            except (ZeroDivisionError, OverflowError, ValueError):
                continue
            if not np.isfinite(r) or abs(fun(r)) > 1e-9:
                continue
            if any(abs(r - q) <= 1e-8 * max(abs(r), 1.0) for q in roots):
                continue
            roots.append(r)
    return n, roots


def growth(V, m, d, pads, family):
    n, roots = least_stable_roots(V, m, d, pads, family)
    R = max([r.real for r in roots], default=-1e300)
    if n > 0 and R < 0.0:
        roots += least_stable_roots(V, m, d, pads, family, rest_frames=True)[1]
        R = max([r.real for r in roots], default=-1e300)
    if n > 0 and R < -1e-9 * max([abs(r) for r in roots], default=1.0):
        raise RuntimeError(f"the count says unstable, no unstable root found at V = {V}")
    return R


def neutral_refine(V0, w0, m, d, pads, family):
    """Dt(i w; V) = 0 for real (w, V) near (w0, V0), by a 2x2 Newton (hybr)."""
    ws = max(abs(w0), m * V0)

    def F(x):
        D = dispersion(1j * ws * x[1], V0 * x[0], m, d, pads, family)
        return [D.real, D.imag]

    sol = optimize.root(F, [1.0, w0 / ws], method="hybr", tol=1e-15,
                        options={"xtol": 1e-15, "maxfev": 400})
    V, w = V0 * sol.x[0], ws * sol.x[1]
    return V, w, abs(dispersion(1j * w, V, m, d, pads, family))


def _guess(m, d, pads, family):
    lam = complex(m)
    C1 = layer_CYg(lam, m, d / 2, DISC, family)[0]
    C2 = 0.0
    if pads.kind == "halfplane":
        C2 = 2 / (pads.mat.Ep * m)
    elif pads.kind == "layer":
        C2 = layer_CYg(lam, m, pads.h, pads.mat, "sym")[0]
    return float(m * m * (C1 + C2) / (F * DISC.delta))


def crossings(m, d, pads, family, V_lo, V_hi, fine=1.05, stop_at_first=False):
    """Every speed in [V_lo, V_hi] where R(V) changes sign: (V, +1 becoming unstable or
    -1 stable again), local maxima of R on the grid refined by bounded maximisation."""
    R = lambda V: growth(V, m, d, pads, family)  # noqa: E731
    solve = lambda a, b: optimize.brentq(R, a, b, xtol=1e-14 * b, rtol=1e-15)  # noqa: E731
    grid = [V_lo]
    while grid[-1] < V_hi:
        grid.append(min(grid[-1] * fine, V_hi))
    Rs, out = [], []
    for i, Vg in enumerate(grid):
        Rs.append(R(Vg))
        if i and (Rs[-2] < 0) != (Rs[-1] < 0):
            out.append((solve(grid[i - 1], Vg), 1 if Rs[-1] >= 0 else -1))
        elif i >= 2 and Rs[-3] <= Rs[-2] >= Rs[-1] and Rs[-2] < 0 and \
                Rs[-2] + 2.0 * max(Rs[-2] - Rs[-3], Rs[-2] - Rs[-1]) >= 0:
            res = optimize.minimize_scalar(lambda lv: -R(math.exp(lv)),
                                           bounds=(math.log(grid[i - 2]), math.log(Vg)),
                                           method="bounded", options={"xatol": 1e-10})
            if -res.fun >= 0:
                top = math.exp(res.x)
                out += [(solve(grid[i - 2], top), 1), (solve(top, Vg), -1)]
        if stop_at_first and out:
            break
    return sorted(out)


def polish(Vc, m, d, pads, family):
    """(V, w) of the neutral mode near the crossing Vc."""
    for eps in (0.0, 1e-10, -1e-10, 1e-8, -1e-8):
        _, roots = least_stable_roots(Vc * (1 + eps), m, d, pads, family, k=8,
                                      rest_frames=True)
        if roots:
            break
    bc = max(roots, key=lambda r: r.real)
    V, w, res = neutral_refine(Vc, bc.imag, m, d, pads, family)
    if abs(V / Vc - 1) > 1e-7:
        raise RuntimeError(f"polishing moved V: {Vc} -> {V}")
    return V, w, res


def critical_speed(m, d, pads, family, beyond=None):
    """The lowest speed at which a mode grows, the neutral w, and (with ``beyond``)
    every crossing up to ``beyond`` times it."""
    V_guess = _guess(m, d, pads, family)
    V0 = 0.03 * V_guess
    if winding(V0, m, d, pads, family)[0]:
        raise RuntimeError("unstable at the lowest speed scanned")
    V = V0
    while True:
        V *= 1.3
        if V > 1e9 * V_guess:
            return None
        if winding(V, m, d, pads, family)[0] > 0:
            break
    first = crossings(m, d, pads, family, V0, V, stop_at_first=True)
    if not first or first[0][1] != 1:
        raise RuntimeError(f"no upward crossing below {V}: {first}")
    Vc, w, res = polish(first[0][0], m, d, pads, family)
    out = dict(V=Vc, omega=w, migration_speed=-w / m, residual=res)
    if beyond is not None:
        allc = crossings(m, d, pads, family, V0, beyond * Vc)
        out["crossings"] = [dict(speed=float(polish(v, m, d, pads, family)[0]), direction=s)
                            for v, s in allc]
    return out


def minimum_over_wavelength(d, pads, family, points=40):
    """The least critical speed over L in [d, 200 d] and its wavelength."""
    Ls = np.geomspace(d, 200 * d, points)
    rows = [critical_speed(2 * math.pi / L, d, pads, family) for L in Ls]
    V = np.array([r["V"] for r in rows])
    i = int(np.argmin(V))
    if i in (0, points - 1):
        return dict(L_min=float(Ls[i]), V_min=float(V[i]), boundary=True,
                    grid_L=Ls.tolist(), grid_V=V.tolist())
    # The neutral point continued in ln L from the least point of the grid.
    L0, V0, w0 = Ls[i], rows[i]["V"], rows[i]["omega"]

    def vc(lL):
        L = math.exp(lL)
        s = (L0 / L)                      # V ~ m and w ~ m^2 at a fixed m d: a guess
        V, w, res = neutral_refine(V0 * s, w0 * s * s, 2 * math.pi / L, d, pads, family)
        return V if res < 1e-9 else math.inf

    res = optimize.minimize_scalar(vc, bounds=(math.log(Ls[i - 1]), math.log(Ls[i + 1])),
                                   method="bounded", options={"xatol": 1e-10})
    L_min = math.exp(res.x)
    check = critical_speed(2 * math.pi / L_min, d, pads, family)
    if abs(check["V"] / res.fun - 1) > 1e-9:
        raise RuntimeError(f"the continued minimum is not the critical speed: {check}")
    return dict(L_min=L_min, V_min=check["V"], migration_speed_at_min=check["migration_speed"],
                boundary=False, grid_L=Ls.tolist(), grid_V=V.tolist())


def self_checks():
    """The closed forms against the boundary conditions' determinant (relative)."""
    rng = np.random.default_rng(12345)
    out = {}
    for pads in (Pads("halfplane", PAD), Pads("layer", PAD, 0.01), Pads("rigid_nonconducting")):
        e_fam = e_full = 0.0
        for L in (0.005, 0.02, 0.2, 2.0):
            m = 2 * math.pi / L
            for V in (0.01, 3.0, 300.0):
                for _ in range(3):
                    b = (rng.random() * m * V * 10 ** rng.uniform(-4, 0)
                         + 1j * m * V * rng.uniform(-2, 1))
                    Ds = {fam: dispersion(b, V, m, D_DISC, pads, fam) for fam in ("sym", "anti")}
                    for fam in ("sym", "anti"):
                        D2 = dispersion_generic(b, V, m, D_DISC, pads, fam)
                        e_fam = max(e_fam, abs(Ds[fam] - D2) / max(abs(1 - Ds[fam]), 1e-300))
                    Df = dispersion_generic(b, V, m, D_DISC, pads, "full")
                    P = Ds["sym"] * Ds["anti"]
                    e_full = max(e_full, abs(Df - P) / max(abs(P), abs(1 - P)))
        out[pads.kind] = dict(family_vs_boundary_conditions=e_fam, whole_disc_vs_product=e_full)
    return out


def main():
    t0 = time.time()
    out = {"units": "SI: m, m/s, rad/s, 1/s",
           "conventions": {
               "frame": "the pads'; the disc moves at +V; fields exp(b t + i m x), m = 2 pi/L",
               "migration_speed": "-omega/m, the crests' speed relative to the pads, positive "
                                  "in the disc's direction (V: at rest on the disc)",
               "families": "sym: equal pressures on both faces (the package's 'symmetric'); "
                           "anti: opposite ones ('antisymmetric')",
               "crossings": "every neutral crossing up to 3 times the critical speed; "
                            "direction +1 where a mode starts to grow with V, -1 where it stops",
               "minimum": "over L in [d, 200 d] (the package's range); boundary: at an end",
               "windows": "every crossing below V_high where a family grows in a window "
                          "below the critical speed of another branch"},
           "materials": {"disc": DISC.__dict__, "pad": PAD.__dict__}, "friction": F,
           "checks": self_checks(), "cases": {}}
    out["windows"] = []
    for name, L, fam, V_high in WINDOWS:
        d, pads, m = CASES[name]["d"], CASES[name]["pads"], 2 * math.pi / L
        V0 = 0.03 * _guess(m, d, pads, fam)
        allc = crossings(m, d, pads, fam, V0, V_high)
        out["windows"].append(dict(case=name, L=L, family=fam, V_high=V_high, crossings=[
            dict(speed=float(polish(v, m, d, pads, fam)[0]), direction=s) for v, s in allc]))
        print("window", name, L, fam, out["windows"][-1]["crossings"], flush=True)
    for name, case in CASES.items():
        d, pads = case["d"], case["pads"]
        entry = {"description": case["description"], "d": d, "pads": pads.kind, "pad_h": pads.h,
                 "per_wavelength": []}
        for L in case["L"]:
            m = 2 * math.pi / L
            row = {"L": L}
            for fam in ("sym", "anti"):
                row[fam] = critical_speed(m, d, pads, fam, beyond=3.0)
                if pads.kind == "rigid_nonconducting":
                    row[fam]["closed_form"] = closed_form_rigid_nonconducting(m, d, fam)
            entry["per_wavelength"].append(row)
            print(name, L, row["sym"]["V"], row["anti"]["V"], f"{time.time() - t0:.0f} s",
                  flush=True)
        if name in ("A", "B", "D"):
            entry["minimum"] = {fam: minimum_over_wavelength(d, pads, fam) for fam in ("sym", "anti")}
            print(name, "minimum", {k: (v["L_min"], v["V_min"], v["boundary"])
                                    for k, v in entry["minimum"].items()},
                  f"{time.time() - t0:.0f} s", flush=True)
        out["cases"][name] = entry
    # The roots next to the axis at a few speeds (case A, L = 50 mm).
    m = 2 * math.pi / 0.05
    out["roots_A_50mm"] = {fam: {str(V): [[r.real, r.imag] for r in
                                           least_stable_roots(V, m, D_DISC, CASES["A"]["pads"],
                                                              fam, k=8)[1]]
                                 for V in (400.0, 459.0, 600.0, 800.0, 930.0)}
                           for fam in ("sym", "anti")}
    # Whole, or not at all (the package is not imported: a file beside, then renamed).
    part = OUT.with_name(OUT.name + ".part")
    part.write_text(json.dumps(out, indent=1) + "\n")
    os.replace(part, OUT)
    print("written", OUT, f"{time.time() - t0:.0f} s")


if __name__ == "__main__":
    sys.exit(main())
