"""Thermoelastic instability of layered sliding systems: one dispersion relation for
every stack of layers and half-planes (brake discs between pads, pads on backing
plates, clutch packs).

A *layup* is a stack of bodies along ``y`` (bottom first), each a layer of given
thickness or a half-plane at either end, each elastic and heat-conducting (or a
non-conductor, ``K = 0``) with its material moving along ``x`` at the sliding
velocity ``U`` (the slider's bodies) or at rest (the counterface's).  Neighbouring
bodies slide on each other (Coulomb friction, frictional heat, perfect thermal
contact) or are bonded; the outer faces of the end layers carry one of
:data:`FACE_CONDITIONS` (a free face, a rigid backing plate, a plane of symmetry).

Every field of a perturbation is ``exp(b t + i m x)`` times a function of ``y``.  In
each body it is a combination of closed-form solutions decaying away from either
face (derivation, "Thermoelastic instability of layers", L1-L12): two of the heat
equation with convection, ``kappa (T'' - m^2 T) = (b + i m U) T`` (L1), their
thermoelastic displacements from a displacement potential (L3, divided differences
that stay regular as ``gamma -> m``), and four isothermal Papkovich-Neuber solutions
(L2).  The face conditions (L5-L7) are linear combinations of six fields at the
faces (``u_x, u_y, sigma_xy, sigma_yy, T, q``); stacked, they make a square matrix
``M(b)``, and ``det M(b) = 0`` is the dispersion relation of every layup (L8).  A
half-plane keeps only its decaying solutions, so two half-planes give the relation
(H7) of :mod:`thermocontact.physics.tei`.

The conditions are written once, as coefficients of face fields
(:func:`condition_matrix`); the second method
(:func:`thermocontact.discretisation.tei_depth.layup_operator`, L14) supplies its own
face fields from a Chebyshev discretisation in depth.  :func:`layups` builds the
families of a brake disc, pads on backing plates and a clutch pack (L12).

Plane stress is plane strain with ``nu -> nu/(1 + nu)``,
``E -> E (1 + 2 nu)/(1 + nu)^2`` and ``alpha -> alpha (1 + nu)/(1 + 2 nu)`` (L9,
:func:`plane_stress_material`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from ..problem.materials import Material
from ..problem.validation import InputError

__all__ = [
    "BACKINGS",
    "Body",
    "CLUTCH_FAMILIES",
    "FACE_CONDITIONS",
    "FIELDS",
    "Layup",
    "body_fields",
    "condition_matrix",
    "condition_terms",
    "dispersion_log_derivatives",
    "dispersion_matrix",
    "dispersion_ratio",
    "face_fields",
    "field_group",
    "layup_dispersion",
    "layups",
    "mode_shape",
    "plane_stress_material",
]

#: Conditions at an outer face of an end layer: the faces' elastic and thermal
#: constraints (derivation, L7).  "free": no traction, no heat; "slip-insulated":
#: a rigid backing plate on which the layer slips freely, no heat through it;
#: "bonded-insulated": bonded to the rigid plate, no heat; "slip-isothermal": slips
#: on a plate held at its initial temperature; "symmetric" and "antisymmetric":
#: the mid-plane of a layer of twice the thickness, for the modes even and odd in
#: the temperature about it.
FACE_CONDITIONS = {
    "free": (("sxy", "syy"), "q"),
    "slip-insulated": (("uy", "sxy"), "q"),
    "bonded-insulated": (("ux", "uy"), "q"),
    "slip-isothermal": (("uy", "sxy"), "T"),
    "symmetric": (("uy", "sxy"), "q"),
    "antisymmetric": (("ux", "syy"), "T"),
}
#: The face fields, in this order: displacements, the tractions on planes y =
#: const, temperature and heat flux along +y (scaled: see :func:`face_fields`).
FIELDS = ("ux", "uy", "sxy", "syy", "T", "q")
_F = {name: i for i, name in enumerate(FIELDS)}
_INTERFACES = ("sliding", "bonded")


def plane_stress_material(mat: Material) -> Material:
    """The plane-strain stand-in of ``mat`` in plane stress (L9).

    ``nu' = nu/(1 + nu)``, ``E' = E (1 + 2 nu)/(1 + nu)^2`` (the shear modulus
    unchanged) and ``alpha' = alpha (1 + nu)/(1 + 2 nu)``: with these, the plane-strain
    equations are those of plane stress (``(1 - nu')/mu = 2/E``,
    ``alpha'(1 + nu') = alpha``).  Thermal properties are unchanged.
    """
    nu = mat.nu
    return Material(mat.name, mat.E * (1.0 + 2.0 * nu) / (1.0 + nu) ** 2, nu / (1.0 + nu),
                    mat.alpha * (1.0 + nu) / (1.0 + 2.0 * nu), mat.K, mat.k)


@dataclass(frozen=True)
class Body:
    """One body of a layup.

    Parameters
    ----------
    material : Material
        In plane strain (see :func:`plane_stress_material`).
    thickness : float or None
        Layer thickness, m; None for a half-plane (only at an end of the stack).
    moving : bool
        Whether its material moves at the sliding velocity ``U`` (a part of the
        slider) or rests (a part of the counterface).
    """

    material: Material
    thickness: float | None
    moving: bool

    @property
    def conducts(self) -> bool:
        return self.material.K > 0.0

    @property
    def columns(self) -> int:
        """Unknown amplitudes: 2 elastic and 1 thermal per decaying direction."""
        per = 3 if self.conducts else 2
        return per if self.thickness is None else 2 * per


@dataclass(frozen=True)
class Layup:
    """A stack of bodies, bottom first, and how they touch.

    Parameters
    ----------
    bodies : tuple of Body
        A half-plane only first (extending to ``y = -inf``) or last (``+inf``).
    interfaces : tuple of str
        Between bodies ``i`` and ``i + 1``: "sliding" (friction, frictional heat,
        perfect thermal contact, free slip) or "bonded".
    bottom, top : str
        The outer faces' conditions, one of :data:`FACE_CONDITIONS`; "infinite" for
        a half-plane's end; "periodic" (both) for a cell of a periodic stack.
    friction : float
        Coulomb coefficient ``f`` at every sliding interface.
    dundurs : bool
        Keep the friction traction's elastic effect (the Dundurs term of the
        half-planes); False: the sliding interfaces carry no shear elastically.
    plane : str
        "strain" or "stress" (the bodies' materials are given as they are; plane
        stress is applied through :func:`plane_stress_material`).
    floquet : float or None
        With ``bottom = top = "periodic"``: the stack repeats the bodies as one cell,
        the fields of the next cell ``e^{i floquet}`` times this one's (L7); the
        last body's top face slides on the next cell's first body.
    """

    bodies: tuple
    interfaces: tuple
    bottom: str
    top: str
    friction: float
    dundurs: bool = True
    plane: str = "strain"
    floquet: float | None = None

    def __post_init__(self):
        n = len(self.bodies)
        if n < 1 or len(self.interfaces) != n - 1:
            raise InputError("a layup needs one interface between each pair of bodies",
                             parameters=("interfaces",))
        for kind in self.interfaces:
            if kind not in _INTERFACES:
                raise InputError(f"interface must be one of {list(_INTERFACES)}, got {kind!r}",
                                 parameters=("interfaces",))
        periodic = (self.bottom == "periodic", self.top == "periodic")
        if any(periodic) and (not all(periodic) or self.floquet is None):
            raise InputError("a periodic stack has bottom = top = 'periodic' and a floquet "
                             "phase", parameters=("floquet",))
        for end, body, name in ((self.bottom, self.bodies[0], "bottom"),
                                (self.top, self.bodies[-1], "top")):
            if end == "periodic" and body.thickness is not None:
                continue
            if (end == "infinite") != (body.thickness is None):
                raise InputError(f"{name}: 'infinite' exactly when the end body is a "
                                 f"half-plane", parameters=(name,))
            if end != "infinite" and end not in FACE_CONDITIONS:
                raise InputError(f"{name} must be one of {sorted(FACE_CONDITIONS)}, got "
                                 f"{end!r}", parameters=(name,))
        if self.plane not in ("strain", "stress"):
            raise InputError(f"plane must be 'strain' or 'stress', got {self.plane!r}",
                             parameters=("plane",))
        for body in self.bodies[1:-1]:
            if body.thickness is None:
                raise InputError("only an end body may be a half-plane",
                                 parameters=("bodies",))
        for i, kind in enumerate(self.interfaces):
            a, b = self.bodies[i], self.bodies[i + 1]
            if kind == "sliding" and not (a.conducts or b.conducts):
                raise InputError("slider and counterface must not both be non-conducting "
                                 f"(K = 0): the frictional heat at the interface of "
                                 f"{a.material.name} and {b.material.name} would enter neither",
                                 parameters=("slider", "counterface"))

    @property
    def columns(self) -> int:
        return sum(b.columns for b in self.bodies)

    def elastic(self, body: Body) -> Material:
        """The body's material as the plane-strain equations take it (L9)."""
        return body.material if self.plane == "strain" else plane_stress_material(body.material)

    @lru_cache(maxsize=64)  # noqa: B019 (a frozen, hashable problem statement)
    def references(self):
        """``(mu, a, K)``: the scales of stress, thermal expansion ``alpha (1 + nu)/(1 -
        nu)`` and conductivity by which the face fields are made dimensionless
        (geometric means; the conductors' only for ``a`` and ``K``)."""
        mats = [self.elastic(b) for b in self.bodies]
        cond = [m for m in mats if m.K > 0.0] or mats
        mu = math.exp(np.mean([math.log(m.mu) for m in mats]))
        a = math.exp(np.mean([math.log(_potential(m)) for m in cond]))
        K = math.exp(np.mean([math.log(m.K) for m in cond if m.K > 0.0] or [0.0]))
        return mu, a, K


def _potential(mat: Material) -> float:
    """``alpha (1 + nu)/(1 - nu)``, 1/K: the source of the thermoelastic displacement
    potential, ``lap Omega = alpha (1 + nu)/(1 - nu) T`` (L3)."""
    return mat.alpha * (1.0 + mat.nu) / (1.0 - mat.nu)


def _sinhc(z):
    """``sinh(z)/z`` (1 at 0), accurate at small ``|z|`` where ``(e^z - 1)/z`` cancels."""
    return np.where(z == 0, 1.0, np.sinh(z) / np.where(z == 0, 1.0, z))


def _potential_profile(G, tau, e=None):
    """``(D, D')`` of ``D = (e^{-G tau} - e^{-tau})/(G^2 - 1)`` at ``tau >= 0`` (L3):
    the displacement potential, in units of ``1/m^2``, of a temperature ``e^{-G tau}``
    (``tau = m`` times the distance from the face; ``e`` that temperature, if known),
    and its derivative in ``tau``.  Regular at ``G = 1``: near it ``D = -tau e^{-(1 +
    G) tau/2} sinhc((1 - G) tau/2)/(G + 1)``, a divided difference without
    cancellation."""
    G = np.asarray(G, dtype=complex)
    tau = np.asarray(tau, dtype=float)
    d = G - 1.0
    with np.errstate(over="ignore", invalid="ignore", divide="ignore", under="ignore"):
        e_t = np.exp(-tau)
        near = np.abs(d * tau) < 1.0
        if near.all():
            D = -tau * np.exp(-0.5 * (1.0 + G) * tau) * _sinhc(-0.5 * d * tau) / (G + 1.0)
        else:
            e = np.exp(-G * tau) if e is None else e
            D = (e - e_t) / np.where(near, 1.0, G * G - 1.0)
            if near.any():
                dd = np.where(near, d, 0.0)
                close = -tau * np.exp(-0.5 * (1.0 + G) * tau) * _sinhc(-0.5 * dd * tau) / (
                    G + 1.0)
                D = np.where(near, close, D)
    return D, -G * D - e_t / (G + 1.0)


def _phi2(z):
    """``(e^z - 1 - z)/z^2`` at ``|z| < 1/2``, by its series to ``z^13`` (1/2 at 0; the
    rest below ``|z|^14/16! < 4e-18``)."""
    series = np.full(z.shape, 1.0 / math.factorial(15), dtype=complex)
    for k in range(12, -1, -1):            # sum of z^k/(k + 2)!, Horner's rule
        series = series * z + 1.0 / math.factorial(k + 2)
    return series


def _potential_profile_dG(G, tau, e, D):
    """``(dD/dG, dD'/dG)`` of :func:`_potential_profile` (``e = e^{-G tau}``, ``D``
    its profile): with ``f(x) = e^{-x tau}``, ``D = f[G, 1]/(G + 1)``, so ``dD/dG =
    (f[G, G, 1] - D)/(G + 1)``, the second divided difference ``f[G, G, 1] = tau^2
    e^{-G tau} phi_2(tau (G - 1))`` without cancellation near ``G = 1``
    (``phi_2(z) = (e^z - 1 - z)/z^2``); and ``D' = -G D - e^{-tau}/(G + 1)``."""
    with np.errstate(over="ignore", invalid="ignore", under="ignore", divide="ignore"):
        d = G - 1.0
        z = d * tau
        near = np.abs(z) < 0.5
        if near.all():
            f2 = tau * tau * e * _phi2(z)
        else:
            f2 = (-tau * e - (G + 1.0) * D) / d
            if near.any():
                f2[near] = (tau * tau * e)[near] * _phi2(z[near])
        dD = (f2 - D) / (G + 1.0)
        return dD, -D - G * dD + np.exp(-tau) / (G + 1.0) ** 2


def face_fields(body: Body, b, wavenumber, velocity, refs, upper=True, mat=None):
    """The six face fields of each of a body's solutions (L2-L4).

    Parameters
    ----------
    body : Body
    b, wavenumber, velocity : array_like
        Growth rates (complex, 1/s), wavenumbers ``m > 0`` (1/m) and sliding
        velocities ``U`` (m/s; a body at rest ignores it), broadcast to one shape
        ``S``.
    refs : tuple
        ``(mu, a, K)`` of :meth:`Layup.references`.
    upper : bool, optional
        For a half-plane: whether it lies above the stack (decaying toward
        ``y = +inf``, its face the bottom one) or below it.
    mat : Material, optional
        The body's material as the plane-strain equations take it (default: its own).

    Returns
    -------
    ndarray, shape ``S + (2, 6, columns)``
        ``[..., face, field, column]``: the faces bottom (0) and top (1), the fields
        of :data:`FIELDS` made dimensionless, ``2 mu m u``, ``sigma``,
        ``2 mu a T`` and ``2 mu a q/(K m)`` with the reference scales; a
        half-plane's one face is repeated.  Columns: the elastic solutions decaying
        from the bottom face (a harmonic ``phi`` and a ``psi``), then from the top,
        then the thermal solutions in the same order (conductors only); a
        half-plane above the stack has only the bottom's, one below only the top's.
    """
    return body_fields(body, b, wavenumber, velocity, refs, _face_depths(body), upper, mat)


def _face_depths(body: Body):
    """The depths of a body's faces (a half-plane's one face twice)."""
    return np.array([0.0, 0.0 if body.thickness is None else body.thickness])


def body_fields(body: Body, b, wavenumber, velocity, refs, depths, upper=True, mat=None):
    """The six fields of each of a body's solutions at ``depths`` (L2-L4): as
    :func:`face_fields`, at the distances ``depths`` (m) above a layer's bottom face
    or from a half-plane's face into it.

    Returns
    -------
    ndarray, shape ``S + (len(depths), 6, columns)``
    """
    sol = _Solutions.of([(body, upper, body.material if mat is None else mat)], refs)
    b, m, U = _broadcast(b, wavenumber, velocity)
    F = _fields_last(sol, b.reshape(-1), m.reshape(-1), U.reshape(-1),
                     np.asarray(depths, dtype=float).reshape(1, -1))
    return _points_first(F[0][:, :, sol.columns], b.shape)


def _broadcast(b, wavenumber, velocity):
    """``b`` (complex), ``m`` and ``U`` (float) as arrays of one shape."""
    b = np.asarray(b, dtype=complex)
    m = np.asarray(wavenumber, dtype=float)
    U = np.asarray(velocity, dtype=float)
    if b.shape == m.shape == U.shape:
        return b, m, U
    return np.broadcast_arrays(b, m, U)


@dataclass(frozen=True)
class _Solutions:
    """The solutions (L2-L4) of a stack of bodies as coefficients of the few functions
    of depth they are made of, so that :func:`_fields` evaluates all of them at once.

    Each solution starts from a face (``s = -1`` the bottom, ``+1`` the top) and
    decays away from it; ``t = m (y - y_start) = sign tau - shift m H`` with ``tau =
    m`` times the depth, ``s t <= 0``.  The elastic fields are ``(A + B t) e^{s t}``
    (a harmonic ``phi = e^{s t}/m^2``, ``2 mu u = grad phi``; and ``psi = e^{s t}/m``,
    ``2 mu u = grad((y - y_s) psi) - 4 (1 - nu) psi e_y``); the thermal ones
    ``cD D + cdD D' + (ce + cG G) e^{-G |t|}`` (L1, L3).  Every body has two starts
    (a half-plane's second, and a non-conductor's thermal solutions, with no
    coefficients) and six columns, of which ``columns`` are its own."""

    starts: np.ndarray      # (bodies, 2): s of each start
    sign: np.ndarray        # (bodies,): t = sign tau - shift m H
    shift: np.ndarray       # (bodies, 2)
    thickness: np.ndarray   # (bodies,): H (0 for a half-plane)
    moving: np.ndarray      # (bodies,): 1.0 for the slider's bodies
    kappa: np.ndarray       # (bodies,): diffusivity (1 for a non-conductor)
    A: np.ndarray           # (bodies, 6, 2, 2): elastic, phi and psi
    B: np.ndarray
    cD: np.ndarray          # (bodies, 6, 2): thermal
    cdD: np.ndarray
    ce: np.ndarray
    cG: np.ndarray
    columns: np.ndarray     # each body's own columns among its six, bodies in order

    @property
    def thermal_terms(self):
        """The thermal fields by the one term each has (:func:`_thermal_sum`): ``(kind,
        fields, coefficients)``, the coefficients ``(nb, 1, fields, 2, 1)``; "D", "dD",
        "e" and "eG" for ``cD D``, ``cdD D'``, ``ce e`` and ``cG G e`` (the solutions of
        L1-L3 have no field with two)."""
        cached = self.__dict__.get("_thermal_terms")
        if cached is None:
            names = ("D", "dD", "e", "eG")
            coefs = (self.cD, self.cdD, self.ce, self.cG)
            used = np.array([[np.any(c[:, f]) for c in coefs] for f in range(6)])
            if (used.sum(axis=1) > 1).any():
                raise ValueError("a thermal field of two kinds of term")
            cached = []
            for k, (name, c) in enumerate(zip(names, coefs)):
                fields = np.flatnonzero(used[:, k])
                if fields.size:
                    cached.append((name, fields, c[:, fields][:, None, ..., None]))
            unused = np.flatnonzero(~used.any(axis=1))
            if unused.size:
                cached.append(("D", unused, np.zeros((len(self.kappa), 1, unused.size, 2, 1),
                                                     dtype=complex)))
            cached = tuple(cached)
            object.__setattr__(self, "_thermal_terms", cached)
        return cached

    @staticmethod
    def of(bodies, refs) -> "_Solutions":
        """``bodies``: ``(Body, upper, material in plane strain)`` each; ``refs`` as
        for :func:`face_fields`."""
        mu_ref, a_ref, K_ref = refs
        nb = len(bodies)
        A = np.zeros((nb, 6, 2, 2), dtype=complex)
        B = np.zeros((nb, 6, 2, 2), dtype=complex)
        cD, cdD, ce, cG = (np.zeros((nb, 6, 2), dtype=complex) for _ in range(4))
        starts, shift = np.full((nb, 2), -1.0), np.zeros((nb, 2))
        sign, thickness, moving, kappa = (np.ones(nb), np.zeros(nb), np.zeros(nb),
                                          np.ones(nb))
        columns = []
        ux, uy, sxy, syy, T, q = range(6)
        for j, (body, upper, mat) in enumerate(bodies):
            r, nu = mu_ref / mat.mu, mat.nu
            layer = body.thickness is not None
            ns = 2 if layer else 1
            if layer:
                starts[j], shift[j], thickness[j] = (-1.0, 1.0), (0.0, 1.0), body.thickness
            elif not upper:
                starts[j, 0], sign[j] = 1.0, -1.0
            moving[j] = float(body.moving)
            s = starts[j, :ns]
            a, bb = A[j, :, :ns], B[j, :, :ns]
            # phi-type
            a[ux, :, 0], a[uy, :, 0], a[sxy, :, 0], a[syy, :, 0] = 1j * r, s * r, 1j * s, 1.0
            # psi-type
            bb[ux, :, 1] = 1j * r
            a[uy, :, 1], bb[uy, :, 1] = (-3.0 + 4.0 * nu) * r, s * r
            a[sxy, :, 1], bb[sxy, :, 1] = 1j * (-1.0 + 2.0 * nu), 1j * s
            a[syy, :, 1], bb[syy, :, 1] = -2.0 * (1.0 - nu) * s, 1.0
            own = list(range(2 * ns))
            if body.conducts:
                kappa[j] = mat.k
                pot = _potential(mat) / a_ref
                kr = mat.K / K_ref
                dy = -s                        # d/dy = -s d/d(distance)
                cD[j, ux, :ns], cD[j, syy, :ns] = 1j * pot, pot / r
                cdD[j, uy, :ns], cdD[j, sxy, :ns] = pot * dy, 1j * pot * dy / r
                ce[j, T, :ns] = 1.0
                cG[j, q, :ns] = -s * kr        # q = -K dT/dy
                own += [4 + i for i in range(ns)]
            columns += [6 * j + c for c in own]
        return _Solutions(starts, sign, shift, thickness, moving, kappa, A, B, cD, cdD, ce,
                          cG, np.array(columns))


def _points_first(a, shape):
    """``a`` with its last axis (the points) moved first and shaped ``shape``."""
    return np.ascontiguousarray(_last_first(a)).reshape(shape + a.shape[:-1])


def _last_first(a):
    """A view of ``a`` with its last axis first."""
    return a.transpose((a.ndim - 1,) + tuple(range(a.ndim - 1)))


def _fields_last(sol: _Solutions, b, m, U, depths, derivative=False):
    """The fields of every body of ``sol`` at ``depths`` (``(bodies, P)``, m), ``b``,
    ``m``, ``U`` of one axis (the ``N`` points): shape ``(bodies, P, 6, 6, N)``, the
    six columns of each body as in :class:`_Solutions` (the elastic solutions, two
    per start, then the thermal, one per start).  With ``derivative``: also their
    derivatives in the body's ``gamma/m = G`` (L1) of its thermal columns, the only
    ones that depend on it, ``(bodies, P, 6, 2, N)``, and ``G`` itself, ``(bodies,
    N)``.

    The points are the last axis, so that every array operation runs over them
    innermost, not over the few starts and solutions; each point's values are those
    it has alone.  Both kinds of columns are written into one array, not joined."""
    t = _start_coordinates(sol, m, depths)
    out = np.empty(t.shape[:2] + (6, 6, t.shape[-1]), dtype=complex)
    pairs = out.reshape(t.shape[:2] + (6, 3, 2, t.shape[-1]))     # the columns by twos
    _elastic_last(sol, t, pairs[:, :, :, :2])
    extra = _thermal_last(sol, b, m, U, t, derivative, pairs[:, :, :, 2])
    return (out,) + extra if derivative else out


def _start_coordinates(sol: _Solutions, m, depths):
    """``t = m (y - y_start)`` at ``depths`` of every start of every body, ``(nb, P,
    2, N)`` (:class:`_Solutions`)."""
    tau = depths[..., None] * m                                            # (nb, P, N)
    return (sol.sign[:, None, None, None] * tau[:, :, None]
            - (sol.thickness[:, None] * m)[:, None, None] * sol.shift[:, None, :, None])


def _elastic_last(sol: _Solutions, t, out=None):
    """The elastic columns of :func:`_fields_last`, ``(nb, P, 6, 4, N)``, at the
    coordinates ``t`` of :func:`_start_coordinates` (or into ``out``, ``(nb, P, 6, 2, 2,
    N)``, by start and solution): they depend on ``m`` only."""
    with np.errstate(under="ignore", over="ignore", invalid="ignore"):
        g = np.exp(sol.starts[:, None, :, None] * t)[:, :, None, :, None]  # (nb, P, 1, 2, 1, N)
        el = sol.A[:, None, ..., None] + sol.B[:, None, ..., None] * t[:, :, None, :, None]
        if out is None:
            return (el * g).reshape(el.shape[:3] + (4, el.shape[-1]))      # (nb, P, 6, 4, N)
        return np.multiply(el, g, out=out)


def _thermal_last(sol: _Solutions, b, m, U, t, derivative=False, out=None):
    """The thermal columns of :func:`_fields_last`, ``(nb, P, 6, 2, N)`` (into ``out``
    if given; with ``derivative``: also their ``G``-derivatives and ``G``).

    Each field is ``cD D + cdD D' + e^{-G |t|} (ce + cG G)`` (:class:`_Solutions`),
    of which every field has one term (:attr:`_Solutions.thermal_terms`): only that
    term is computed, the same products as in the whole sum."""
    G = np.sqrt(1.0 + (b + sol.moving[:, None] * (1j * (m * U)))
                / (sol.kappa[:, None] * (m * m)))[:, None, None]            # L1, (nb, 1, 1, N)
    if out is None:
        out = np.empty(t.shape[:2] + (6,) + t.shape[2:], dtype=complex)
    with np.errstate(under="ignore", over="ignore", invalid="ignore"):
        dist = np.abs(t)                   # m times the distance from the start face
        e = np.exp(-G * dist)
        D, dD = _potential_profile(G, dist, e)
        _thermal_sum(sol, D, dD, e, G, out)
        if not derivative:
            return out
        dD_G, ddD_G = _potential_profile_dG(G, dist, e, D)
        dth = np.empty_like(out)
        _thermal_sum(sol, dD_G, ddD_G, e, G, dth, dist)
    return dth, G[:, 0, 0]


def _thermal_sum(sol: _Solutions, D, dD, e, G, out, dist=None):
    """``out[:, :, f] = cD D + cdD dD + e (ce + cG G)`` for each field ``f`` (shapes
    ``(nb, P, 2, N)``), or with ``dist``, their ``G``-derivative ``cD D + cdD dD + e
    (cG - dist (ce + cG G))`` (``D``, ``dD`` then the profiles' derivatives): the
    fields of each kind of term (:attr:`_Solutions.thermal_terms`) in one product, the
    same as each field's sum of its terms of nonzero coefficient."""
    for kind, fields, c in sol.thermal_terms:
        if kind == "D":
            value = D[:, :, None] * c
        elif kind == "dD":
            value = dD[:, :, None] * c
        elif kind == "e":
            value = e[:, :, None] * (c if dist is None else 0.0 - dist[:, :, None] * c)
        else:
            Gc = G[:, :, None] * c
            value = e[:, :, None] * (Gc if dist is None else c - dist[:, :, None] * Gc)
        out[:, :, fields] = value


@lru_cache(maxsize=64)
def condition_matrix(layup: Layup):
    """The face conditions as coefficients of the face fields (L5-L7).

    Returns
    -------
    (C0, C1) : ndarrays, shape ``(rows, bodies, 2, 6)``
        Row ``r`` says ``sum (C0 + h C1)[r, j, face, field] * field(body j, face) = 0``
        in the dimensionless fields of :func:`face_fields`, with
        ``h = 2 mu a f V/(K m)`` the frictional heat's coefficient (the
        references' scales).  Rows: each interface's from the bottom up, then the
        bottom's and the top's outer face.
    """
    nb = len(layup.bodies)
    rows0, rows1 = [], []
    links = [(i, i + 1, kind, 1.0) for i, kind in enumerate(layup.interfaces)]
    if layup.bottom == "periodic":
        # The next cell's first body, its fields e^{i phase} times this cell's.
        links.append((nb - 1, 0, "sliding", complex(np.exp(1j * layup.floquet))))

    def row(*terms, heat=()):
        c0 = np.zeros((nb, 2, 6), dtype=complex)
        c1 = np.zeros((nb, 2, 6), dtype=complex)
        for j, face, name, coef in terms:
            c0[j, face, _F[name]] += coef * (phase if j == a and face == 0 else 1.0)
        for j, face, name, coef in heat:
            c1[j, face, _F[name]] += coef * (phase if j == a and face == 0 else 1.0)
        rows0.append(c0)
        rows1.append(c1)

    for bb, a, kind, phase in links:
        # a: the body above (its bottom face 0); bb: the body below (its top face 1).
        lo, hi = layup.bodies[bb], layup.bodies[a]
        row((a, 0, "uy", 1.0), (bb, 1, "uy", -1.0))
        row((a, 0, "syy", 1.0), (bb, 1, "syy", -1.0))
        row((a, 0, "sxy", 1.0), (bb, 1, "sxy", -1.0))
        if kind == "bonded":
            row((a, 0, "ux", 1.0), (bb, 1, "ux", -1.0))
            if hi.conducts and lo.conducts:
                row((a, 0, "T", 1.0), (bb, 1, "T", -1.0))
                row((a, 0, "q", 1.0), (bb, 1, "q", -1.0))
            elif hi.conducts:
                row((a, 0, "q", 1.0))
            elif lo.conducts:
                row((bb, 1, "q", 1.0))
            continue
        # Sliding: sigma_xy = s f P on both sides, P = -sigma_yy, s the sign of the
        # upper body's velocity relative to the lower's (L5).
        s = float(hi.moving) - float(lo.moving)
        shear = layup.friction * s if layup.dundurs else 0.0
        row((a, 0, "sxy", 1.0), (a, 0, "syy", shear))
        # Heat (L6): q into the upper body + q into the lower = f |U_rel| P.
        terms = ([(a, 0, "q", 1.0)] if hi.conducts else []) + (
            [(bb, 1, "q", -1.0)] if lo.conducts else [])
        row(*terms, heat=[(a, 0, "syy", abs(s))])
        if hi.conducts and lo.conducts:
            row((a, 0, "T", 1.0), (bb, 1, "T", -1.0))
    a, phase = -1, 1.0
    for j, face, end in ((0, 0, layup.bottom), (nb - 1, 1, layup.top)):
        if end in ("infinite", "periodic"):
            continue
        elastic, thermal = FACE_CONDITIONS[end]
        for name in elastic:
            row((j, face, name, 1.0))
        if layup.bodies[j].conducts:
            row((j, face, thermal, 1.0))
    return np.array(rows0), np.array(rows1)


def heat_coefficient(layup: Layup, wavenumber, speed):
    """``h = 2 mu a f |V|/(K m)`` of :func:`condition_matrix`, dimensionless."""
    mu_ref, a_ref, K_ref = layup.references()
    return (2.0 * mu_ref * a_ref * layup.friction / K_ref) * np.abs(speed) / wavenumber


def condition_terms(layup: Layup, b, wavenumber, speed):
    """``(M_0, M_1)`` with ``M(b) = M_0(b) + h M_1(b)`` (L8; ``h`` of
    :func:`heat_coefficient`): the face conditions of :func:`condition_matrix` without
    and with the frictional heat's coefficient, applied to every body's solutions
    (:func:`face_fields`), evaluated once for both.

    Parameters
    ----------
    layup : Layup
    b, wavenumber, speed : array_like
        As for :func:`dispersion_matrix`.

    Returns
    -------
    (ndarray, ndarray), each of shape ``S + (n, n)``
    """
    b, m, V = _broadcast(b, wavenumber, speed)
    asm = _assembly(layup)
    M0, heat = _condition_rows(asm, _fields_last(asm.solutions, b.reshape(-1), m.reshape(-1),
                                                 V.reshape(-1), asm.depths))
    M1 = np.zeros_like(M0)
    M1[asm.heat_rows] = heat
    return _points_first(M0, b.shape), _points_first(M1, b.shape)


def _condition_rows(asm, F, group=None):
    """``(M_0, E^T M_1)`` of :func:`condition_terms`, ``(rows, columns, N)``, from the
    face fields ``F``, ``(nb, 2, 6, c, N)`` of :func:`_fields_last` (``c`` columns of
    each body; ``group``: see :func:`_grouped`): ``M_1`` in its rows of the
    frictional heat only, the columns every body's ``c``, or with ``c = 6`` those of
    ``M``."""
    terms, heat_terms, which = (asm.terms, asm.heat_terms, None) if group is None else group
    F = F.reshape((12 * F.shape[0],) + F.shape[3:])
    M0, M1 = _applied(terms, F, which), _applied(heat_terms, F, which)
    if F.shape[1] == 6 and asm.own is not None:
        return M0[:, asm.own], M1[:, asm.own]
    return M0, M1


@dataclass(frozen=True)
class _Terms:
    """Rows of :func:`condition_matrix` as sums of the few face fields each names:
    on body ``j``'s columns row ``r`` is ``sum_t weights[t, r, j] F[slots[t, r, j]]``,
    ``F`` the bodies' face fields flattened (``12 j + 6 face + field``; a shorter sum
    padded with zero weights), instead of a product with the mostly zero
    coefficients."""

    slots: np.ndarray       # (T, rows, nb), int
    weights: np.ndarray     # (T, rows, nb); (K, T, rows, nb) for K layups of a group

    @staticmethod
    def of(Cs):
        """From the coefficients ``Cs``, ``(K, rows, nb, 2, 6)``, of ``K`` layups, on
        the union of their fields (a field some do not name has a zero weight)."""
        K, rows, nb = Cs.shape[:3]
        Cs = Cs.reshape(K, rows, nb, 12)
        used = np.any(Cs != 0, axis=0)
        T = max(1, int(used.sum(axis=-1).max()))
        slots = np.zeros((T, rows, nb), dtype=np.intp)
        weights = np.zeros((K, T, rows, nb), dtype=complex)
        for r, j in np.ndindex(rows, nb):
            slots[:, r, j] = 12 * j
            for t, f in enumerate(np.flatnonzero(used[r, j])):     # in the fields' order
                slots[t, r, j] = 12 * j + f
                weights[:, t, r, j] = Cs[:, r, j, f]
        return _Terms(slots, weights[0] if K == 1 else weights)

    @property
    def plan(self):
        """How :func:`_applied` takes the sums, made once: ``((slots, fixes), rest)``.
        The first term of every sum is gathered whole (``slots``, ``(rows, nb)``), then
        ``fixes`` = ``(kind, r, j, w)`` change the pairs ``(r, j)`` whose first weight
        is not 1 in every layup: "zero" (0 in every layup), "neg" (-1 in every one),
        "same" (``w`` the same in every one) or "each" (``w`` per layup, ``(K,
        n)``).  ``rest``: ``(slots, kind, r, j, w)`` each later term added where its
        weight is not zero in every layup, "one" (1), "neg" (-1), "same" or "each"."""
        cached = self.__dict__.get("_plan")
        if cached is None:
            W = self.weights if self.weights.ndim == 4 else self.weights[None]
            same = np.all(W == W[:1], axis=0)                              # (T, rows, nb)
            w0 = W[0]

            def pick(mask, kind, t):
                r, j = np.nonzero(mask)
                w = (w0[t, r, j] if kind == "same" else W[:, t, r, j])
                return r, j, w

            fixes = []
            for kind, mask in (("zero", same[0] & (w0[0] == 0)),
                               ("neg", same[0] & (w0[0] == -1)),
                               ("same", same[0] & (w0[0] != 0) & (w0[0] != 1) & (w0[0] != -1)),
                               ("each", ~same[0])):
                if mask.any():
                    fixes.append((kind,) + pick(mask, kind, 0))
            rest = []
            for t in range(1, W.shape[1]):
                for kind, mask in (("one", same[t] & (w0[t] == 1)),
                                   ("neg", same[t] & (w0[t] == -1)),
                                   ("same", same[t] & (w0[t] != 0) & (w0[t] != 1)
                                    & (w0[t] != -1)),
                                   ("each", ~same[t])):
                    if mask.any():
                        r, j, w = pick(mask, kind, t)
                        rest.append((self.slots[t, r, j], kind, r, j, w))
            cached = ((self.slots[0], tuple(fixes)), tuple(rest))
            object.__setattr__(self, "_plan", cached)
        return cached


def _applied(terms, F, which=None):
    """``(rows, nb c, N)``: the rows of ``terms`` applied to the face fields ``F``,
    ``(12 nb, c, N)``; with ``which`` (``N``; ``terms`` of a group), point ``i`` by
    the ``which[i]``-th layup's weights.  A point's value is the one it has alone
    for finite fields: the same products summed in the same order, without the
    terms whose weight is zero in every layup (:meth:`_Terms.plan`), a weight of 1
    or -1 taken as a copy or a change of sign."""
    (first, fixes), rest = terms.plan
    out = F[first]                                                   # (rows, nb, c, N)
    for kind, r, j, w in fixes:
        if kind == "zero":
            out[r, j] = 0.0
        elif kind == "neg":
            out[r, j] = -out[r, j]
        else:
            out[r, j] = out[r, j] * _weights(kind, w, which)
    for slot, kind, r, j, w in rest:
        if kind == "one":
            out[r, j] += F[slot]
        elif kind == "neg":
            out[r, j] -= F[slot]
        else:
            out[r, j] += F[slot] * _weights(kind, w, which)
    return out.reshape((out.shape[0], out.shape[1] * out.shape[2], out.shape[3]))


def _weights(kind, w, which):
    """Weights ``w`` of one kind of :meth:`_Terms.plan` against ``(n, c, N)``: the same
    for every layup (``(n,)``), or per point by its layup (``(K, n)``)."""
    if kind == "same":
        return w[:, None, None]
    return w[which].T[:, None, :]


def field_group(layup: Layup):
    """A key shared by the layups whose dispersion matrices differ only in the rows of
    their outer faces (a disc's symmetric and antisymmetric families): the same bodies,
    interfaces and plane, hence the same solutions, unknowns and rows of the
    frictional heat.  :func:`dispersion_log_derivatives` and
    :func:`dispersion_ratio` evaluate points of several such layups together."""
    return (layup.bodies, layup.interfaces, layup.friction, layup.dundurs, layup.plane,
            layup.bottom == "periodic")


def _grouped(layup, which):
    """``(the first layup, group)``: ``layup`` one layup (``which`` None; group None),
    or a sequence of layups of one :func:`field_group`, group ``(terms, heat terms,
    which)``, the :class:`_Terms` of all of them on one pattern."""
    if which is None:
        return layup, None
    layup = tuple(layup)
    which = np.asarray(which).reshape(-1)
    return layup[0], _group_terms(layup) + (which,)


@lru_cache(maxsize=64)
def _group_terms(layups):
    """The :class:`_Terms` of the conditions and of the rows of the frictional heat of
    layups of one :func:`field_group`, on the union of their fields."""
    if len({field_group(lay) for lay in layups}) != 1:
        raise ValueError("layups of one field_group only")
    C = [condition_matrix(lay) for lay in layups]
    rows = _assembly(layups[0]).heat_rows
    return (_Terms.of(np.array([c[0] for c in C])),
            _Terms.of(np.array([c[1][rows] for c in C])))


@dataclass(frozen=True)
class _Assembly:
    """What :func:`condition_terms` needs of a layup, made once: every body's
    solutions, the rows of ``C_0`` and those of ``C_1`` that carry the frictional heat
    (``heat_rows``) of :func:`condition_matrix` as :class:`_Terms`, the faces'
    depths, which of the bodies' six columns each are theirs (None: all), the
    frictional heat's coefficient per ``|V|/m`` and the conducting layers' ``(kappa,
    moving)`` (:func:`layup_dispersion`)."""

    solutions: _Solutions
    terms: _Terms
    heat_terms: _Terms
    heat_rows: np.ndarray
    depths: np.ndarray
    own: np.ndarray | None
    heat: float
    layers: tuple


def _assembly(layup: Layup) -> _Assembly:
    """The layup's :class:`_Assembly`, kept on the (frozen) layup."""
    cached = layup.__dict__.get("_assembly")
    if cached is None:
        C0, C1 = condition_matrix(layup)
        last = len(layup.bodies) - 1
        sol = _Solutions.of([(body, j == last, layup.elastic(body))
                             for j, body in enumerate(layup.bodies)], layup.references())
        heat_rows = np.flatnonzero(np.any(C1.reshape(C1.shape[0], -1) != 0, axis=1))
        own = sol.columns
        if np.array_equal(own, np.arange(6 * len(layup.bodies))):
            own = None
        kap = np.array([b.material.k for b in layup.bodies
                        if b.thickness is not None and b.conducts])
        mov = np.array([float(b.moving) for b in layup.bodies
                        if b.thickness is not None and b.conducts])
        cached = _Assembly(sol, _Terms.of(C0[None]), _Terms.of(C1[None, heat_rows]),
                           heat_rows, np.array([_face_depths(body) for body in layup.bodies]),
                           own, float(heat_coefficient(layup, 1.0, 1.0)), (kap, mov))
        object.__setattr__(layup, "_assembly", cached)
    return cached


def dispersion_matrix(layup: Layup, b, wavenumber, speed, heat=True):
    """``M(b)``: the face conditions applied to every body's solutions (L8).

    Parameters
    ----------
    layup : Layup
    b, wavenumber, speed : array_like
        Growth rates in the frame of the bodies at rest (complex, 1/s), wavenumbers
        (1/m) and the moving bodies' velocity ``U`` (m/s), broadcast to a shape
        ``S``.
    heat : bool, optional
        False: without the frictional heat (``h = 0``; the convection kept), the
        matrix ``M_0(b)`` whose determinant is zero only at free thermal modes, all
        decaying (L15).

    Returns
    -------
    ndarray, shape ``S + (n, n)``
        Square; ``n`` the unknown amplitudes of all bodies.
    """
    b, m, V = _broadcast(b, wavenumber, speed)
    M0, M1 = condition_terms(layup, b, m, V)
    if not heat:
        return M0
    return M0 + (_assembly(layup).heat * np.abs(V) / m)[..., None, None] * M1


def layup_dispersion(layup: Layup, b, wavenumber, speed):
    """The dispersion function ``det M(b) / prod gamma_j/m``, zero at a mode (L8);
    analytic in ``b`` to the right of the continuous spectra ``Re b <= -kappa m^2`` of
    the half-planes.

    A conducting layer's two thermal solutions ``e^{-gamma eta}``, ``e^{-gamma zeta}``
    become one as ``gamma -> 0``: ``det M`` then has a zero that is no mode, at
    ``b = -i m U - kappa m^2``, next to the neutral modes fixed on the layer.  In the
    basis ``cosh``, ``sinh(gamma .)/gamma`` about the mid-plane, which stays
    independent, the determinant is ``det M`` divided by ``2 (gamma/m) e^{-gamma h}``
    per layer; dividing by ``gamma/m`` alone removes that zero and adds none."""
    b, m, V = _broadcast(b, wavenumber, speed)
    kap, mov = _assembly(layup).layers
    with np.errstate(all="ignore"):     # a determinant that under- or overflows: no root
        d = np.linalg.det(dispersion_matrix(layup, b, m, V))
        if kap.size:
            G = np.sqrt(1.0 + (b[..., None] + 1j * (m * V)[..., None] * mov)
                        / (kap * (m * m)[..., None]))
            d = d / np.prod(G, axis=-1)
    return d


def dispersion_log_derivatives(layup: Layup, b, wavenumber, speed, which=None):
    """``d ln D/db`` and ``d ln D/dV`` of the dispersion function ``D`` of
    :func:`layup_dispersion` (L8, L16), in closed form: by Jacobi's formula ``d ln
    det M = tr(M^{-1} dM)``, with ``dM/db`` and ``dM/dV`` from the derivatives of the
    thermal solutions in ``G = gamma/m`` (``dG/db = 1/(2 G kappa m^2)``, ``dG/dV = i m
    /(2 G kappa m^2)`` on a moving body) and of the frictional heat's ``h`` in ``V``;
    less the conducting layers' ``d ln G/db``, ``d ln G/dV``.  A Newton step on ``D``
    in ``b`` is ``-1/(d ln D/db)``; a root's speed of travel ``db/dV = -(d ln
    D/dV)/(d ln D/db)``.

    Parameters
    ----------
    layup : Layup, or sequence of Layup
        With ``which``: layups of one :func:`field_group`.
    b, wavenumber, speed : array_like
        As for :func:`dispersion_matrix`, broadcast to a shape ``S``; ``speed > 0``.
    which : array_like of int, optional
        Of shape ``S`` (one axis): the layup of each point.

    Returns
    -------
    ndarray, complex, shape ``S + (2,)``
        ``[d ln D/db, d ln D/dV]``, s and s/m; NaN where ``M`` is singular.
    """
    layup, group = _grouped(layup, which)
    b, m, V = _broadcast(b, wavenumber, speed)
    shape = b.shape
    b, m, V = b.reshape(-1), m.reshape(-1), V.reshape(-1)
    asm = _assembly(layup)
    sol = asm.solutions
    cols, bodies, heat_rows = _derivative_terms(layup)
    F, dF, G = _fields_last(sol, b, m, V, asm.depths, derivative=True)
    with np.errstate(all="ignore"):
        # dM/db: nonzero in the thermal columns only, each of one body; the same
        # columns of dM/dV are i m U/V times them (G depends on b + i m U).  The
        # points last until the solve.
        M, M1 = _condition_rows(asm, F, group)                  # (n, n, N), (rows, n, N)
        hq = asm.heat / m
        h = hq * np.abs(V)
        M[heat_rows] += h * M1
        T0, T1 = _condition_rows(asm, dF, group)
        dG = (1.0 / (2.0 * G * sol.kappa[:, None] * (m * m)))[bodies]   # dG/db, (k, N)
        dMb = T0[:, cols] * dG
        dMb[heat_rows] += h * (T1[:, cols] * dG)
        # tr(M^-1 M_1): M_1 nonzero in the rows of the frictional heat only.
        n, k, nh = M.shape[0], len(cols), len(heat_rows)
        rhs = np.zeros((b.size, n, k + nh), dtype=complex)
        rhs[..., :k] = _last_first(dMb)
        rhs[:, heat_rows, k + np.arange(nh)] = 1.0
        X = _solve(_last_first(M), rhs)
        own = np.arange(6 * len(layup.bodies)) if asm.own is None else asm.own
        at = np.flatnonzero(own % 6 >= 4)                  # the thermal columns' places
        diag = X[:, at, np.arange(k)]                                     # (N, k)
        heat = np.diagonal(_last_first(M1) @ X[..., k:], axis1=-2, axis2=-1)
        moving = 1j * m[:, None] * sol.moving[bodies]
        out = np.stack([_sum(diag), _sum(moving * diag) + hq * np.sign(V) * _sum(heat)],
                       axis=-1)
        kap, mov = asm.layers
        if kap.size:
            Gl = np.sqrt(1.0 + (b[:, None] + 1j * (m * V)[:, None] * mov)
                         / (kap * (m * m)[:, None]))
            dl = 1.0 / (2.0 * Gl * Gl * kap * (m * m)[:, None])             # d ln G/db
            out[:, 0] -= _sum(dl)
            out[:, 1] -= _sum(1j * m[:, None] * mov * dl)
    return out.reshape(shape + (2,))


def _sum(a):
    """The sum over the last (short) axis, term by term in order: each point's value
    the same in a batch of any size (a reduction's order may depend on the layout)."""
    out = a[..., 0].copy()
    for i in range(1, a.shape[-1]):
        out += a[..., i]
    return out


@lru_cache(maxsize=64)
def _derivative_terms(layup: Layup):
    """What :func:`dispersion_log_derivatives` (and :func:`dispersion_ratio`, the rows of the
    heat) need of a layup: the thermal columns of
    ``M`` as indices into the bodies' thermal columns ``(body, start)`` flattened,
    the body of each, and the rows of ``M`` that carry the frictional heat."""
    asm = _assembly(layup)
    nb = len(layup.bodies)
    own = np.arange(6 * nb) if asm.own is None else asm.own
    thermal = own[own % 6 >= 4]
    return 2 * (thermal // 6) + thermal % 6 - 4, thermal // 6, asm.heat_rows


def _solve(M, rhs):
    """``M^{-1} rhs`` for a stack; NaN for the singular matrices of it."""
    try:
        return np.linalg.solve(M, rhs)
    except np.linalg.LinAlgError:
        out = np.full(rhs.shape, np.nan, dtype=complex)
        for i in np.ndindex(M.shape[:-2]):
            try:
                out[i] = np.linalg.solve(M[i], rhs[i])
            except np.linalg.LinAlgError:
                pass
        return out


def dispersion_ratio(layup: Layup, b, wavenumber, speed, which=None):
    """``det M(b)/det M_0(b)`` (:func:`dispersion_matrix` with and without the
    frictional heat), the function whose winding along the imaginary axis counts the
    growing modes (L15): zero at the modes, no pole in ``Re b >= 0`` (those of ``det
    M_0`` are free thermal modes, which decay), tending to 1 as ``|b| -> inf`` there.
    ``M_1`` is nonzero only in the rows of the frictional heat (one per sliding
    interface), so by the matrix determinant lemma the ratio is ``det(I + h E^T M_1
    M_0^{-1} E)``, ``E`` the unit columns of those rows: one factorisation of
    ``M_0``, no determinant that over- or underflows.

    Parameters
    ----------
    layup : Layup, or sequence of Layup
        As for :func:`dispersion_log_derivatives`.
    b, wavenumber, speed : array_like
        As for :func:`dispersion_matrix`, broadcast to a shape ``S``.
    which : array_like of int, optional
        As for :func:`dispersion_log_derivatives`.

    Returns
    -------
    ndarray, complex, shape ``S``
    """
    layup, group = _grouped(layup, which)
    b, m, V = _broadcast(b, wavenumber, speed)
    shape = b.shape
    b, m, V = b.reshape(-1), m.reshape(-1), V.reshape(-1)
    asm = _assembly(layup)
    M0, M1 = _condition_rows(asm, _fields_last(asm.solutions, b, m, V, asm.depths), group)
    h = asm.heat * np.abs(V) / m
    rows = asm.heat_rows
    unit = np.zeros((M0.shape[0], rows.size))
    unit[rows, np.arange(rows.size)] = 1.0
    with np.errstate(over="ignore", under="ignore", invalid="ignore"):
        Y = _solve(_last_first(M0), np.broadcast_to(unit, (b.size,) + unit.shape))
        K = np.eye(rows.size) + h[:, None, None] * (_last_first(M1) @ Y)
        return (K[:, 0, 0] if rows.size == 1 else np.linalg.det(K)).reshape(shape)


#: The backing plates a pad layer may sit on (:data:`FACE_CONDITIONS`).
BACKINGS = ("slip-insulated", "bonded-insulated", "slip-isothermal")
#: A clutch pack's families: the friction disc's mid-plane's symmetry, and whether
#: neighbouring cells (separator plate and friction disc) move in phase (the
#: separator's mid-plane of the same symmetry) or in anti-phase (the other).
CLUTCH_FAMILIES = {
    "symmetric in-phase": ("symmetric", "symmetric"),
    "antisymmetric in-phase": ("antisymmetric", "antisymmetric"),
    "symmetric anti-phase": ("symmetric", "antisymmetric"),
    "antisymmetric anti-phase": ("antisymmetric", "symmetric"),
}


def layups(slider: Material, counterface: Material, friction, *, dundurs=True,
           plane="strain", slider_thickness=None, faces=2, counterface_thickness=None,
           backing="slip-insulated", separator=None, separator_thickness=None) -> dict:
    """The families of modes of a brake or clutch, each as a :class:`Layup` (L12).

    * Two half-planes (no thickness given): ``{}`` (the relation of
      :mod:`thermocontact.physics.tei`).
    * A disc (``slider_thickness`` d) rubbing on ``faces = 2`` identical pads: the
      half-disc on a pad, its mid-plane "symmetric" or "antisymmetric" (the two
      families); on one pad (``faces = 1``), the other face free and insulated: one
      family, "all".  A half-plane slider on a pad layer: "all".
    * Pads: half-planes, or layers of thickness ``counterface_thickness`` on a rigid
      backing plate (:data:`BACKINGS`).
    * A clutch pack (``separator`` given): the cell of half a separator plate (at
      rest), a facing (the counterface's material and thickness) and half the
      friction disc's core (the slider's), both moving; the four families of
      :data:`CLUTCH_FAMILIES`.

    The counterface lies below the slider, as for two half-planes.
    """
    if separator is not None:
        cell = (Body(separator, 0.5 * separator_thickness, False),
                Body(counterface, counterface_thickness, True),
                Body(slider, 0.5 * slider_thickness, True))
        return {name: Layup(cell, ("sliding", "bonded"), sep, core, friction, dundurs, plane)
                for name, (core, sep) in CLUTCH_FAMILIES.items()}
    if slider_thickness is None and counterface_thickness is None:
        return {}
    pad = Body(counterface, counterface_thickness, False)
    bottom = "infinite" if counterface_thickness is None else backing
    if slider_thickness is None:
        return {"all": Layup((pad, Body(slider, None, True)), ("sliding",), bottom,
                             "infinite", friction, dundurs, plane)}
    if faces == 1:
        return {"all": Layup((pad, Body(slider, slider_thickness, True)), ("sliding",),
                             bottom, "free", friction, dundurs, plane)}
    half = Body(slider, 0.5 * slider_thickness, True)
    return {name: Layup((pad, half), ("sliding",), bottom, name, friction, dundurs, plane)
            for name in ("antisymmetric", "symmetric")}


def mode_shape(layup: Layup, b, wavenumber, speed, points=41):
    """A mode's temperature, normal displacement and normal stress through every
    body (L8): the null vector of ``M(b)`` (the last right singular vector), its
    solutions summed at ``points`` depths per body.

    Returns
    -------
    list of (y, T, u_y, sigma_yy) per body, bottom first
        ``y`` in m from the first interface (a half-plane over ``3/m``);
        complex amplitudes, the temperature's largest modulus made 1 (K),
        ``u_y`` in m/K and ``sigma_yy`` in Pa/K per unit of it.
    """
    m = float(wavenumber)
    refs = layup.references()
    mu_ref, a_ref, _ = refs
    M = dispersion_matrix(layup, complex(b), m, speed)
    coef = np.linalg.svd(M)[2][-1].conj()
    out, col, base = [], 0, 0.0
    last = len(layup.bodies) - 1
    for j, body in enumerate(layup.bodies):
        h = body.thickness
        depths = np.linspace(0.0, 3.0 / m if h is None else h, points)
        F = body_fields(body, complex(b), m, speed, refs, depths, upper=j == last,
                        mat=layup.elastic(body))
        vals = F @ coef[col:col + body.columns]
        col += body.columns
        if h is None and j == 0:
            y = -depths[::-1]
            vals = vals[::-1]
        else:
            y = base + depths
            base += 0.0 if h is None else h
        out.append([y, vals[:, 4] / (2.0 * mu_ref * a_ref), vals[:, 1] / (2.0 * mu_ref * m),
                    vals[:, 3]])
    peak = max(np.max(np.abs(o[1])) for o in out) or 1.0
    return [(y, T / peak, u / peak, s / peak) for y, T, u, s in out]
