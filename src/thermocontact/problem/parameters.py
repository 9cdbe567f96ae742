"""Dimensionless parameters of the problem, validated on construction."""

from __future__ import annotations

from dataclasses import dataclass

from .validation import InputError, check_nonnegative, check_positive

__all__ = ["ConvergenceWarning", "Parameters", "SolveError"]


#: Range of c = Pe k2/k1.  Above C_MAX the cylinder's kernels are narrower than any
#: discretisation here resolves; below C_MIN they are constant to rounding (the
#: problem is its limit c -> 0, reached to 1e-16 by c = 1e-16) and products with c
#: would underflow.
C_MAX = 1e9
C_MIN = 1e-100


class SolveError(RuntimeError):
    """The discrete problem has no (unique, well-conditioned) solution."""


class ConvergenceWarning(UserWarning):
    """A result whose error estimate misses its target."""


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

    Notes
    -----
    Derived groups used by the equations (derivation section 5):
    ``c = Pe k2/k1``, the scale of the cylinder's kernels, and
    ``eta = (1 - K2/K1) / (1 + K2/K1)``, the share of the pressure in the heat-flux
    difference that removes the Cauchy part of the heat equation's pressure term.
    """

    pe: float
    fhpe: float
    K2_over_K1: float
    k2_over_k1: float | None = None
    delta1_over_delta2: float = 1.0

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
        c = self.pe * self.k2_over_k1
        if not C_MIN <= c <= C_MAX:
            raise InputError(
                f"pe * k2_over_k1 (the cylinder's kernel scale c) must be in "
                f"[{C_MIN:.0e}, {C_MAX:.0e}], got {c:.3g} (pe = {self.pe:.3g}, "
                f"k2_over_k1 = {self.k2_over_k1:.3g})")

    @property
    def cylinder_scale(self) -> float:
        """``c = Pe k2/k1``: the cylinder kernels' argument is ``c (s - r)``."""
        return self.pe * self.k2_over_k1

    @property
    def eta(self) -> float:
        """``eta = (1 - K2/K1)/(1 + K2/K1)`` (corrected eq. 23; derivation D17)."""
        rho = self.K2_over_K1
        return (1.0 - rho) / (1.0 + rho)
