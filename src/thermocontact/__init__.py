"""thermocontact: steady thermoelastic sliding contact with frictional heating.

A heat-conducting elastic cylinder slides over a stationary heat-conducting elastic
half-plane; frictional heat distorts both surfaces.  :func:`solve` returns the
contact's load ratio, offset, heat partition, pressure and heat-flux
distributions and the validity of the single-patch solution.
"""

from ._version import __version__
from .discretisation import paper_collocation as _collocation  # noqa: F401  (registers "paper")
from .discretisation import product_integration as _product  # noqa: F401  (registers "product")
from .discretisation import edge_graded_methods as _graded  # noqa: F401  (registers "graded")
from .discretisation.system import METHODS
from .problem.parameters import InputError, Parameters, SolveError
from .solvers.single_patch import ContactSolution, solve
from .analysis.validity import Validity

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
