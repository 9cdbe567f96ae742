"""A second method for the sliding half-planes' instability: a discretisation in depth.

Each conducting body's temperature amplitude ``T(eta)`` (``eta`` the depth below its
surface) is collocated at Chebyshev–Lobatto points of ``xi`` in ``[-1, 1]`` mapped
onto the whole depth, ``eta = l (1 + xi)/(1 - xi)`` (``xi = 1`` is ``eta = inf``,
where ``T = 0``).  The heat equation with convection (H1), temperature continuity
and the heat balance at the interface (H5), with the pressure given by the contact
condition (H6) and each body's thermal displacement by Maysel's integral
``2 alpha (1 + nu) int T e^{-m eta} d eta`` (D3; Clenshaw–Curtis weights), make a
linear generalised eigenproblem ``L x = b M x`` for the growth rate ``b``.

It shares nothing with the root search of :mod:`thermocontact.physics.tei` but the
material constants: neither the closed-form kernels (H3, H4) nor the polynomial
(H8).  Its eigenvalues converge spectrally in the number of points; the continuous
spectrum (``Re b <= -kappa m^2``) appears as a cloud of eigenvalues to be ignored.
"""

from __future__ import annotations


import numpy as np
import scipy.linalg

from ..physics.tei import SlidingPair

__all__ = ["depth_modes"]


def _chebyshev(n):
    """Lobatto points ``cos(pi j/n)`` (1 first), differentiation matrix and
    Clenshaw–Curtis weights on ``[-1, 1]``."""
    j = np.arange(n + 1)
    x = np.cos(np.pi * j / n)
    c = np.where((j == 0) | (j == n), 2.0, 1.0) * (-1.0) ** j
    dx = x[:, None] - x[None, :]
    d = np.outer(c, 1.0 / c) / (dx + np.eye(n + 1))
    d -= np.diag(d.sum(axis=1))
    # Clenshaw–Curtis (Trefethen, Spectral Methods in MATLAB, clencurt).
    theta = np.pi * j / n
    w = np.zeros(n + 1)
    v = np.ones(n - 1)
    if n % 2 == 0:
        w[0] = w[n] = 1.0 / (n * n - 1)
        for k in range(1, n // 2):
            v -= 2.0 * np.cos(2 * k * theta[1:-1]) / (4 * k * k - 1)
        v -= np.cos(n * theta[1:-1]) / (n * n - 1)
    else:
        w[0] = w[n] = 1.0 / (n * n)
        for k in range(1, (n - 1) // 2 + 1):
            v -= 2.0 * np.cos(2 * k * theta[1:-1]) / (4 * k * k - 1)
    w[1:-1] = 2.0 * v / n
    return x, d, w


def depth_modes(pair: SlidingPair, wavenumber, velocity, n=48):
    """Growth rates ``b`` (1/s, counterface frame) of the discretised problem.

    Parameters
    ----------
    pair : SlidingPair
    wavenumber : float
        ``m > 0``, 1/m.
    velocity : float
        The slider's signed velocity ``U``, m/s.
    n : int, optional
        Chebyshev intervals per conducting body.

    Returns
    -------
    ndarray of complex
        The finite eigenvalues, by decreasing real part (the rightmost are the
        modes; those with ``Re b <= -kappa m^2`` approximate the continuous spectrum).
    """
    m = float(wavenumber)
    x, d, w = _chebyshev(n)
    bodies = [(mat, u) for mat, u in ((pair.slider, velocity), (pair.counterface, 0.0))
              if mat.K > 0.0]
    size = (n + 1) * len(bodies)
    L = np.zeros((size, size), dtype=complex)
    M = np.zeros((size, size))
    speed = abs(velocity)
    c = pair.dundurs_factor(velocity)
    surface = []       # (index of the surface point, K, its derivative row)
    pressure = np.zeros(size, dtype=complex)  # P = pressure @ T
    for i, (mat, u) in enumerate(bodies):
        o = i * (n + 1)
        # Between the depth scales 1/m and sqrt(kappa/(m V)) of the fields.
        ell = 1.0 / (m * (1.0 + speed / (mat.k * m)) ** 0.25)
        with np.errstate(divide="ignore"):
            jac = (1.0 - x) ** 2 / (2.0 * ell)             # d xi / d eta
            eta = ell * (1.0 + x) / (1.0 - x)
        d1 = jac[:, None] * d
        d2 = d1 @ d1
        op = mat.k * (d2 - m * m * np.eye(n + 1)) - 1j * m * u * np.eye(n + 1)
        L[o + 1:o + n, o:o + n + 1] = op[1:n]
        M[o + 1:o + n, o + 1:o + n] = np.eye(n - 1)
        L[o, o] = 1.0                                      # T = 0 at infinite depth
        weights = np.zeros(n + 1)
        weights[1:] = w[1:] * np.exp(-m * eta[1:]) / jac[1:]   # d eta = d xi / jac
        # (H6): P = (2 m/(A c)) sum alpha (1 + nu) int T e^{-m eta} d eta.
        pressure[o:o + n + 1] = (2.0 * m / (pair.compliance * c)
                                 * mat.alpha * (1.0 + mat.nu) * weights)
        surface.append((o + n, mat.K, d1[n]))
    # Heat balance (H5): sum over bodies of -K dT/d eta at the surface = f V P.
    flux_row = surface[-1][0]
    row = np.zeros(size, dtype=complex)
    for i, (idx, K, deriv) in enumerate(surface):
        o = i * (n + 1)
        row[o:o + n + 1] -= K * deriv
    row -= pair.friction * speed * pressure
    L[flux_row] = row
    if len(surface) == 2:                                  # equal surface temperatures
        L[surface[0][0], surface[0][0]] = 1.0
        L[surface[0][0], surface[1][0]] = -1.0
    b = scipy.linalg.eigvals(L, M)
    b = b[np.isfinite(b)]
    return b[np.argsort(-b.real, kind="stable")]
