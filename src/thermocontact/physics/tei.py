"""Thermoelastic instability (TEI) of two sliding half-planes: the dispersion relation.

Two elastic, heat-conducting half-planes in plane strain, the *slider* (body 1,
``y > 0``) sliding over the *counterface* (body 2, ``y < 0``, at rest in the frame
used here) with velocity ``U`` along ``x`` (``|U| = V``), friction ``f``.  Every
perturbation of the uniform sliding state is a sum of modes
``exp(b t + i m x)``; ``m > 0`` is the wavenumber ``2 pi / L`` and ``b`` the complex
growth rate in the counterface's frame.  The derivation, with its checks, is the
section "Thermoelastic instability of sliding half-planes" of ``docs/derivation.md``
(equations H1-H12 cited below).

A body with conductivity ``K = 0`` is a non-conductor (the limit ``K -> 0`` at a
fixed heat capacity ``rho c``): no heat enters it and it does not distort thermally.

This module holds the physics and the root search on the dispersion relation; the
second method, a discretisation in depth, is
:mod:`thermocontact.discretisation.tei_depth`, and the studies (critical speed,
modes, most unstable wavelength) are :mod:`thermocontact.studies.tei`.
"""

from __future__ import annotations

import cmath
import math
from dataclasses import dataclass

import numpy as np

from ..problem.materials import Material, dundurs_beta
from ..problem.validation import InputError, check_nonnegative

__all__ = [
    "FRICTION_RANGE",
    "SPEED_RANGE",
    "SlidingPair",
    "WAVELENGTH_RANGE",
    "dispersion",
    "high_speed_limit",
    "high_speed_roots",
    "high_speed_unstable",
    "modes",
    "speed_lower_bound",
    "surface_kernels",
]

#: Wavelengths studied, m: a nanometre to a kilometre (beyond, the dimensionless
#: groups of the dispersion relation overflow or underflow).
WAVELENGTH_RANGE = (1e-9, 1e3)
#: Sliding speeds studied besides 0, m/s: below, the growth rates underflow and the
#: most unstable wavelength is not resolved; above, no machine slides.
SPEED_RANGE = (1e-9, 1e4)
#: Coefficients of friction besides 0 (no frictional heat): below, the critical speed
#: overflows; above, no pair of materials slides.
FRICTION_RANGE = (1e-6, 10.0)


@dataclass(frozen=True)
class SlidingPair:
    """Two half-planes sliding over each other, friction and the Dundurs term.

    Parameters
    ----------
    slider : Material
        Body 1, the half-plane that slides.
    counterface : Material
        Body 2, at rest in the frame of the dispersion relation.
    friction : float
        Coulomb coefficient ``f >= 0``.
    dundurs : bool, optional
        Keep (default) the normal displacement that the friction traction ``f p``
        causes between dissimilar materials (``beta f``, derivation section 5c).

    Raises
    ------
    InputError
        If a body is not a :class:`Material`, ``friction < 0``, or neither body
        conducts heat.
    """

    slider: Material
    counterface: Material
    friction: float
    dundurs: bool = True

    def __post_init__(self):
        for name in ("slider", "counterface"):
            if not isinstance(getattr(self, name), Material):
                raise InputError(f"{name} must be a Material, got {getattr(self, name)!r}",
                                 parameters=(name,))
        object.__setattr__(self, "friction", check_nonnegative("friction", self.friction))
        object.__setattr__(self, "dundurs", bool(self.dundurs))
        if self.slider.K == 0.0 and self.counterface.K == 0.0:
            raise InputError("slider and counterface must not both be non-conducting "
                             "(K = 0): no heat would enter either body",
                             parameters=("slider", "counterface"))

    @property
    def bodies(self) -> tuple[Material, Material]:
        return self.slider, self.counterface

    @property
    def compliance(self) -> float:
        """``A = (1 - nu1)/mu1 + (1 - nu2)/mu2 = 2/E*``, 1/Pa (plane strain)."""
        return self.slider.compliance + self.counterface.compliance

    @property
    def beta(self) -> float:
        """The paper's ``beta`` of the pair, slider as body 1 (0 with ``dundurs=False``)."""
        return dundurs_beta(self.slider, self.counterface) if self.dundurs else 0.0

    def dundurs_factor(self, velocity) -> complex:
        """``c = 1 + i sgn(U) beta f / 2`` of the contact condition (H6)."""
        return 1.0 + 0.5j * math.copysign(1.0, velocity) * self.beta * self.friction


def _expansion(mat: Material) -> float:
    """``alpha (1 + nu) = delta K``, 1/K; 0 for a non-conductor, which does not distort."""
    return mat.alpha * (1.0 + mat.nu) if mat.K > 0.0 else 0.0


def _root(w):
    """Principal square root, ``Re >= 0``: the field decays into the body (H2)."""
    return np.sqrt(np.asarray(w, dtype=complex))


def surface_kernels(b, wavenumber, velocity, material: Material):
    """A half-plane's transient surface response to a surface temperature
    ``Theta exp(b t + i m x)`` (H1-H4).

    Parameters
    ----------
    b : complex or array_like
        Growth rate, 1/s, in the frame where the body's material moves at ``velocity``.
    wavenumber : float
        ``m > 0``, 1/m.
    velocity : float
        The material's velocity along ``x``, m/s.
    material : Material

    Returns
    -------
    heat : complex ndarray
        Heat flux into the body per unit surface temperature, ``K gamma``, W/m^2/K.
    displacement : complex ndarray
        Outward thermoelastic surface displacement per unit surface temperature,
        ``2 alpha (1 + nu)/(gamma + m)``, m/K (Maysel's integral, D3); both 0 for a
        non-conductor.  ``gamma = sqrt(m^2 + (b + i m U)/kappa)``, ``Re gamma > 0``.
    """
    b = np.asarray(b, dtype=complex)
    m = wavenumber
    if material.K == 0.0:
        zero = np.zeros(b.shape, dtype=complex)
        return zero, zero.copy()
    gamma = _root(m * m + (b + 1j * m * velocity) / material.k)
    return material.K * gamma, 2.0 * _expansion(material) / (gamma + m)


def dispersion(pair: SlidingPair, b, wavenumber, velocity):
    """The dispersion function ``D(b)``, dimensionless, zero at a mode (H7).

    ``D = (f V m / A) sum_i W_i / sum_i Y_i - (1 + i sgn(U) beta f / 2)``, with
    ``W_i``, ``Y_i`` the displacement and heat of :func:`surface_kernels`, the
    slider's material moving at ``U = velocity`` and the counterface's at rest.

    Parameters
    ----------
    pair : SlidingPair
    b : complex or array_like
        Growth rate in the counterface's frame, 1/s.
    wavenumber : float
        ``m = 2 pi / L``, 1/m.
    velocity : float
        The slider's signed velocity ``U``, m/s.
    """
    h1, w1 = surface_kernels(b, wavenumber, velocity, pair.slider)
    h2, w2 = surface_kernels(b, wavenumber, 0.0, pair.counterface)
    coupling = pair.friction * abs(velocity) * wavenumber / pair.compliance
    return coupling * (w1 + w2) / (h1 + h2) - pair.dundurs_factor(velocity)


def speed_lower_bound(pair: SlidingPair, wavenumber) -> float:
    """A speed below which no mode grows: ``A m (K1 + K2) / (f (a1 + a2))`` (H9),
    ``a = alpha (1 + nu)`` of each conductor; ``inf`` without friction."""
    a = _expansion(pair.slider) + _expansion(pair.counterface)
    if pair.friction == 0.0 or a == 0.0:
        return math.inf
    return (pair.compliance * wavenumber * (pair.slider.K + pair.counterface.K)
            / (pair.friction * a))


def _padd(*polys):
    """Sum of coefficient arrays (lowest degree first) of any lengths."""
    out = np.zeros(max(len(p) for p in polys), dtype=complex)
    for p in polys:
        out[: len(p)] += p
    return out


def _reference(pair: SlidingPair, velocity):
    """(reference body, its velocity, other body, its velocity): the reference is the
    counterface unless it does not conduct."""
    if pair.counterface.K > 0.0:
        return pair.counterface, 0.0, pair.slider, velocity
    return pair.slider, velocity, pair.counterface, 0.0


def modes(pair: SlidingPair, wavenumber, velocity, *, polish=True):
    """Every mode ``b`` of the dispersion relation, fastest growing first (H8).

    With ``z = gamma_r / m`` of a conducting reference body ``r`` (the counterface
    unless it does not conduct) and ``z_o = sqrt(w(z))`` of the other body, the
    relation reads ``E0(z) + E1(z) z_o = 0``; every mode is a root of the
    polynomial ``E0^2 - w E1^2`` (degree 6; 2 with a non-conductor).  The roots with
    ``Re z > 0`` and ``Re z_o > 0`` that satisfy the unsquared relation are the
    modes; each is polished by Newton's method on the relation itself.

    Parameters
    ----------
    pair : SlidingPair
    wavenumber : float
        ``m > 0``, 1/m.
    velocity : float
        The slider's signed velocity ``U`` relative to the counterface, m/s.
    polish : bool, optional
        Newton steps on the unsquared relation (default).

    Returns
    -------
    ndarray of complex
        Growth rates ``b`` in the counterface's frame, 1/s, by decreasing real part.
    """
    m = float(wavenumber)
    ref, u_ref, other, u_other = _reference(pair, velocity)
    c = pair.dundurs_factor(velocity)
    scale = pair.friction * abs(velocity) / (pair.compliance * m * ref.K)
    g_r = 2.0 * _expansion(ref) * scale
    one_conductor = other.K == 0.0
    conv = np.convolve  # coefficients lowest degree first
    if one_conductor:
        # g_r/(z + 1) = c z: a quadratic.
        coef = np.array([g_r, -c, -c])
        k_ratio = rho = g_o = 0.0
        p_o = 0.0
    else:
        g_o = 2.0 * _expansion(other) * scale
        rho = other.K / ref.K
        k_ratio = ref.k / other.k
        p_o = (u_other - u_ref) / (other.k * m)
        w = np.array([1.0 - k_ratio + 1j * p_o, 0.0, k_ratio])
        zp1 = np.array([1.0, 1.0])
        e1 = _padd([g_r], -c * conv(zp1, [rho, 1.0]))
        e0 = _padd(g_o * zp1, [g_r], -c * conv(zp1, _padd(rho * w, [0.0, 1.0])))
        coef = _padd(conv(e0, e0), -conv(w, conv(e1, e1)))
    # Trailing zeros (an exactly cancelled leading coefficient) are no roots.
    nz = np.flatnonzero(np.abs(coef) > 1e-300)
    roots = np.roots(coef[: nz[-1] + 1][::-1]) if nz.size and nz[-1] > 0 else np.array([])

    sqrt = cmath.sqrt  # principal branch, Re >= 0; scalars: a mode takes microseconds
    shift = complex(1.0 - k_ratio, p_o)

    def residual(zz):
        if one_conductor:
            return g_r / (zz + 1.0) - c * zz, -g_r / (zz + 1.0) ** 2 - c
        zo = sqrt(k_ratio * zz * zz + shift)
        f = g_o / (zo + 1.0) + g_r / (zz + 1.0) - c * (rho * zo + zz)
        dzo = k_ratio * zz / zo
        df = -g_o * dzo / (zo + 1.0) ** 2 - g_r / (zz + 1.0) ** 2 - c * (rho * dzo + 1.0)
        return f, df

    found = []
    for zz in roots:
        zz = complex(zz)
        if polish:
            for _ in range(30):
                f, df = residual(zz)
                if df == 0 or not cmath.isfinite(df):
                    break
                step = f / df
                zz -= step
                if abs(step) <= 1e-15 * max(1.0, abs(zz)):
                    break
        if not cmath.isfinite(zz) or zz.real <= 0.0:
            continue
        size = abs(c) * abs(zz) + g_r / abs(zz + 1.0)
        if not one_conductor:
            zo = sqrt(k_ratio * zz * zz + shift)
            if zo.real <= 0.0:
                continue
            size += abs(c) * rho * abs(zo) + g_o / abs(zo + 1.0)
        if abs(residual(zz)[0]) > 1e-8 * size:
            continue  # a root of the squared relation only (z_o of the other sign)
        b = ref.k * m * m * (zz * zz - 1.0) - 1j * m * u_ref
        if all(abs(b - x) > 1e-9 * max(abs(b), ref.k * m * m) for x in found):
            found.append(complex(b))
    found.sort(key=lambda x: (-x.real, x.imag))
    return np.array(found, dtype=complex)


def high_speed_roots(pair: SlidingPair, direction: float = 1.0) -> np.ndarray:
    """The growth rates at infinite speed, ``X = b/(V m)`` (the limit V -> inf, H10).

    With ``b = V m X``, each body's field becomes a one-dimensional transient one
    (``gamma_2 ~ sqrt(V X/(kappa_2 m))``, ``gamma_1 ~ sqrt(V (X + i s)/(kappa_1 m))``,
    ``s = sgn U``) and the relation ``h1/zeta1 + h2/zeta2 = c (e1 zeta1 + e2 zeta2)``,
    ``zeta2 = sqrt(X)``, ``zeta1 = sqrt(X + i s)``, ``h = 2 f alpha (1 + nu)
    sqrt(kappa)/A``, ``e = K/sqrt(kappa)``, no longer depends on ``V``.  Squared, it
    is the cubic ``(X + i s)(h2 - c e2 X)^2 = X (c e1 (X + i s) - h1)^2``.  Each root
    is polished by Newton's method on the unsquared relation in the smaller of
    ``zeta1``, ``zeta2`` (a mode nearly at rest on a body has its ``zeta`` small, and
    ``X`` from the cubic alone would lose the digits of its real part) and kept if
    both ``Re zeta > 0`` and the relation holds to 1e-10.

    Returns
    -------
    ndarray of complex
        The roots ``X`` (none without friction).
    """
    s = math.copysign(1.0, direction)
    c = pair.dundurs_factor(s)
    A = pair.compliance

    def he(mat):
        if mat.K == 0.0:
            return 0.0, 0.0
        root = math.sqrt(mat.k)
        return 2.0 * pair.friction * _expansion(mat) * root / A, mat.K / root

    (h1, e1), (h2, e2) = he(pair.slider), he(pair.counterface)
    if pair.friction == 0.0:
        return np.array([], dtype=complex)
    if e1 == 0.0 or e2 == 0.0:
        # One conductor: zeta = h/(c e), X = zeta^2 (- i s for the slider).
        z = (h1 / (c * e1)) if e2 == 0.0 else (h2 / (c * e2))
        return np.array([z * z - (1j * s if e2 == 0.0 else 0.0)])
    conv = np.convolve  # lowest degree first
    left = conv([1j * s, 1.0], conv([h2, -c * e2], [h2, -c * e2]))
    inner = [c * e1 * 1j * s - h1, c * e1]
    right = conv([0.0, 1.0], conv(inner, inner))
    sqrt = cmath.sqrt
    out = []
    for x in np.roots(_padd(left, -right)[::-1]):
        x = complex(x)
        # u is the smaller zeta; the other is sqrt(u^2 -+ i s).
        first = abs(x + 1j * s) < abs(x)
        shift = -1j * s if first else 1j * s
        u = sqrt(x + 1j * s) if first else sqrt(x)
        for _ in range(60):
            v = sqrt(u * u + shift)
            z1, z2 = (u, v) if first else (v, u)
            f = h1 / z1 + h2 / z2 - c * (e1 * z1 + e2 * z2)
            dv = u / v if v != 0 else 0.0
            dz1, dz2 = (1.0, dv) if first else (dv, 1.0)
            df = (-h1 / z1**2 - c * e1) * dz1 + (-h2 / z2**2 - c * e2) * dz2
            if df == 0 or not cmath.isfinite(df):
                break
            step = f / df
            u -= step
            if abs(step) <= 1e-16 * abs(u):
                break
        v = sqrt(u * u + shift)
        z1, z2 = (u, v) if first else (v, u)
        if z1.real <= 0.0 or z2.real <= 0.0:
            continue
        lhs, rhs = h1 / z1 + h2 / z2, c * (e1 * z1 + e2 * z2)
        if abs(lhs - rhs) > 1e-10 * (abs(lhs) + abs(rhs)):
            continue  # a root of the squared relation only
        # X = zeta2^2 = zeta1^2 - i s: the real part exactly from the smaller zeta.
        X = complex((u * u).real, (z2 * z2).imag) if first else u * u
        if all(abs(X - y) > 1e-12 * max(1.0, abs(X)) for y in out):
            out.append(X)
    return np.array(out, dtype=complex)


def high_speed_limit(pair: SlidingPair, direction: float = 1.0) -> str:
    """What the modes do as ``V -> inf`` at a fixed wavelength (H10): "grows" if a root
    of :func:`high_speed_roots` has ``Re X > 1e-10 |X|`` (a mode grows at every
    large enough speed, at a rate ``~ V m Re X``), "decays" if every root has
    ``Re X < -1e-10 |X|``, else "neutral" (undecided at leading order: identical
    materials put theirs on the imaginary axis, H11b)."""
    X = high_speed_roots(pair, direction)
    tol = 1e-10 * np.maximum(1.0, np.abs(X))
    if np.any(X.real > tol):
        return "grows"
    if np.all(X.real < -tol):
        return "decays"
    return "neutral"


def high_speed_unstable(pair: SlidingPair, direction: float = 1.0) -> bool:
    """Whether a mode grows at every large enough speed (:func:`high_speed_limit`)."""
    return high_speed_limit(pair, direction) == "grows"
