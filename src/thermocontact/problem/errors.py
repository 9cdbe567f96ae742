"""The package's exceptions and warnings, importable without NumPy (the command line
names them before it needs any numerics)."""

from .validation import InputError

__all__ = ["ConvergenceWarning", "InputError", "SolveError"]


class SolveError(RuntimeError):
    """The discrete problem has no (unique, well-conditioned) solution."""


class ConvergenceWarning(UserWarning):
    """A result whose error estimate misses its target."""
