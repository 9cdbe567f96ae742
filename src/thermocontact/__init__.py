"""thermocontact: steady thermoelastic sliding contact with frictional heating.

A heat-conducting elastic cylinder slides over a stationary heat-conducting elastic
half-plane; frictional heat distorts both surfaces.  :func:`solve` returns the
contact's load ratio, offset, heat partition, pressure and heat-flux
distributions and the validity of the single-patch solution.
"""

from ._version import __version__
from . import collocation as _collocation  # noqa: F401  (registers "paper")
from . import product as _product  # noqa: F401  (registers "product")
from . import graded_methods as _graded  # noqa: F401  (registers "graded")
from .assembly import METHODS
from .parameters import InputError, Parameters, SolveError
from .solver import ContactSolution, solve
from .validity import Validity

__all__ = [
    "METHODS",
    "ContactSolution",
    "InputError",
    "Parameters",
    "SolveError",
    "Validity",
    "solve",
    "__version__",
]
