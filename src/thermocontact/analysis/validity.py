"""The inequalities of unilateral contact: compressive pressure, open gap, positive load.

The gap outside the contact is the integral of the slope mismatch ``G(s)``, the
left side minus the right side of the contact equation (D14) continued to
``|s| > 1`` (derivation section 7, which corrects the paper's eqs. 29-30).  Every
piece is integrated in closed form: the Cauchy part term by term in the pressure's
``U``-series, the cylinder's step kernel through its antiderivative
``-E(u) = -exp(-u) I0(u)`` and the half-plane's ``sgn`` kernel exactly.  The
discrete solution satisfies (D14) only at collocation points, so its slope
mismatch at an edge, ``G(+-1)``, is a discretisation residual rather than zero; it
is removed (and reported) so that the sign of the gap just outside an edge is
decided by the solution's ``(|s| - 1)^{3/2}`` term, not by that residual.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..discretisation.system import SHARED_BLOCKS_N
from ..io.results import Result
from ..numerics.batched import stacked
from ..numerics.moment_engine import MIN_BLOCK, geometry_cache
from ..numerics.extrema import interpolated_minima, polish_minimum
from ..physics.green_functions import cylinder_displacement_drop, moving_slope
from ..problem.parameters import Parameters

__all__ = ["Validity", "assess", "assess_many", "gap", "gaps", "pressure_samples"]


@dataclass(frozen=True, eq=False, repr=False)
class Validity(Result):
    """Margins of the contact inequalities of one solution.

    Positions are in ``s = (x - sigma)/Delta``; ``s = -1`` is the trailing edge
    ``x = a`` (where the cylinder's surface leaves the contact), ``s = +1`` the
    leading edge ``x = b``.  Pressures are normalised so that their integral over
    the contact is 1; gaps are in units of ``Delta^2 / R``.

    Attributes
    ----------
    valid : bool
        All of: positive load, ``pressure_margin >= 0``, ``gap_margin >= 0`` and
        no tensile edge layer wider than :data:`EDGE_LAYER_TOLERANCE` half-widths
        (``edge_margins >= 0``).
    positive_load : bool
        ``P_H/P > 0``.
    min_pressure, min_pressure_at : float
        Least contact pressure and where (0 at an edge for a valid solution).
    pressure_margin, pressure_margin_at : float
        Least value of ``p(s) / sqrt(1 - s^2)`` over ``-1 <= s <= 1``: negative
        when the pressure is tensile anywhere, including just inside an edge.
    min_gap, min_gap_at : float
        Least gap outside the contact and where (0 at an edge when valid).
    gap_margin, gap_margin_at : float
        Least value of ``g(s) / (|s| - 1)^{3/2}`` outside the contact: negative
        where the bodies interpenetrate.
    edge_log_coefficients : tuple of float
        Coefficients ``k-`` and ``k+`` of the terms ``k sqrt(1 -+ s) ln(1 -+ s)``
        in the pressure at ``s = -1`` and ``+1``:
        ``k = sqrt(2) fHPe (1 - delta1/delta2) psi(+-1) / pi`` (derivation section
        8); zero when ``delta1 = delta2``.  Without the Dundurs term a positive
        ``k`` makes the pressure tensile in a layer just inside that edge however
        fine the discretisation (heat flowing at the edge into the less distortive
        body).  With it the logarithm becomes ``kappa (1 -+ s)^(1/2)``,
        ``kappa = -+ pi k/b``, and whether a layer opens depends also on the edge's
        exponent (D22b, D22c).
    edge_slope_residual : tuple of float
        Slope mismatch ``G`` of the discrete solution at ``s = -1`` and ``+1``
        (zero for the exact solution; a measure of discretisation error).
    edge_layer_log_widths : tuple of float
        Natural logarithm of the width, in half-widths, of the tensile layer inside
        each edge: the depth where the bracket of (D22c) vanishes (``-a/k`` from
        ``p ~ sqrt(1 -+ s) (a + k ln(1 -+ s))`` without the Dundurs term); ``-inf``
        where no layer opens (the widths themselves, :attr:`edge_layer_widths`,
        underflow below 1e-308).
    edge_margins : tuple of float
        The bracket of (D22c) at the tolerated depth, where the edge carries a term
        (``k != 0``): >= 0 exactly when no layer wider than
        :data:`EDGE_LAYER_TOLERANCE` opens (floored at 0 where none opens);
        ``max(a, 0)`` where ``k = 0``.
    strictly_valid : bool
        ``valid`` with no tensile layer of any width, the criterion of Comninou
        and Dundurs (without the Dundurs term: every edge coefficient ``<= 0``).
    margin_change : float or None
        The largest change of the three margins from the solution at ``n/2``: an
        estimate of their error (None when not compared).
    """

    valid: bool
    positive_load: bool
    min_pressure: float
    min_pressure_at: float
    pressure_margin: float
    pressure_margin_at: float
    min_gap: float
    min_gap_at: float
    gap_margin: float
    gap_margin_at: float
    edge_log_coefficients: tuple[float, float]
    edge_slope_residual: tuple[float, float]
    margin_change: float | None = None
    edge_layer_log_widths: tuple[float, float] = (-np.inf, -np.inf)
    edge_margins: tuple[float, float] = (np.inf, np.inf)
    strictly_valid: bool | None = None

    @property
    def edge_layer_widths(self) -> tuple[float, float]:
        """Widths of the tensile edge layers, in half-widths (0: none, or below 1e-308)."""
        return tuple(float(np.exp(x)) for x in self.edge_layer_log_widths)

    def margins(self) -> dict[str, float]:
        """The signed margins, each >= 0 exactly when its inequality holds.

        ``pressure``: least ``p/sqrt(1 - s^2)``; ``gap``: least ``g/(|s| - 1)^{3/2}``;
        ``edge``: the smaller of :attr:`edge_margins` (section 8).
        """
        return {"pressure": self.pressure_margin, "gap": self.gap_margin,
                "edge": min(self.edge_margins)}

    def certain(self) -> bool:
        """Whether every margin's sign is beyond its change since the coarser level."""
        if self.margin_change is None:
            return True
        # A margin of exactly zero is so by construction (no edge term when
        # delta1 = delta2 or fHPe = 0): its sign is not in doubt.
        return all(abs(m) > self.margin_change or m == 0.0 for m in self.margins().values())

    @property
    def failures(self) -> tuple[str, ...]:
        """The inequalities that fail, each with where: e.g. ``"gap margin -0.02 at s = 1.013"``."""
        out = []
        if not self.positive_load:
            out.append("load ratio P_H/P <= 0")
        if self.pressure_margin < 0.0:
            out.append(f"pressure margin {self.pressure_margin:.3g} at s = "
                       f"{self.pressure_margin_at:.4g} ({_edge_name(self.pressure_margin_at)})")
        if self.gap_margin < 0.0:
            out.append(f"gap margin {self.gap_margin:.3g} at s = {self.gap_margin_at:.4g} "
                       f"({_edge_name(self.gap_margin_at)})")
        for m, lw, at in zip(self.edge_margins, self.edge_layer_log_widths, (-1.0, 1.0)):
            if m < 0.0:
                out.append(f"tensile layer {_width(lw)} half-widths wide inside the "
                           f"{_edge_name(at)} (edge term, derivation sections 8 and 5c; "
                           f"tolerated: {EDGE_LAYER_TOLERANCE:g})")
        return tuple(out)

    @property
    def reason(self) -> str:
        """``"valid"``, or ``"invalid: "`` and the failing inequalities; a tolerated
        edge layer is named."""
        if not self.valid:
            return "invalid: " + "; ".join(self.failures)
        layers = [f"{_width(lw)} half-widths wide inside the {_edge_name(at)}"
                  for lw, at in zip(self.edge_layer_log_widths, (-1.0, 1.0)) if lw > -np.inf]
        if layers:
            return ("valid (strictly invalid: tensile edge layer " + " and ".join(layers)
                    + f", below the tolerated {EDGE_LAYER_TOLERANCE:g})")
        return "valid"

    def _summary(self) -> str:
        return (f"valid={self.valid}, pressure_margin={self.pressure_margin:.3g}, "
                f"gap_margin={self.gap_margin:.3g}, edge_margin={min(self.edge_margins):.3g}")

    def _record(self) -> dict:
        """The margins as a record (:meth:`~thermocontact.io.results.Result.to_dict`)."""
        return {
            "valid": self.valid,
            "reason": self.reason,
            "positive_load": self.positive_load,
            "min_pressure": self.min_pressure,
            "min_pressure_at": self.min_pressure_at,
            "pressure_margin": self.pressure_margin,
            "pressure_margin_at": self.pressure_margin_at,
            "min_gap": self.min_gap,
            "min_gap_at": self.min_gap_at,
            "gap_margin": self.gap_margin,
            "gap_margin_at": self.gap_margin_at,
            "strictly_valid": self.strictly_valid,
            "edge_log_coefficients": list(self.edge_log_coefficients),
            "edge_layer_widths": list(self.edge_layer_widths),
            "edge_layer_log_widths": [x if np.isfinite(x) else None
                                      for x in self.edge_layer_log_widths],
            "edge_margins": list(self.edge_margins),
            "edge_slope_residual": list(self.edge_slope_residual),
            "margin_change": self.margin_change,
        }


#: Widest tensile layer inside an edge, in half-widths, that is not held against a
#: solution: the layer opened by a positive edge coefficient (D22) has width
#: exp(-a/k), which is below 1e-6 of the half-width (a nanometre on a millimetre
#: contact, far below any surface's roughness) for every k small enough that the
#: strict criterion k <= 0 would condemn an otherwise sound contact.
EDGE_LAYER_TOLERANCE = 1e-6
#: Depth 1 -+ s at which the bracket a + k ln(1 -+ s) of (D22) is read off the
#: solution and carried to EDGE_LAYER_TOLERANCE along its slope k.  At 1e-3 the next
#: term, O((1 -+ s) ln(1 -+ s)), still bends the bracket by 1.6e-2 of a; at 1e-5 the
#: bracket agrees with the one read at 1e-6 to 2e-4, and the graded solution
#: resolves it to 1e-4 from n = 64 (Pe = 5, K2/K1 = 10, delta1/delta2 = 0 and 2, and
#: Pe = 1000, delta1/delta2 = 0.5; derivation section 8).
_EDGE_DEPTH = 1e-5


def _width(log_width: float) -> str:
    """A layer width for a message: ``3.1e-12`` or, below 1e-300, ``e^-3512``."""
    if log_width > -690.0:
        return f"{np.exp(log_width):.2g}"
    return f"e^{log_width:.0f}"


def _edge_name(s: float) -> str:
    """The edge nearer to ``s``: ``s > 0`` the leading edge."""
    return "leading edge" if s > 0.0 else "trailing edge"


#: Points per block of :func:`gap`: no more than the moments take in one block, and
#: from n = 512 fewer, so that a block's point geometry (points times the common rule's
#: nodes, about 4 n) stays near 4 MB.
GAP_BLOCK = MIN_BLOCK
GAP_ENTRIES = 2**16
GAP_BLOCK_MIN = 32


def gap(par: Parameters, rep, phi, psi, load_ratio, sigma, lam, s):
    """Gap ``g(s)`` outside the contact, in units of ``Delta^2 / R``.

    Implements derivation eqs. (D20)-(D21): for ``s > 1``
    ``g = sigma (s - 1) + (s^2 - 1)/2 - (pi / 2L) [J_C - F J_T]`` with the Cauchy
    part ``J_C = sum_j a_j I_{j+1}(s)``, the thermal part
    ``J_T = d/c integral (p + q)(r) [E(c(1 - r)) - E(c(s - r))] dr + (1 - lam)(s - 1)/2``,
    and the edge residual ``G(1)(s - 1)`` removed; mirrored for ``s < -1``.

    Parameters
    ----------
    par : Parameters
    rep : Representation
        The solution's representation; it integrates the cylinder's kernels
        against the solution the method's way.
    phi, psi : ndarray, shape (n,)
        Nodal values of the unknowns.
    load_ratio, sigma, lam : float
        ``P_H/P``, ``sigma/Delta`` and ``lambda`` of the solution.
    s : array_like
        Points with ``|s| >= 1``.

    Returns
    -------
    g : ndarray
        Gap at ``s``.
    residual : tuple of float
        ``(G(-1), G(1))``.
    """
    s = np.atleast_1d(np.asarray(s, dtype=float))
    g, residual = gaps(par, rep, np.asarray(phi, dtype=float)[None, :],
                       np.asarray(psi, dtype=float)[None, :],
                       *(np.array([v], dtype=float)
                         for v in (par.fhpe, load_ratio, sigma, lam)), s)
    return g[0], (float(residual[0, 0]), float(residual[0, 1]))


def gaps(par: Parameters, rep, phi, psi, fhpe, load_ratio, sigma, lam, s):
    """:func:`gap` of ``m`` solutions that differ only in ``fHPe`` and the closure,
    at the same points ``s`` (a grid line: every row operator applied once to all).

    Parameters
    ----------
    par : Parameters
        Everything but ``fhpe`` (which is ``fhpe``'s, per solution).
    rep : Representation
    phi, psi : ndarray, shape (m, n)
    fhpe, load_ratio, sigma, lam : ndarray, shape (m,)
    s : ndarray
        Points with ``|s| >= 1``.

    Returns
    -------
    g : ndarray, shape (m, s.size)
        Gap in units of ``Delta^2 / R`` (D20-D21).
    residual : ndarray, shape (m, 2)
        ``(G(-1), G(1))`` of each solution.
    """
    s = np.atleast_1d(np.asarray(s, dtype=float))
    block = max(GAP_BLOCK_MIN, min(GAP_BLOCK, GAP_ENTRIES // rep.n))
    if s.size > block:
        # The kernels below carry each point's own distance past the edge: blocks of
        # points small enough for the moments to take whole.  From n = 512 each
        # block's point geometry is dropped once its row operators are formed (17 MB
        # for 256 points at n = 1024); below, it is kept for the next grid line's
        # kernels at the same points (1 MB at n = 32).
        parts = []
        for i in range(0, s.size, block):
            with geometry_cache(rep.n).transient(when=rep.n >= SHARED_BLOCKS_N):
                parts.append(gaps(par, rep, phi, psi, fhpe, load_ratio, sigma, lam,
                                  s[i:i + block]))
        return np.concatenate([g for g, _ in parts], axis=1), parts[0][1]
    F, L = fhpe, load_ratio
    cauchy_left, cauchy_right = rep.cauchy_edges_many(phi).T
    eta = par.eta
    # The moving bodies' slope kernels sgn(c) N(c u) H(c u), each with its weight on
    # the heat it receives: the cylinder d (p + q) with c > 0, a moving half-plane
    # (p - q) with c2 of either sign (section 5b); a stationary half-plane's
    # sgn(u)/2 is integrated exactly below.
    c2 = par.half_plane_scale
    moving = []
    if par.delta1_over_delta2:
        moving.append(("cylinder", par.cylinder_scale, par.delta1_over_delta2, 1.0))
    if c2:
        moving.append(("half-plane", c2, 1.0, -1.0))
    if not np.any(F):
        # No heat: every thermal term is multiplied by F = 0, so its kernels (a grid
        # line's Hertzian point) are not formed.
        moving = []

    def against(key, kernel, points, scale, sign):
        # integral K (p + sign q) dr with q = q' + eta p; the row operators depend
        # only on the representation, the kernel's scale and the points, so sweeps
        # reuse them.
        points = np.asarray(points, dtype=float)
        ib, iq = rep.rows((key, scale, points.tobytes()),
                          lambda: rep.integrate(kernel, points, scale=abs(scale)))
        return (1.0 + sign * eta) * stacked(ib, phi).T + sign * stacked(iq, psi).T

    # Residual slope mismatch at the edges (D14 evaluated at s = -1, +1).  A moving
    # body's kernel vanishes at the edge its material reaches last (c > 0: s = -1).
    zero = np.zeros_like(F)
    thermal_edges = [zero, zero] if c2 else [-0.5 * (1.0 - lam), 0.5 * (1.0 - lam)]
    for name, c, weight, sign in moving:
        edge = 1.0 if c > 0.0 else -1.0
        slope = against("slope " + name, lambda u, c=c: moving_slope(u, c), [edge], c, sign)
        thermal_edges[c > 0.0] = thermal_edges[c > 0.0] + weight * slope[0]
    g_left_edge = cauchy_left - F * thermal_edges[0] - (2 / np.pi) * L * (sigma - 1.0)
    g_right_edge = cauchy_right - F * thermal_edges[1] - (2 / np.pi) * L * (sigma + 1.0)

    out = np.zeros((F.size, s.size))
    # Work with the distance tt = |s| - 1 past the edge (exact in floating point
    # near the edge) so that no O(1) quantity is formed and cancelled there.  Each
    # part of j is an integral over the interval between the edge and s, in
    # increasing t (from s to -1 on the left).  Arrays are (point, solution).
    for side, edge_residual in ((1.0, g_right_edge), (-1.0, g_left_edge)):
        on = side * s > 1.0
        if not np.any(on):
            continue
        tt = side * s[on] - 1.0
        right = side > 0.0
        jc = rep.cauchy_outside_many(phi, tt, right).T
        col = tt[:, None]
        jt = 0.0 if c2 else side * 0.5 * (1.0 - lam)[None, :] * col
        for name, c, weight, sign in moving:
            if c * side < 0.0:
                continue  # the body's material has not yet reached this side
            # The kernel's antiderivative is -E(c u)/|c|: the integral is
            # side [E(|c|(1 -+ r)) - E(|c|(1 -+ r) + |c| tt)] / |c|, a kernel of
            # u = s - r in which |c| (1 -+ r) = c u - |c| tt on either side.
            h = abs(c) * col
            drop = lambda u, c=c, h=h: cylinder_displacement_drop(c * u - h, h)
            jt = jt + side * (weight / abs(c)) * against("drop " + name, drop,
                                                         side * (1.0 + tt), c, sign)
        j = jc - F[None, :] * jt - edge_residual[None, :] * col
        out[:, on] = (side * sigma[None, :] * col + col * (1.0 + 0.5 * col)
                      - side * np.pi / (2 * L)[None, :] * j).T
    return out, np.column_stack([g_left_edge, g_right_edge])


def _grid_gaps(par: Parameters, rep, phi, psi, fhpe, load_ratio, sigma, lam, so, base):
    """:func:`gaps` at the gap margin's points ``so``: an extended grid's points that are
    also ``base``'s, the grid without the extension (:func:`_outside_grid`), by
    ``base``'s row operators, which every solution of the same edge terms shares, and
    only the extension's own points by new ones (the row operators are per point: the
    same numbers but for rounding)."""
    known = np.zeros(so.size, dtype=bool) if base is None else np.isin(so, base)
    if not known.any():
        return gaps(par, rep, phi, psi, fhpe, load_ratio, sigma, lam, so)
    g_base, residual = gaps(par, rep, phi, psi, fhpe, load_ratio, sigma, lam, base)
    g = np.empty((g_base.shape[0], so.size))
    g[:, known] = g_base[:, np.searchsorted(base, so[known])]
    if not known.all():
        g[:, ~known] = gaps(par, rep, phi, psi, fhpe, load_ratio, sigma, lam, so[~known])[0]
    return g, residual


def pressure_samples(n: int) -> int:
    """Samples of the pressure margin ``phi`` over the contact, evenly in the
    representation's variable (``tau``): 32 a period of its highest term ``cos(n tau)``,
    ``16 n + 1``, at least 513 and at most 2049 (from n = 128 on).  The least sample is
    interpolated or polished between its neighbours; 2049 at n <= 32 move the margin
    by 3e-12 at most (tests/test_validity.py; 5.9e-13 over a 200 x 200 map)."""
    return int(min(2049, max(513, 16 * n + 1)))


#: Distances ``|s| - 1`` where the gap is checked: 160 points from 1e-8 to 1e3,
#: extended when the terms linear in ``s`` could still compete with ``s^2/2`` there.
_GAP_T = np.geomspace(1e-8, 1e3, 160)


def _outside_end(par: Parameters, fhpe, sigma, lam, load_ratio):
    """How far past the edges the gap is checked, out to where ``s^2/2`` dominates
    every other term: None for :data:`_GAP_T`'s own end, else the extended end."""
    d = par.delta1_over_delta2
    reach = 2.0 + 2.0 * abs(sigma)
    reach += np.pi / abs(load_ratio) * fhpe * (2.0 + 2.0 * abs(lam)) * (1.0 + d)
    return float(min(4.0 * reach, 1e8)) if 4.0 * reach > _GAP_T[-1] else None


def _outside_grid(end, band):
    """Points outside the contact out to ``end`` (:func:`_outside_end`).

    Where an edge coefficient is positive (``band``, per edge) the bodies also
    overlap in a layer just outside that edge (the gap's face of the same logarithm,
    section 8): the gap margin is taken outside the tolerated width there, as the
    pressure margin is inside.  The side's points are the same geometric sequence
    moved out to start at the tolerated width: sampled margins (polish=False) are
    interpolated in the index, which wants the spacing even in ln(|s| - 1).
    """
    t = _GAP_T
    if end is not None:
        t = np.concatenate([t, np.geomspace(t[-1], end, 41)[1:]])
    so = np.concatenate([-1.0 - t[::-1], 1.0 + t])
    for side, opens in ((-1.0, band[0]), (1.0, band[1])):
        if opens:
            on_side = np.sign(so) == side
            t = np.sort(np.abs(so[on_side]) - 1.0)
            t = t * (EDGE_LAYER_TOLERANCE / t[0])
            t = t[t <= 1.0001 * (np.abs(so[on_side]).max() - 1.0)]
            so = np.sort(np.concatenate([so[~on_side], side * (1.0 + t)]))
    return so


#: With ``polish=False``, margins whose interpolated minimum is nearer zero than
#: this are still polished on the closed forms, so that their signs are exact.  It
#: is 1500 times the largest difference between the two minima measured on the
#: margins of 216 solutions (6.4e-8; tests/test_validity.py).
POLISH_BAND = 1e-4


def least_of(f, x, values, i, polish):
    """The least value near sample ``i``: on the closed form ``f``, or from the samples.

    The samples are interpolated in their index (the representations space them
    evenly in the variable in which the margins are smooth: ``tau`` or
    ``ln(|s| - 1)``), the position mapped back linearly.
    """
    at, value = least_of_many(lambda _: f, x, np.asarray(values, dtype=float)[None, :], [i],
                              polish)
    return float(at[0]), float(value[0])


def least_of_many(f_of, x, values, i, polish):
    """:func:`least_of` of several margins sampled at the same ``x``: ``values`` of
    shape (m, N), ``i`` each row's least sample, ``f_of(r)`` row ``r``'s closed form.
    The samples' interpolants are minimised together; only the rows polished (all with
    ``polish``, else those within :data:`POLISH_BAND` of zero) evaluate ``f``."""
    values = np.asarray(values, dtype=float)
    i = np.asarray(i, dtype=int)
    at, value = np.empty(len(i)), np.empty(len(i))
    todo = range(len(i))
    if not polish:
        k = np.arange(len(x), dtype=float)
        at_k, value = interpolated_minima(k, values, i)
        at = np.interp(at_k, k, x)
        todo = np.flatnonzero(~(np.abs(value) > POLISH_BAND))
    for r in todo:
        at[r], value[r] = polish_minimum(f_of(r), x, values[r], int(i[r]))
    return at, value


def _expm1_over(r, x):
    """``expm1(r x)/r``, ``x`` at ``r = 0``: the bracket's edge term per unit ``k``."""
    return x if r == 0.0 else np.expm1(r * x) / r


def edge_terms(par: Parameters, rep, phi, psi):
    """The pressure's bracket at each edge and the tensile layer it opens (D22, D22b).

    Near an edge, at depth ``e = 1 -+ s``, ``p/e^x = a + k t E(r, ln e)`` with the
    edge's exponent ``x`` (1/2, or the Dundurs term's), ``r = 1/2 - x``,
    ``E(r, y) = expm1(r y)/r`` (``y`` at ``r = 0``), ``k`` the coefficient of (D22) and
    ``t = arctan(b)/b`` (1 at ``b = 0``): with the Dundurs term the logarithm is
    ``kappa ((1 -+ s)^(1/2) - ...)``, ``kappa r = k t`` (D22b), and as ``b -> 0`` it
    becomes the logarithm continuously.  The bracket is monotone in ``ln e``; a layer
    opens where it is negative at the edge itself, and its width is the depth where it
    vanishes.  ``a`` is read off the solution at depth :data:`_EDGE_DEPTH`.

    Returns
    -------
    k_log, exponents, margins, log_widths : ndarray, shape (2,)
        At ``s = -1`` and ``+1``.
    layer : ndarray of bool, shape (2,)
        Where a layer opens.  Wherever an edge term exists (``k != 0``) the
        pressure and gap margins are taken outside the tolerated width, layer or not,
        so that they stay continuous where a layer appears.
    """
    k_log, exponents, margins, log_widths, layer = edge_terms_many(
        par, rep, np.asarray(phi, dtype=float)[None, :], np.asarray(psi, dtype=float)[None, :],
        np.array([par.fhpe]))
    return k_log[0], exponents, margins[0], log_widths[0], layer[0]


def edge_terms_many(par: Parameters, rep, phi, psi, fhpe):
    """:func:`edge_terms` of ``m`` solutions that differ only in ``fHPe`` and the
    closure: ``phi``, ``psi`` of shape (m, n), ``fhpe`` of shape (m,); every result
    but ``exponents`` gains a first axis of length m."""
    b = par.free_term
    psi_edges = rep.psi_edges_many(psi)
    k_log = (np.sqrt(2.0) * np.asarray(fhpe, dtype=float)[:, None]
             * (1.0 - par.delta1_over_delta2) * psi_edges / np.pi)
    t = float(np.arctan(b) / b) if b else 1.0
    exponents = np.array([1.0 - rep.alpha, rep.alpha])
    e = _EDGE_DEPTH
    near = np.array([-1.0 + e, 1.0 - e])
    p_near = stacked(rep.pressure_matrix(near), phi)
    margins, log_widths, layer = _edge_brackets(p_near, k_log, exponents, t)
    return k_log, exponents, margins, log_widths, layer


def _edge_brackets(p_near, k_log, exponents, t):
    """The edge margins, the layers' log widths and whether a layer opens, of the
    pressures ``p_near`` (m, 2) at depth :data:`_EDGE_DEPTH` from the edges with the
    coefficients ``k_log`` (m, 2) (:func:`edge_terms`): per edge, all solutions at once,
    each by the operations it would take alone."""
    e = _EDGE_DEPTH
    count = p_near.shape[0]
    margins, log_widths = np.empty((count, 2)), np.empty((count, 2))
    layer = np.empty((count, 2), dtype=bool)
    for i in range(2):
        r, kt = 0.5 - exponents[i], k_log[:, i] * t
        a = p_near[:, i] / e ** exponents[i] - kt * _expm1_over(r, np.log(e))
        has = kt != 0.0  # an edge term (NaN counts, as its truth value does)
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            # The bracket at the edge itself: -inf * sign(k) unless r > 0, where E -> -1/r.
            at_edge = a - kt / r if r > 0.0 else np.where(has, -np.inf * np.sign(kt), a)
            # Without an edge term a tensile edge is no layer.
            layer[:, i] = opens = has & (at_edge < 0.0)
            at_tolerance = a + kt * _expm1_over(r, np.log(EDGE_LAYER_TOLERANCE))
            # A layer: the bracket at the tolerated depth.  No layer yet: there where
            # positive, the value it takes when a layer opens (so the margin is
            # continuous).  No edge term: the bracket where positive, else 0 (a tensile
            # edge without a layer is the pressure margin's to judge).  (max(x, 0.0): x
            # unless 0 is greater, NaN and -0.0 kept.)
            bracket = np.where(has, at_tolerance, a)
            margins[:, i] = np.where(opens, at_tolerance,
                                     np.where(0.0 > bracket, 0.0, bracket))
            # Depth where a + kt E(r, y) = 0: y = -a/kt, or log1p(-a r/kt)/r; 0 where
            # tensile from the whole edge region inward.
            depth = -a / kt if r == 0.0 else np.log1p(-a * r / kt) / r
            log_widths[:, i] = np.where(opens, np.where(a <= 0.0, 0.0, depth), -np.inf)
    return margins, log_widths, layer


def assess(par: Parameters, rep, phi, psi, load_ratio, sigma, lam, *, polish=True) -> Validity:
    """Evaluate every contact inequality of a discrete solution.

    The pressure margin ``phi = p/sqrt(1 - s^2)`` is sampled at
    :func:`pressure_samples` points of ``[-1, 1]`` (edges included; 513 up to n = 32,
    2049 from n = 128), spaced as the method's representation suggests (its
    ``phi_samples``); the gap margin ``g/(|s| - 1)^{3/2}`` at 160 points on
    each side, spaced geometrically from ``1e-8`` to ``1e3`` past the edge (further
    when the ``s^2/2`` term does not yet dominate there).  Each least sample is
    then polished on the closed forms between its neighbours
    (:func:`~thermocontact.numerics.extrema.polish_minimum`; the gap's in
    ``ln(|s| - 1)``).

    With ``polish=False`` (maps: no new kernel evaluations per solution) the least
    value is that of a local interpolant of the samples
    (:func:`~thermocontact.numerics.extrema.interpolated_minimum`), polished on
    the closed forms only when it is within :data:`POLISH_BAND` of zero.

    Returns
    -------
    Validity
    """
    return assess_many([par], rep, np.asarray(phi, dtype=float)[None, :],
                       np.asarray(psi, dtype=float)[None, :], [load_ratio], [sigma], [lam],
                       polish=polish)[0]


def assess_many(pars, rep, phi, psi, load_ratio, sigma, lam, *, polish=True) -> list:
    """:func:`assess` of ``m`` solutions that differ only in ``fHPe`` and the closure
    (a grid line): the samples of all are formed by the same row operators at once,
    and the least samples interpolated together.

    Parameters
    ----------
    pars : sequence of Parameters
        Each solution's; equal but for ``fhpe``.
    rep : Representation
    phi, psi : ndarray, shape (m, n)
    load_ratio, sigma, lam : array_like, shape (m,)
    polish : bool

    Returns
    -------
    list of Validity
        Each as :func:`assess` gives it.
    """
    # The point geometry of the checks' kernels serves their row operators only, which
    # the row-operator cache keeps: from n = 512 dropped at the end (30 MB at n = 512
    # and 1024); below kept for the next grid line's kernels at the same points (a few
    # MB).
    with geometry_cache(rep.n).transient(when=rep.n >= SHARED_BLOCKS_N):
        return _assess_many(pars, rep, phi, psi, load_ratio, sigma, lam, polish)


def _assess_many(pars, rep, phi, psi, load_ratio, sigma, lam, polish):
    par = pars[0]
    phi, psi = np.asarray(phi, dtype=float), np.asarray(psi, dtype=float)
    F = np.array([p.fhpe for p in pars], dtype=float)
    L, sigma, lam = (np.asarray(v, dtype=float) for v in (load_ratio, sigma, lam))
    m = F.size
    k_log, exponents, edge_margins, log_widths, layer = edge_terms_many(par, rep, phi, psi, F)
    # The edges whose term can open a layer: their tolerated width is the edge
    # margin's to judge, not the pressure's or the gap's.
    band = k_log != 0.0  # (a layer needs an edge term)

    sp, phis = rep.phi_samples_many(phi, pressure_samples(rep.n))
    p = rep.pressure_weight(sp)[None, :] * phis
    ip = np.argmin(p, axis=1)
    phi_min, phi_min_at = np.empty(m), np.empty(m)
    # Where a layer opens, phi -> -infinity at that edge (D22): the pressure margin
    # is taken outside the tolerated layer, which the edge margin covers.
    for key in {tuple(row) for row in band}:
        rows = np.flatnonzero(np.all(band == key, axis=1))
        keep = np.ones(sp.size, dtype=bool)
        if key[0]:
            keep &= sp >= -1.0 + EDGE_LAYER_TOLERANCE
        if key[1]:
            keep &= sp <= 1.0 - EDGE_LAYER_TOLERANCE
        if rows.size == m and keep.all():  # (the common case: no copy)
            sp_in, phis_in = sp, phis
        else:
            sp_in, phis_in = sp[keep], phis[np.ix_(rows, keep)]
        phi_min_at[rows], phi_min[rows] = least_of_many(
            lambda r: (lambda x, ph=phi[rows[r]]: rep.phi_at(ph, x)), sp_in, phis_in,
            np.argmin(phis_in, axis=1), polish)

    # The gap's points: the same for every solution that reaches as far and has the
    # same edge terms.
    grids = {}
    for r in range(m):
        key = (_outside_end(par, F[r], sigma[r], lam[r], L[r]), bool(band[r, 0]),
               bool(band[r, 1]))
        grids.setdefault(key, []).append(r)
    min_gap, min_gap_at = np.empty(m), np.empty(m)
    gap_min, gap_min_at = np.empty(m), np.empty(m)
    residual = np.empty((m, 2))
    for (end, *key), rows in grids.items():
        rows = np.array(rows)
        so = _outside_grid(end, key)
        g, residual[rows] = _grid_gaps(par, rep, phi[rows], psi[rows], F[rows], L[rows],
                                       sigma[rows], lam[rows], so,
                                       None if end is None else _outside_grid(None, key))
        ig = np.argmin(g, axis=1)
        # g ~ (|s| - 1)^(1 + exponent) outside each edge (3/2 without the Dundurs term).
        power = np.where(so > 0.0, 1.0 + exponents[1], 1.0 + exponents[0])
        margin = g / (np.abs(so) - 1.0) ** power
        im = np.argmin(margin, axis=1)
        # The gap vanishes at both edges by construction: include them in the minimum.
        g_least = g[np.arange(rows.size), ig]
        open_ = g_least > 0.0
        min_gap[rows] = np.where(open_, 0.0, g_least)
        min_gap_at[rows] = np.where(open_, np.sign(so[im]), so[ig])
        # Polish the gap margin in y = ln(|s| - 1) on the side of its least sample.
        sides = np.sign(so[im])
        for side in (-1.0, 1.0):
            on = np.flatnonzero(sides == side)
            if on.size == 0:
                continue
            on_side = np.flatnonzero(np.sign(so) == side)
            y = np.log(np.abs(so[on_side]) - 1.0)
            order = np.argsort(y)
            y, ms = y[order], margin[np.ix_(on, on_side[order])]
            side_power = 1.0 + exponents[int(side > 0.0)]

            def gap_margin_of(k, side=side, side_power=side_power):
                r = rows[on[k]]

                def gap_margin(yy):
                    tt = np.exp(yy)
                    gg, _ = gap(pars[r], rep, phi[r], psi[r], L[r], sigma[r], lam[r],
                                side * (1.0 + tt))
                    return gg / tt**side_power
                return gap_margin
            y_min, gap_min[rows[on]] = least_of_many(gap_margin_of, y, ms,
                                                     np.argmin(ms, axis=1), polish)
            gap_min_at[rows[on]] = side * (1.0 + np.exp(y_min))

    positive = L > 0.0
    sound = positive & (phi_min >= 0.0) & (gap_min >= 0.0)
    valid = sound & np.all(edge_margins >= 0.0, axis=1)
    strict = sound & ~np.any(layer, axis=1)
    # Plain Python numbers, converted once per array.
    fields = {"valid": valid.tolist(), "positive_load": positive.tolist(),
              "min_pressure": p[np.arange(m), ip].tolist(), "min_pressure_at": sp[ip].tolist(),
              "pressure_margin": phi_min.tolist(), "pressure_margin_at": phi_min_at.tolist(),
              "min_gap": min_gap.tolist(), "min_gap_at": min_gap_at.tolist(),
              "gap_margin": gap_min.tolist(), "gap_margin_at": gap_min_at.tolist(),
              "edge_log_coefficients": list(map(tuple, k_log.tolist())),
              "edge_slope_residual": list(map(tuple, residual.tolist())),
              "edge_layer_log_widths": list(map(tuple, log_widths.tolist())),
              "edge_margins": list(map(tuple, edge_margins.tolist())),
              "strictly_valid": strict.tolist()}
    return Validity.build_each(fields, zip(*fields.values()))
