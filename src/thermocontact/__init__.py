"""thermocontact: steady thermoelastic sliding contact with frictional heating.

A heat-conducting elastic cylinder slides over a stationary heat-conducting elastic
half-plane; frictional heat distorts both surfaces.  :func:`solve` (or
:class:`Model` for many solves that share an assembly) returns the contact's load
ratio, offset, heat partition, pressure and heat-flux distributions and the
validity of the single-patch solution.
"""

from ._version import __version__
from .analysis.validity import Validity
from .discretisation.methods import DEFAULT_METHOD, METHODS, Method
from .numerics.cache import clear_caches
from .problem.parameters import ConvergenceWarning, Parameters, SolveError
from .problem.validation import InputError
from .solvers.result import ContactSolution
from .solvers.single_patch import Model, solve

__all__ = [
    "DEFAULT_METHOD",
    "METHODS",
    "ContactSolution",
    "ConvergenceWarning",
    "InputError",
    "Method",
    "Model",
    "Parameters",
    "SolveError",
    "Validity",
    "clear_caches",
    "solve",
    "__version__",
]
