"""A second method for the thermoelastic instability: discretisations in depth.

:func:`depth_modes`, for two sliding half-planes: each conducting body's temperature
amplitude ``T(eta)`` (``eta`` the depth below its surface) is collocated at
Chebyshev–Lobatto points of ``xi`` in ``[-1, 1]`` mapped onto the whole depth,
``eta = l (1 + xi)/(1 - xi)`` (``xi = 1`` is ``eta = inf``, where ``T = 0``).  The heat
equation with convection (H1), temperature continuity and the heat balance at the
interface (H5), with the pressure given by the contact condition (H6) and each body's
thermal displacement by Maysel's integral ``2 alpha (1 + nu) int T e^{-m eta} d eta``
(D3; Clenshaw–Curtis weights), make a linear generalised eigenproblem ``L x = b M x``
for the growth rate ``b``.  It shares nothing with the root search of
:mod:`thermocontact.physics.tei` but the material constants.

:func:`layup_operator` and :func:`layup_modes`, for any layup of
:mod:`thermocontact.physics.tei_layers` (L14): every body's temperature and both
displacements collocated, the heat and Navier equations in the plane asked for written
directly, and the face conditions of
:func:`~thermocontact.physics.tei_layers.condition_matrix` (the one statement of them)
applied to the discretised face fields; the statics eliminated, ``dT/dt = A T``.

Eigenvalues converge spectrally in the number of points; a half-plane's continuous
spectrum (``Re b <= -kappa m^2``) appears as a cloud of eigenvalues to be ignored.
"""

from __future__ import annotations


import math

import numpy as np
import scipy.linalg

from ..numerics.cache import small_cache
from ..physics.tei import SlidingPair

__all__ = ["depth_modes", "layup_modes", "layup_operator"]


@small_cache(16)
def _chebyshev(n):
    """Lobatto points ``cos(pi j/n)`` (1 first), differentiation matrix and
    Clenshaw–Curtis weights on ``[-1, 1]``; made once per ``n`` (read-only)."""
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
    for a in (x, d, w):
        a.flags.writeable = False
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


@small_cache(64)
def _body_operators(body, n, m, speed, plane, upper, refs, split=False):
    """One body's collocation: the interior rows (heat, then Navier's two equations),
    the rows that hold its fields at zero at infinity (a half-plane), its face fields
    as linear maps of its nodal unknowns, and which unknowns are the interior
    temperatures.  The latest 64 kept (read-only): a disc's two families are often
    reseeded at the same wavenumber and speed, with the same bodies.

    Unknowns ``[T, u_x, u_y]`` at the points (``T`` only for a conductor).  The
    elastic law is written in the plane asked for, directly: plane strain
    ``lambda = 2 mu nu/(1 - 2 nu)``, ``beta = 2 mu (1 + nu) alpha/(1 - 2 nu)``;
    plane stress ``lambda = 2 mu nu/(1 - nu)``, ``beta = 2 mu (1 + nu) alpha/(1 - nu)``.

    The speed enters a layer only through the convection ``-i m U T`` of a moving
    one's heat rows: the rest (:func:`_body_collocation`) is kept per wavenumber, for
    the reseedings of a scan at one wavenumber and many speeds.
    """
    rows, F, mass, cols, count = _body_collocation(
        body, n, m, speed if body.thickness is None else 0.0, plane, upper, refs, split)
    U = speed if body.moving else 0.0
    if mass and U != 0.0:
        # The convection on the diagonal of the heat rows, as written whole below
        # (the off-diagonal terms are zeros); the others are the kept ones.
        rows = rows.copy()
        on = (np.arange(len(mass)), np.array(mass))
        rows[on] = rows[on] - 1j * m * U
        rows.flags.writeable = False
    return rows, F, mass, cols, count


@small_cache(64)
def _body_collocation(body, n, m, speed, plane, upper, refs, split=False):
    """:func:`_body_operators` without the convection (``U = 0``; ``speed`` only for a
    half-plane's mapped grid)."""
    mat = body.material
    x, d, _ = _chebyshev(n)
    mu = mat.mu
    if plane == "strain":
        lam = 2.0 * mu * mat.nu / (1.0 - 2.0 * mat.nu)
        beta = 2.0 * mu * (1.0 + mat.nu) * mat.alpha / (1.0 - 2.0 * mat.nu)
    else:
        lam = 2.0 * mu * mat.nu / (1.0 - mat.nu)
        beta = 2.0 * mu * (1.0 + mat.nu) * mat.alpha / (1.0 - mat.nu)
    U = 0.0
    if body.thickness is not None:
        # y = h (1 - x)/2: x = 1 the bottom face (point 0), x = -1 the top (point n).
        d1 = -(2.0 / body.thickness) * d
        faces = {0: 0, 1: n}
        infinity = None
    else:
        pe = abs(speed) / (mat.k * m) if mat.K > 0.0 and not split else 0.0
        ell = 1.0 / (m * (1.0 + pe) ** 0.25)
        with np.errstate(divide="ignore"):
            jac = (1.0 - x) ** 2 / (2.0 * ell)          # d xi/d eta, eta the depth
        d1 = jac[:, None] * d * (1.0 if upper else -1.0)  # d/dy = +-d/d eta
        faces = {0: n, 1: n}
        infinity = 0
    d2 = d1 @ d1
    npt = n + 1
    eye = np.eye(npt)
    conducts = mat.K > 0.0
    nf = 3 if conducts else 2
    o_t, o_x, o_y = (0, npt, 2 * npt) if conducts else (None, 0, npt)
    cols = nf * npt
    inner = np.array([i for i in range(npt) if i not in set(faces.values()) and i != infinity])
    k = inner.size
    E = eye[inner]
    # Navier's equations at the interior points, x then y, interleaved as (x, y) pairs.
    nav = np.zeros((k, 2, cols), dtype=complex)
    nav[:, 0, o_x:o_x + npt] = mu * d2[inner] - (lam + 2.0 * mu) * m * m * E
    nav[:, 0, o_y:o_y + npt] = 1j * m * (lam + mu) * d1[inner]
    nav[:, 1, o_y:o_y + npt] = (lam + 2.0 * mu) * d2[inner] - mu * m * m * E
    nav[:, 1, o_x:o_x + npt] = 1j * m * (lam + mu) * d1[inner]
    rows = [nav.reshape(2 * k, cols)]
    mass = []
    if conducts:
        nav[:, 0, o_t:o_t + npt] = -1j * m * beta * E
        nav[:, 1, o_t:o_t + npt] = -beta * d1[inner]
        heat = np.zeros((k, cols), dtype=complex)
        heat[:, o_t:o_t + npt] = mat.k * (d2[inner] - m * m * E) - 1j * m * U * E
        rows = [heat, nav.reshape(2 * k, cols)]
        mass = list(o_t + inner)
    rows = list(np.concatenate(rows))
    zero_rows = []
    if infinity is not None:
        for o in ([o_t] if conducts else []) + [o_x, o_y]:
            r = np.zeros(cols, dtype=complex)
            r[o + infinity] = 1.0
            zero_rows.append(r)
    mu_ref, a_ref, K_ref = refs
    F = np.zeros((2, 6, cols), dtype=complex)
    for f, i in faces.items():
        F[f, 0, o_x + i] = 2.0 * mu_ref * m
        F[f, 1, o_y + i] = 2.0 * mu_ref * m
        F[f, 2, o_x:o_x + npt] = mu * d1[i]
        F[f, 2, o_y + i] += 1j * m * mu
        F[f, 3, o_y:o_y + npt] = (lam + 2.0 * mu) * d1[i]
        F[f, 3, o_x + i] += 1j * m * lam
        if conducts:
            F[f, 3, o_t + i] -= beta
            F[f, 4, o_t + i] = 2.0 * mu_ref * a_ref
            F[f, 5, o_t:o_t + npt] = -mat.K * d1[i] * 2.0 * mu_ref * a_ref / (K_ref * m)
    rows = np.array(rows + zero_rows)
    for a in (rows, F):
        a.flags.writeable = False
    return rows, F, tuple(mass), cols, len(rows)


def _split(layup, m, speed):
    """The layup with each conductor's thermal boundary layers as bodies of their own,
    bonded to the rest of it: at a Péclet number ``P = V/(kappa m)`` the temperature
    varies over ``1/(m sqrt(1 + P))`` near a sliding face, the displacements over
    ``1/m``; one Chebyshev grid would need both.  The skins are 25 such lengths
    thick (the temperature falls by ``e^{-17}`` or more across), at the faces that
    slide, and a layer less than 1.5 times as thick as its skins and the rest is kept
    whole.  A layer thicker than ``8/m`` is cut into pieces (at most 16) no thicker,
    the elastic fields' scale."""
    from ..physics.tei_layers import Body, Layup

    bodies, interfaces = [], []
    last = len(layup.bodies) - 1
    bottom, top = layup.bottom, layup.top
    for j, body in enumerate(layup.bodies):
        mat = body.material
        end = last > 0 and j in (0, last) and layup.bottom != "periodic"
        if end and body.thickness is not None and m * body.thickness > 40.0:
            # An end layer thicker than 40/m: its far face is e^{-40} away, and the
            # half-plane's mapped grid carries its fields better than a stack of pieces
            # (a thick layer's dense thermal modes blur the ones near them).
            body = Body(mat, None, body.moving)
            if j == 0:
                bottom = "infinite"
            else:
                top = "infinite"
        pe = abs(speed) / (mat.k * m) if mat.K > 0.0 else 0.0
        skin = 25.0 / (m * np.sqrt(1.0 + pe))
        h = body.thickness
        # Skins at the faces that slide: the others carry no thin thermal layer.
        periodic = layup.bottom == "periodic"       # the cells slide on each other
        below = (j > 0 and layup.interfaces[j - 1] == "sliding") or (j == 0 and periodic)
        above = (j < last and layup.interfaces[j] == "sliding") or (j == last and periodic)
        if pe < 100.0:
            parts = [h]
        elif h is None:
            parts = [skin, None] if j == last else [None, skin]
        elif h < (1 + below + above) * 1.5 * skin:
            parts = [h]
        else:
            parts = [skin] * below + [h - (below + above) * skin] + [skin] * above
        if h is not None:
            # The elastic fields vary over 1/m: a layer thicker than 8/m in pieces.
            cut = [min(16, math.ceil(m * p / 8.0)) for p in parts]
            parts = [p / k for p, k in zip(parts, cut) for _ in range(k)]
        if j > 0:
            interfaces.append(layup.interfaces[j - 1])
        for k, t in enumerate(parts):
            if k:
                interfaces.append("bonded")
            bodies.append(Body(mat, t, body.moving))
    return Layup(tuple(bodies), tuple(interfaces), bottom, top, layup.friction,
                 layup.dundurs, layup.plane, layup.floquet)


def layup_modes(layup, wavenumber, speed, n=32, count=None):
    """Growth rates ``b`` (1/s, in the frame of the bodies at rest) of a layup,
    discretised in depth: the second method of the layered TEI, the eigenvalues of
    :func:`layup_operator`.

    Parameters
    ----------
    layup : thermocontact.physics.tei_layers.Layup
    wavenumber : float
        ``m > 0``, 1/m.
    speed : float
        Sliding velocity ``U`` of the moving bodies, m/s.
    n : int, optional
        Chebyshev intervals per body.
    count : int, optional
        Return only this many, the largest real parts.

    Returns
    -------
    ndarray of complex
        Eigenvalues by decreasing real part.
    """
    # NumPy's LAPACK: the one whose threads the package limits (cli.main, api.tei).
    b = np.linalg.eigvals(layup_operator(layup, wavenumber, speed, n))
    b = b[np.argsort(-b.real, kind="stable")]
    return b if count is None else b[:count]


def layup_operator(layup, wavenumber, speed, n=32):
    """The layup's linearised equations discretised in depth: ``dT/dt = A T`` for the
    temperatures at the interior points (the second method of the layered TEI).

    Each body's temperature and displacements are collocated at ``n + 1``
    Chebyshev-Lobatto points (a layer's thickness, or a half-plane's depth mapped
    as for :func:`depth_modes`; a thin thermal boundary layer made a body of its
    own, :func:`_split`); the rows are the heat equation with convection (L1),
    Navier's equations with the thermal load in the plane of the layup (written
    directly, not through the plane-stress substitution), and the face conditions
    of :func:`thermocontact.physics.tei_layers.condition_matrix` applied to the
    discretised face fields.  The displacements and face temperatures are
    eliminated (the elastic problem is static).  It shares with the root search
    only the statement of the face conditions.

    Returns
    -------
    ndarray, complex, square
        ``A``, 1/s, at one speed (the speed enters through the convection and the
        frictional heat).
    """
    from ..physics.tei_layers import condition_matrix, heat_coefficient

    m, speed = float(wavenumber), float(speed)      # keys of the bodies' collocations
    refs = layup.references()          # the scales of the face fields: the layup's own
    heat = heat_coefficient(layup, m, speed)
    whole = len(layup.bodies)
    layup = _split(layup, m, speed)
    split = len(layup.bodies) > whole
    last = len(layup.bodies) - 1
    parts = [_body_operators(body, n, m, speed, layup.plane, j == last, refs, split)
             for j, body in enumerate(layup.bodies)]
    offsets = np.cumsum([0] + [p[3] for p in parts])
    size = int(offsets[-1])
    C0, C1 = condition_matrix(layup)
    C = C0 + heat * C1
    # The interior temperatures (the dynamic unknowns) and their heat rows first, the
    # static ones after, each body's block written where it goes.
    dyn_cols = np.concatenate([offsets[j] + np.array(p[2], dtype=int)
                               for j, p in enumerate(parts)])
    place = np.empty(size, dtype=int)
    place[np.concatenate([dyn_cols, _others(size, dyn_cols)])] = np.arange(size)
    nd = dyn_cols.size
    L = np.zeros((size, size), dtype=complex)
    r_dyn, r_st = 0, nd
    cond = size - C.shape[0]
    for j, (rows, F, mass, cols, ninner) in enumerate(parts):
        at = place[offsets[j]:offsets[j] + cols]
        k, rest = len(mass), rows.shape[0] - len(mass)       # heat rows come first
        L[r_dyn:r_dyn + k, at] = rows[:k]
        L[r_st:r_st + rest, at] = rows[k:]
        r_dyn, r_st = r_dyn + k, r_st + rest
        L[cond:, at] = np.einsum("rfk,fkc->rc", C[:, j], F)
    # The static rows are equations = 0: each scaled to unit size (their magnitudes
    # span 20 decades, and LU then slows on subnormal numbers).
    static = L[nd:]
    static *= 1.0 / np.max(np.abs(static), axis=1, keepdims=True)
    Lss, Lsd = static[:, nd:], static[:, :nd]
    return L[:nd, :nd] - L[:nd, nd:] @ np.linalg.solve(Lss, Lsd)


def _others(size, idx):
    """The indices below ``size`` not in ``idx``, in order."""
    keep = np.ones(size, dtype=bool)
    keep[idx] = False
    return np.flatnonzero(keep)
