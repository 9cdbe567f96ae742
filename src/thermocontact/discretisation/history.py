"""The transient contact's history operators: element responses per time step.

Equal elements of width ``h`` on a fixed window (units of the Hertz half-width ``l``)
carry, over each time step ``dt`` (units ``l^2/kappa2``), a constant heat flux.  The
surface temperature and displacement at the end of step ``n`` caused by the flux of
step ``n - m`` at an element ``d`` places away is the impulse response of
:mod:`thermocontact.physics.impulse_responses` integrated over the element and over
the step (derivation section 19, eq. R7):

    A[d, m] = integral_{m dt}^{(m+1) dt} E(X_d, tau) d tau,     X_d = d h,

a table Toeplitz in the elements and in time.  With ``tau = sigma^2`` both integrands
are bounded and smooth in ``sigma``; each step is cut into panels over which the
convected pulse moves by at most a quarter of its width (``max(h, 2 sqrt(r tau))``),
and the first into panels graded geometrically toward ``tau = 0``; 12-point
Gauss-Legendre on each.  Their sums over all steps are the steady element integrals of
:mod:`thermocontact.solvers.elements` (section 14b) up to the stationary half-plane's
diverging constants (R3).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .element_operators import ElementOperators, flamant_operator
from ..numerics.cache import BoundedCache
from ..numerics.online_convolution import OnlineConvolution
from ..physics.impulse_responses import element_displacement, element_temperature_sigma

__all__ = ["HeatHistory", "SpatialConvolution", "TABLES", "TransientOperators", "body_rates",
           "lag_tables", "toeplitz", "transient_element_operators"]

#: The lag tables computed, by their inputs (a run and its resumption share them); the
#: largest a run makes (3e6 steps x elements) holds about 100 MB per body.
TABLES = BoundedCache("lag tables", 512 * 2**20)

_GL_X, _GL_W = np.polynomial.legendre.leggauss(12)
#: Geometric panels of the first step toward ``tau = 0`` (ratio 2): to ``2^-40`` of its
#: ``sqrt(dt)``, where every integrand is at its limit to rounding.
_GRADED = 40
#: Offsets per block (bounds the ``(offsets, nodes)`` arrays).
_BLOCK = 1 << 18


def _panels(m, dt, h, r, s):
    """Edges in ``sigma`` of the panels of step ``m`` (``tau`` in ``[m dt, (m+1) dt]``)."""
    a, b = np.sqrt(m * dt), np.sqrt((m + 1) * dt)
    width = max(h, 2.0 * np.sqrt(r * m * dt))
    count = 1 + int(np.ceil(abs(s) * dt / (0.25 * width)))
    if m > 0:
        return np.linspace(a, b, count + 1)
    graded = b * 2.0 ** -np.arange(_GRADED, 0, -1)
    uniform = np.linspace(0.0, b, count + 1)[1:]
    return np.unique(np.concatenate([[0.0], graded[graded < uniform[0]], uniform]))


def _integrate(X, panels, h, r, s):
    """Temperature and displacement of offsets ``X`` integrated over the ``sigma`` panels
    of each of several steps (``panels``: their edges, one array per step): arrays of
    shape ``(X.size, len(panels))``.  The steps' nodes are evaluated together (a long
    run's steps have a few nodes each, which one at a time would cost Python's overhead
    per step), each step's sum taken over its own nodes."""
    sig, wts, starts = [], [], [0]
    for edges in panels:
        lo, hi = edges[:-1], edges[1:]
        half = 0.5 * (hi - lo)
        starts.append(starts[-1] + _GL_X.size * lo.size)
        sig.append(((0.5 * (hi + lo))[:, None] + half[:, None] * _GL_X[None, :]).ravel())
        wts.append((half[:, None] * _GL_W[None, :]).ravel())
    sig, wts, starts = np.concatenate(sig), np.concatenate(wts), starts[:-1]
    T = np.empty((X.size, len(panels)))
    W = np.empty((X.size, len(panels)))
    step = max(1, _BLOCK // sig.size)
    for k in range(0, X.size, step):
        Xb = X[k:k + step, None]
        T[k:k + step] = np.add.reduceat(element_temperature_sigma(Xb, sig[None, :], h, r, s)
                                        * wts, starts, axis=1)
        W[k:k + step] = np.add.reduceat(element_displacement(Xb, (sig * sig)[None, :], h, r, s)
                                        * (2.0 * sig * wts)[None, :], starts, axis=1)
    return T, W


def lag_tables(elements: int, h: float, dt: float, steps: int, r: float = 1.0, s: float = 0.0,
               progress=None):
    """The tables (R7) of one body for offsets ``d = -(N-1) .. N-1`` and lags ``0 .. steps-1``.

    ``progress(done, steps)`` after each lag computed (a long run's tables take
    minutes: 100 000 steps, or 4000 elements); kept in :data:`TABLES`.

    Returns
    -------
    temperature, displacement : ndarray, shape (2N - 1, steps)
        Times ``E/(pi K)`` and ``delta E`` per unit element-flux and step: the
        temperature rise and outward displacement at an element's centre at the end of a
        step, from a unit flux over the step ``m`` steps before on the element ``d``
        places before it (``d = i - j``: the source at smaller x for ``d > 0``, which is
        downstream of the cylinder's surface, moving toward -x).  Read-only (cached).
    """
    key = (int(elements), float(h), float(dt), int(steps), float(r), float(s))
    return TABLES.get(key, lambda: _tables(*key, progress))


def _tables(elements, h, dt, steps, r, s, progress):
    X = h * np.arange(-(elements - 1), elements, dtype=float)
    T = np.empty((X.size, steps))
    W = np.empty((X.size, steps))
    m = 0
    while m < steps:
        # Steps together until their nodes times the offsets fill a block (at least one).
        panels, entries = [], 0
        while m + len(panels) < steps and (not panels or entries < _BLOCK):
            panels.append(_panels(m + len(panels), dt, h, r, s))
            entries += 12 * (panels[-1].size - 1) * X.size
        T[:, m:m + len(panels)], W[:, m:m + len(panels)] = _integrate(X, panels, h, r, s)
        m += len(panels)
        if progress is not None:
            progress(m, steps)
    T.flags.writeable = False
    W.flags.writeable = False
    return T, W


def toeplitz(column, elements):
    """``M[i, j] = column[i - j + N - 1]``: a table's lag as the elements' matrix."""
    i = np.arange(elements)
    return column[i[:, None] - i[None, :] + elements - 1]


class SpatialConvolution:
    """The elements' Toeplitz products by real FFT: ``y_i = sum_j k[i - j + N - 1] x_j``."""

    def __init__(self, elements):
        self.elements = elements
        self.size = 1 << int(np.ceil(np.log2(3 * elements - 2)))

    def kernel(self, table):
        """Transform of a table (offsets along axis 0)."""
        return np.fft.rfft(table, n=self.size, axis=0)

    def forward(self, x):
        return np.fft.rfft(x, n=self.size, axis=-1)

    def backward(self, y):
        N = self.elements
        return np.fft.irfft(y, n=self.size, axis=-1)[..., N - 1:2 * N - 1]


def body_rates(par):
    """Each body's diffusivity ratio ``r = kappa/kappa2`` and convection speed
    ``s = v l/kappa2`` in the transient's units: the cylinder ``(k1/k2, 2 Pe_l)``, the
    stationary half-plane ``(1, 0)``."""
    return (par.pe / par.cylinder_scale, 2.0 * par.pe), (1.0, 0.0)


@dataclass(frozen=True)
class TransientOperators:
    """The transient contact's operators on a window of equal elements (eq. R8).

    Attributes
    ----------
    current : ElementOperators
        The step's own response (lag 0) with Flamant's: the matrices of the step's
        linear system.
    kernels : tuple of ndarray
        Per body, shape ``(steps, 2, 1, modes)``: the lags' responses (gap, then that
        body's temperature rise) in the spatial Fourier variable of ``convolution``,
        for :class:`thermocontact.numerics.online_convolution.OnlineConvolution`.
    convolution : SpatialConvolution
    """

    current: ElementOperators
    kernels: tuple
    convolution: SpatialConvolution


class HeatHistory:
    """The heat both bodies took at the steps before the current one, and what it leaves
    on the elements at the current step: the lag sums of eq. R8, ``sum_{m >= 1}
    A[., m] q[n - m]``, by online convolution in time and FFT in space.

    Parameters
    ----------
    operators : TransientOperators
        The lags' responses (``kernels``) and the elements' convolution.
    """

    def __init__(self, operators: TransientOperators):
        self.convolution = operators.convolution
        self._bodies = [OnlineConvolution(k) for k in operators.kernels]

    def known(self, n: int) -> tuple:
        """Each body's gap and temperature rise at step ``n`` from the steps before it:
        two arrays of shape ``(2, elements)`` (gap, then temperature)."""
        return tuple(self.convolution.backward(body.history(n)) for body in self._bodies)

    def skip(self, n: int) -> None:
        """Step ``n``'s history formed and not evaluated (a step taken as it was)."""
        for body in self._bodies:
            body.history(n)

    def push(self, q1, q2) -> None:
        """Record each body's heat (per element, shape ``(elements,)``) at the current
        step, after its :meth:`known` or :meth:`skip`."""
        for body, q in zip(self._bodies, (q1, q2)):
            body.push(self.convolution.forward(q)[None, :])


def transient_element_operators(par, X, h, dt, steps, progress=None) -> TransientOperators:
    """Operators of ``steps`` steps of ``dt`` on elements of width ``h`` centred at ``X``
    (a stationary half-plane without the Dundurs term; ``par`` in units of ``l``);
    ``progress(done, 2 steps + 3)`` over both bodies' lag tables (:func:`lag_tables`),
    a unit per lag, then a unit for each body's current matrices and one for
    Flamant's."""
    N = X.size
    F, d, rho = par.fhpe, par.delta1_over_delta2, par.K2_over_K1
    conv = SpatialConvolution(N)
    gaps, thetas, kernels = [], [], []
    total = 2 * steps + 3

    def told(done):
        if progress is not None:
            progress(done, total)
    for body, ((r, s), distort, conduct) in enumerate(zip(body_rates(par), (d, 1.0),
                                                          (rho, 1.0))):
        before = body * (steps + 1)
        T, W = lag_tables(N, float(h), float(dt), int(steps), float(r), float(s),
                          lambda done, _, before=before: told(before + done))
        gap = -np.pi * F * distort * W
        theta = conduct * T
        gaps.append(toeplitz(gap[:, 0], N))
        thetas.append(toeplitz(theta[:, 0], N))
        both = np.stack([conv.kernel(gap), conv.kernel(theta)], axis=0)   # (2, modes, steps)
        kernels.append(np.ascontiguousarray(np.transpose(both, (2, 0, 1))[:, :, None, :]))
        told(before + steps + 1)
    current = ElementOperators(flamant_operator(X, h), gaps[0], gaps[1], thetas[0], thetas[1])
    told(total)
    return TransientOperators(current, tuple(kernels), conv)
