"""The registry of discretisation methods: a representation and a scheme each.

A :class:`Method` is a record: its name, how it represents the unknowns, whether
it collocates or projects the equations, the range of its automatic ``n`` and a
one-line summary (from which the command line's help is made).  Tests and
benchmarks are parametrised over :data:`METHODS`.
"""

from __future__ import annotations

from importlib import import_module
from typing import TYPE_CHECKING, NamedTuple

from ..problem.validation import InputError

if TYPE_CHECKING:  # the registry is read (for the command line's help) without NumPy
    from ..problem.parameters import Parameters
    from .system import Blocks

__all__ = ["DEFAULT_METHOD", "DEFAULT_TOL", "METHODS", "Method"]


# A NamedTuple, not a frozen dataclass: the registry is read for the command line's
# help, which dataclasses (its import and its generated methods) would slow by 2-3 ms.
class Method(NamedTuple):
    """One discretisation method (an immutable record).

    Attributes
    ----------
    name : str
    representation_name : str
        The name of a :class:`~.representations.Representation` subclass, available
        as :attr:`representation`.
    scheme : {"collocation", "projection"}
    auto_range : tuple of int
        First and largest ``n`` of the automatic doubling.
    summary : str
        One line for the documentation and the command line's help.
    order_cap : float
        The largest convergence order the Richardson error estimate believes.
    estimate_is_bound : bool
        Whether the error estimate bounds the error on the cases benchmarked; where
        it does not, no result of the method claims convergence.
    """

    name: str
    representation_name: str
    scheme: str
    auto_range: tuple
    summary: str
    order_cap: float = 5.0
    estimate_is_bound: bool = True

    @property
    def representation(self) -> type:
        """The :class:`~.representations.Representation` subclass (imported on first use)."""
        return getattr(import_module(".representations", __package__), self.representation_name)

    @property
    def edge_exponents(self) -> bool:
        """Whether the representation carries edge exponents other than 1/2 (the
        Dundurs term, derivation section 5c)."""
        return self.representation_name == "EdgeGraded"

    def check(self, par: Parameters) -> None:
        """Refuse parameters the method cannot represent."""
        if par.edge_exponent != 0.5 and not self.edge_exponents:
            raise InputError(f"beta_f != 0 needs the edge exponents it makes in the "
                             f"pressure (method graded or graded-collocation), got "
                             f"method {self.name!r}", parameters=("beta_f", "method"))

    def assemble(self, par: Parameters, n: int) -> Blocks:
        """The method's blocks for ``par`` (``fhpe`` not used) with ``n`` unknowns per function."""
        self.check(par)
        rep = (self.representation(n, par.edge_exponent) if self.edge_exponents
               else self.representation(n))
        from .system import assemble

        return assemble(par, rep, self.scheme)

    __call__ = assemble


#: Automatic n of the graded methods: from 8, and at most 256, beyond which the
#: rounding of the edge values of phi (about n^7, derivation section 12) passes 1e-7.
_GRADED_RANGE = (8, 256)
_CHEBYSHEV_RANGE = (16, 1024)
#: The Chebyshev methods converge at order 4 (derivation section 10); their estimate
#: believes at most 3, so that it stays above the error before the asymptotic range
#: (Pe = 1000, K2/K1 = 100: true 1.5e-8 where order 5 estimated 7e-9) and within a
#: factor of about 2 of it once there.
_CHEBYSHEV_ORDER = 3.0

#: Every solution method by name: ``"graded"``, ``"graded-collocation"``, ``"galerkin"``,
#: ``"product"`` and ``"paper"`` (the paper's scheme, kept for comparison).
METHODS: dict[str, Method] = {m.name: m for m in (
    Method("graded", "EdgeGraded", "projection", _GRADED_RANGE,
           "edge-graded cosine series, every integral a moment, equations projected "
           "(the default; derivation section 12)"),
    Method("graded-collocation", "EdgeGraded", "collocation", _GRADED_RANGE,
           "the same representation, equations collocated"),
    Method("galerkin", "Chebyshev", "projection", _CHEBYSHEV_RANGE,
           "Chebyshev series with exact kernel moments, equations projected "
           "(order 4; section 10)", order_cap=_CHEBYSHEV_ORDER),
    Method("product", "Chebyshev", "collocation", _CHEBYSHEV_RANGE,
           "Chebyshev series with exact kernel moments, collocated (product integration)",
           order_cap=_CHEBYSHEV_ORDER),
    Method("paper", "ChebyshevSampled", "collocation", _CHEBYSHEV_RANGE,
           "the paper's scheme: kernels sampled at Gauss-Chebyshev nodes (first order at "
           "best, erratic at high Pe: its error estimate is no bound; section 6)",
           order_cap=1.0, estimate_is_bound=False),
)}

#: The method used unless another is asked for (derivation section 12).
DEFAULT_METHOD = "graded"

#: Target of the error estimate of ``P_H/P`` and ``sigma/Delta`` when ``n`` is chosen.
DEFAULT_TOL = 1e-8
