"""Dimensionless parameters of the problem, validated on construction."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .errors import ConvergenceWarning, SolveError
from .validation import InputError, check_finite, check_nonnegative, check_positive

__all__ = ["ConvergenceWarning", "DISTORTIVITY_RATIO_LIMIT", "DISTORTIVITY_RATIO_MAX",
           "Parameters", "SolveError", "check_moving_half_plane"]


#: Range of c = Pe k2/k1.  Above C_MAX the cylinder's kernels are narrower than any
#: discretisation here resolves; below C_MIN they are constant to rounding (the
#: problem is its limit c -> 0, reached to 1e-16 by c = 1e-16) and products with c
#: would underflow.
C_MAX = 1e9
C_MIN = 1e-100
#: Largest |beta f|: beta is at most 1 in magnitude for real materials (twice
#: Dundurs' constant in magnitude, |beta_D| <= 1/2) and f rarely exceeds 1; at 20 the edge
#: exponents are 0.984 and 0.016.
B_MAX = 20.0
#: Largest distortivity ratio delta1/delta2 of a contact set (``zones``) and of a
#: transient contact.  The materials in the library span 550 (copper against an
#: organic brake block); the cylinder's distortion, ~ delta1 Q1 + delta2 Q2, grows with
#: the ratio as fHPe_l does, so that beyond 1e3 a path from Hertz's zone crosses ever
#: more of its branch.  (The single patch takes any ratio its materials make: a polymer
#: cylinder on steel makes thousands; a dimensionless path or map, up to
#: :data:`DISTORTIVITY_RATIO_LIMIT`.)
DISTORTIVITY_RATIO_MAX = 1e3
#: Largest delta1/delta2 given as a dimensionless input (a path's ends, a map's
#: corners), as lam's 1e6: a path to 1e300 sampled hundreds of decades for minutes.
DISTORTIVITY_RATIO_LIMIT = 1e6


def check_moving_half_plane(speed_ratio, pe, fhpe, *, names=("pe", "fhpe")) -> float:
    """``speed_ratio`` checked against the Peclet number and the coupling it meets: finite;
    the half-plane's kernel scale ``|speed_ratio| pe`` 0 or in ``[C_MIN, C_MAX]`` (not
    checked with ``pe`` None); and 1 (pure rolling, no frictional heat) only with
    ``fhpe = 0``.  ``names``: how the caller calls ``pe`` and ``fhpe`` (``pe_hertz``,
    ``fhpe_hertz`` for a contact set)."""
    speed_ratio = check_finite("speed_ratio", speed_ratio)
    pe_name, fhpe_name = names
    if pe is not None:
        c2 = abs(speed_ratio) * pe
        if c2 != 0.0 and not C_MIN <= c2 <= C_MAX:
            raise InputError(
                f"|speed_ratio| * {pe_name} (the half-plane's kernel scale) must be 0 or in "
                f"[{C_MIN:.0e}, {C_MAX:.0e}], got {c2:.3g} ({pe_name} = {pe:.3g}, "
                f"speed_ratio = {speed_ratio:.3g})", parameters=("speed_ratio", pe_name))
    if speed_ratio == 1.0 and fhpe > 0.0:
        raise InputError(f"speed_ratio 1 is pure rolling, which makes no frictional heat: "
                         f"{fhpe_name} must be 0 there, got {fhpe:g}",
                         parameters=("speed_ratio", fhpe_name))
    return speed_ratio


@dataclass(frozen=True)
class Parameters:
    """The dimensionless groups of the sliding-contact problem.

    Parameters
    ----------
    pe : float
        Peclet number ``Pe = v Delta / (2 k2)`` of the half-plane, > 0.
    fhpe : float
        Thermoelastic coupling ``f H Pe`` (Barber's ``a beta``), >= 0, with
        ``H = k2 delta2 / A`` and ``A = (1 - nu1)/mu1 + (1 - nu2)/mu2``.
    K2_over_K1 : float
        Conductivity ratio, > 0.
    k2_over_k1 : float, optional
        Diffusivity ratio, > 0; defaults to ``K2_over_K1`` (equal volumetric heat
        capacities, the paper's choice for all its results).
    delta1_over_delta2 : float, optional
        Distortivity ratio ``delta1/delta2 >= 0``; 0 is a cylinder that does not
        distort.  Default 1.
    speed_ratio : float, optional
        ``R = v2/v1``: the half-plane's surface speed through the contact over the
        cylinder's, positive in the same direction (derivation section 5b); 0, the
        default, is the paper's stationary half-plane.  Any real number but 1
        with ``fhpe > 0`` (pure rolling makes no frictional heat).
    beta_f : float, optional
        ``B = beta f``, with the paper's ``beta`` of eq. 10 (in magnitude twice
        Dundurs' second constant): the coupling of the friction traction to the normal displacement,
        the free term ``-(B/2) p`` of the contact equation (derivation section 5c).
        0, the default, drops it as the paper does.  ``|B| <= 20``.

    Notes
    -----
    Derived groups used by the equations (derivation sections 5, 5b):
    ``c = Pe k2/k1``, the scale of the cylinder's kernels; ``c2 = R Pe``, the signed
    scale of the moving half-plane's; and ``eta = (1 - K2/K1) / (1 + K2/K1)``, the
    share of the pressure in the heat-flux difference that removes the Cauchy part
    of the heat equation's pressure term.  ``Pe = v1 Delta/(2 k2)`` is made with
    the cylinder's surface speed and ``fHPe = f H |v1 - v2| Delta/(2 k2)`` with the
    sliding speed, which makes the heat, so both are today's at ``R = 0``.
    """

    pe: float
    fhpe: float
    K2_over_K1: float
    k2_over_k1: float | None = None
    delta1_over_delta2: float = 1.0
    speed_ratio: float = 0.0
    beta_f: float = 0.0

    def __post_init__(self):
        object.__setattr__(self, "pe", check_positive("pe", self.pe))
        object.__setattr__(self, "fhpe", check_nonnegative("fhpe", self.fhpe))
        object.__setattr__(
            self, "K2_over_K1", check_positive("K2_over_K1", self.K2_over_K1)
        )
        k = self.K2_over_K1 if self.k2_over_k1 is None else self.k2_over_k1
        object.__setattr__(self, "k2_over_k1", check_positive("k2_over_k1", k))
        object.__setattr__(
            self,
            "delta1_over_delta2",
            check_nonnegative("delta1_over_delta2", self.delta1_over_delta2),
        )
        object.__setattr__(self, "speed_ratio",
                           check_moving_half_plane(self.speed_ratio, self.pe, self.fhpe))
        object.__setattr__(self, "beta_f", check_finite("beta_f", self.beta_f))
        if abs(self.beta_f) > B_MAX:
            raise InputError(f"beta_f must be in [-{B_MAX:g}, {B_MAX:g}], got {self.beta_f:g}",
                             parameters=("beta_f",))
        c = self.pe * self.k2_over_k1
        if not C_MIN <= c <= C_MAX:
            raise InputError(
                f"pe * k2_over_k1 (the cylinder's kernel scale c) must be in "
                f"[{C_MIN:.0e}, {C_MAX:.0e}], got {c:.3g} (pe = {self.pe:.3g}, "
                f"k2_over_k1 = {self.k2_over_k1:.3g})")

    def _check_rolling(self):
        check_moving_half_plane(self.speed_ratio, None, self.fhpe)

    def with_fhpe(self, fhpe) -> "Parameters":
        """These parameters at another ``fhpe``: ``dataclasses.replace(self, fhpe=fhpe)``
        with only the checks that involve ``fhpe`` run again (the others do not change
        along a grid line)."""
        new = object.__new__(Parameters)
        new.__dict__.update(self.__dict__, fhpe=check_nonnegative("fhpe", fhpe))
        new._check_rolling()
        return new

    @property
    def cylinder_scale(self) -> float:
        """``c = Pe k2/k1``: the cylinder kernels' argument is ``c (s - r)``."""
        return self.pe * self.k2_over_k1

    @property
    def half_plane_scale(self) -> float:
        """``c2 = R Pe``, signed: the moving half-plane's kernels' argument is
        ``c2 (s - r)``; 0 for the stationary half-plane."""
        return self.speed_ratio * self.pe

    @property
    def free_term(self) -> float:
        """``b = (B/2) sgn(v1 - v2)``: the coefficient of ``-p`` in the contact equation
        (D14d); the friction on the cylinder points along ``sgn(v1 - v2)``."""
        return 0.5 * self.beta_f * float(np.sign(1.0 - self.speed_ratio))

    @property
    def edge_exponent(self) -> float:
        """``alpha = 1/2 + arctan(b)/pi``: the pressure vanishes as ``(1 - s)^alpha`` at
        the leading edge and ``(1 + s)^(1 - alpha)`` at the trailing one (D14e)."""
        b = self.free_term
        return 0.5 + float(np.arctan(b)) / np.pi if b else 0.5

    @property
    def eta(self) -> float:
        """``eta = (1 - K2/K1)/(1 + K2/K1)`` (corrected eq. 23; derivation D17)."""
        rho = self.K2_over_K1
        return (1.0 - rho) / (1.0 + rho)
