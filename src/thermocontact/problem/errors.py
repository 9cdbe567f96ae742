"""The package's exceptions and warnings, importable without NumPy (the command line
names them before it needs any numerics).

Every error the package raises on purpose derives from :class:`Error`::

    Error
    ├── InputError        a parameter outside its allowed range (ValueError)
    │   ├── MaterialError   a material that cannot be found, read or accepted
    │   └── FileError       a file that cannot be read or written
    ├── SolveError        the discrete problem has no (unique, well-conditioned)
    │   │                 solution (RuntimeError)
    │   └── NotConvergedError  an iteration did not converge within its budget
    └── ExecutionError    the executor failed; finished work is kept (RuntimeError)

Messages name the parameters as the Python API spells them (``K2_over_K1``); a front
end (the command line) names them as its users do, from :attr:`InputError.parameters`.
"""

__all__ = ["ConvergenceWarning", "Error", "ExecutionError", "FileError", "InputError",
           "NotConvergedError", "SolveError"]


class Error(Exception):
    """The root of every error the package raises on purpose: catch it to catch them
    all (a defect of the package is any other exception)."""


class InputError(Error, ValueError):
    """A parameter outside its allowed range; the message names both.

    Parameters
    ----------
    message : str
        One line, naming the parameters as the Python API spells them, the value given
        and the allowed range.
    parameters : tuple of str
        The parameters the message names, so that a front end (the command line)
        can name them as its users spell them (``K2_over_K1`` as ``--K2-over-K1``).
    """

    def __init__(self, message, *, parameters=()):
        super().__init__(message)
        self.parameters = tuple(parameters)

    def __reduce__(self):  # the parameters survive a trip to a worker process
        return (_input_error, (type(self), str(self), self.parameters))


def _input_error(cls, message, parameters):
    return cls(message, parameters=parameters)


class FileError(InputError):
    """A file that cannot be read or written (missing, not of the package's kind, a
    full disk, a folder in the way): one line naming the file and the reason."""


class SolveError(Error, RuntimeError):
    """The discrete problem has no (unique, well-conditioned) solution."""


class NotConvergedError(SolveError):
    """An iteration (Newton's method, an active set, a fixed point) did not converge
    within its budget of steps."""


class ExecutionError(Error, RuntimeError):
    """The executor failed (a worker died, the scheduler was lost): the finished
    tasks are kept, the rest can be run again."""


class ConvergenceWarning(UserWarning):
    """A result whose error estimate misses its target."""
