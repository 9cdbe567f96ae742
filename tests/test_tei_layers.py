"""Thermoelastic instability of layers (docs/derivation.md, "Thermoelastic instability of
layers", L1-L13): the half-plane limit, the closed form of a layer between non-conducting
pads, two methods for every geometry, a count of the unstable roots, exact scalings,
plane stress, the brake stop against a time integration, the call and the command."""

import json
import math

import numpy as np
import pytest
from scipy.linalg import expm
from scipy.optimize import minimize_scalar

from thermocontact.api import tei
from thermocontact.cli import main
from thermocontact.discretisation.tei_depth import layup_modes, layup_operator
from thermocontact.physics.reference_solutions import (layer_compliance, layer_neutral_speed,
                                                        layer_thermal_displacement)
from thermocontact.physics.tei import SlidingPair, modes
from thermocontact.physics.tei_layers import (layup_dispersion, layups, plane_stress_material)
from thermocontact.problem.materials import Material, get_material
from thermocontact.problem.validation import InputError
from thermocontact.studies.tei import critical_speed, family_minimum
from thermocontact.studies.tei_layers import Layered, neutral_point, newton_roots

STEEL = get_material("steel")
IRON = get_material("cast-iron")
PAD = get_material("organic-composite-brake-block")
SINTERED = get_material("sintered-brake-material")
#: Non-conducting pads: the organic pad with K -> 0, and a rigid one.
NC_PAD = Material("nc-pad", PAD.E, PAD.nu, PAD.alpha, 0.0, 0.0)
RIGID = Material("rigid", 1e30, 0.3, 1e-5, 0.0, 0.0)
M = 2.0 * math.pi / 0.05


def _family(name, slider, counterface, friction=0.4, **kw):
    return Layered(name, layups(slider, counterface, friction, **kw)[name])


def _rel(a, b):
    return abs(a - b) / abs(b)


# --- the solutions of a layer (L1-L3) -------------------------------------------------

@pytest.mark.parametrize("plane", ["strain", "stress"])
def test_solutions_satisfy_the_discretised_equations(plane):
    """Each closed-form solution of a moving layer (L2, L3; at Gamma near 1 too, where
    (L3) is a divided difference), sampled at the Chebyshev points of the second method,
    satisfies its discretised heat and Navier equations, and its face fields are those
    of the discretisation's differentiation, to 1e-9 of the terms."""
    from thermocontact.discretisation.tei_depth import _body_operators, _chebyshev
    from thermocontact.physics.tei_layers import Body, body_fields

    mat = IRON if plane == "strain" else plane_stress_material(IRON)
    body = Body(IRON, 0.02, True)
    refs = (IRON.mu, IRON.alpha * (1 + IRON.nu) / (1 - IRON.nu), IRON.K)
    m, V, n = 84.0, 20.0, 40
    rows, F, mass, cols, ninner = _body_operators(body, n, m, V, plane, True, refs)
    x = _chebyshev(n)[0]
    depths = 0.02 * (1 - x) / 2
    for b in (0.3 - 1600j, -1j * m * V + 1e-9 * IRON.k * m * m):
        fields = body_fields(body, b, m, V, refs, depths, mat=mat)
        faces = body_fields(body, b, m, V, refs, [0.0, 0.02], mat=mat)
        for c in range(body.columns):
            T = fields[:, 4, c] / (2 * refs[0] * refs[1])
            X = np.concatenate([T, fields[:, 0, c], fields[:, 1, c]]) / np.repeat(
                [1.0, 2 * refs[0] * m, 2 * refs[0] * m], n + 1)
            res = rows @ X
            res[:len(mass)] -= b * T[1:-1]
            terms = np.abs(rows) @ np.abs(X)          # each row's largest possible sum
            assert np.all(np.abs(res) <= 1e-9 * np.max(terms)), (b, c)
            assert np.max(np.abs(F @ X - faces[:, :, c])) <= 1e-9 * np.max(np.abs(faces[:, :, c]))


def test_depth_operator_does_not_depend_on_the_collocations_kept():
    """The bodies' collocations are kept between calls (a disc's two families share them
    at a wavenumber and speed): each family's operator, its bodies' collocations made
    for the other family first, is the one made afresh; those kept are read-only, and
    emptied by clear_caches."""
    from thermocontact import clear_caches
    from thermocontact.discretisation.tei_depth import (_body_collocation, _body_operators,
                                                        _chebyshev)

    def clear():
        _body_operators.cache_clear()
        _body_collocation.cache_clear()

    lay = layups(IRON, PAD, 0.4, slider_thickness=0.012, counterface_thickness=0.01)
    for v in (0.001, 20.0):              # two bodies; four, the thermal skins split off
        clear()
        shared = [layup_operator(lay[k], M, v, 12) for k in ("symmetric", "antisymmetric")]
        assert _body_operators.cache_info().hits > 0     # the second family's were kept
        fresh = []
        for k in ("symmetric", "antisymmetric"):
            clear()
            fresh.append(layup_operator(lay[k], M, np.asarray(v), 12))   # a 0-d speed
        for a, b in zip(shared, fresh):
            np.testing.assert_array_equal(a, b)
        assert np.max(np.abs(shared[0] - shared[1])) > 0.0      # two families' operators
        # Made at another speed first (the layers' collocations kept without their
        # convection, reused where no thermal skin is split off): the same operator,
        # to the last bit.
        clear()
        layup_operator(lay["symmetric"], M, 3.0 * v, 12)
        again = layup_operator(lay["symmetric"], M, v, 12)
        assert (_body_collocation.cache_info().hits > 0) == (v < 1.0)
        assert again.tobytes() == fresh[0].tobytes()
    rows, F = _body_operators(lay["symmetric"].bodies[0], 12, M, 20.0, "strain", False,
                              lay["symmetric"].references())[:2]
    assert not rows.flags.writeable and not F.flags.writeable
    # The public clear_caches empties them.
    clear_caches()
    assert all(f.cache_info().currsize == 0
               for f in (_body_operators, _body_collocation, _chebyshev))


# --- the derivatives of the dispersion function in closed form (L16) -----------------

@pytest.mark.parametrize("geometry", [
    dict(slider_thickness=0.012, counterface_thickness=0.010),
    dict(counterface_thickness=0.010),
    dict(slider_thickness=0.012, faces=1),
    dict(slider_thickness=0.004, counterface_thickness=0.002, separator=STEEL,
         separator_thickness=0.002)])
def test_log_derivatives_against_finite_differences(geometry):
    """d ln D/db and d ln D/dV (Jacobi's formula) against fourth-order central
    differences of D, to 1e-7: growing and decaying b, a mode's frequency on either
    body (Gamma near 1, the divided difference of (L3) in series, and far from it)."""
    V = 20.0
    for name, lay in layups(IRON, PAD, 0.4, **geometry).items():
        fam = Layered(name, lay)
        for b in (3.0 + 40j, -1.0 - 1000j, 0.3j * fam.scale(M), -1j * M * V + 0.2 * fam.scale(M)):
            got = fam.log_derivatives(b, M, V)

            def D(db, dv):
                return layup_dispersion(lay, b + db, M, V + dv)

            # Steps of a thousandth of the scale D varies on: in b about either body's
            # frame, in V about the moving bodies' (L10).
            hb = 1e-3 * (min(abs(b), abs(b + 1j * M * V)) + fam.scale(M))
            hv = 1e-3 * (abs(b + 1j * M * V) + fam.scale(M)) / M
            fd = [(-D(2 * h * e, 2 * h * (1 - e)) + 8 * D(h * e, h * (1 - e))
                   - 8 * D(-h * e, -h * (1 - e)) + D(-2 * h * e, -2 * h * (1 - e)))
                  / (12 * h * D(0, 0)) for h, e in ((hb, 1), (hv, 0))]
            assert abs(got[0] - fd[0]) < 1e-7 * abs(fd[0]), (name, b)
            assert abs(got[1] - fd[1]) < 1e-7 * abs(fd[1]), (name, b)


# --- every thickness to infinity: the half-planes ------------------------------------

@pytest.mark.parametrize("dundurs", [True, False])
@pytest.mark.parametrize("geometry", [
    dict(slider_thickness=1.0), dict(slider_thickness=1.0, faces=1),
    dict(counterface_thickness=1.0),
    dict(slider_thickness=1.0, counterface_thickness=1.0, backing="bonded-insulated")])
def test_thick_layers_are_half_planes(geometry, dundurs):
    """m d/2 = 63: the layers' modes are the half-planes' (H7) to 1e-10, the Dundurs
    term included, for every family and backing."""
    pair = SlidingPair(STEEL, PAD, 0.4, dundurs)
    vc, mode = critical_speed(pair, M)
    b = modes(pair, M, 60.0)[0]
    for name, lay in layups(STEEL, PAD, 0.4, dundurs=dundurs, **geometry).items():
        fam = Layered(name, lay)
        V, w, ok = neutral_point(fam, M, vc * 1.001, -mode.migration_speed * M)
        assert ok and _rel(V, vc) < 1e-10
        assert abs(-w / M - mode.migration_speed) < 1e-10 * vc
        root, ok = newton_roots(lambda z, _: fam.log_derivatives(z, M, 60.0)[..., 0],
                                [b * (1 + 1e-6)],
                                fam.scale(M))
        assert ok[0] and abs(root[0] - b) < 1e-10 * abs(b)


def test_a_refused_step_given_up_early_changes_nothing_but_the_work(monkeypatch):
    """The speed scan gives up a step as soon as a mode surely lands outside its band
    (derivation, the speed scan): the scan of the disc's symmetric family at n = 7 on
    R = 120 mm, with the rule and without it, has the same speeds, counts, maxima,
    crossing and certificate, the rule given up steps (9 measured) and its Newton's
    method fewer evaluations (172 against 193)."""
    from thermocontact.studies import tei_layers

    family = _disc()
    plain = tei_layers.newton_roots
    work = {}

    def counted(rule):
        def newton(log_derivative, x0, scale, iters=25, abandon=None):
            def evaluated(z, act):
                work[rule] = work.get(rule, 0) + 1
                return log_derivative(z, act)

            def asked(*args):
                given_up = abandon(*args)
                work[rule, "given up"] = work.get((rule, "given up"), 0) + given_up
                return given_up
            return plain(evaluated, x0, scale, iters,
                         asked if rule and abandon is not None else None)
        return newton
    scans = {}
    for rule in (True, False):
        monkeypatch.setattr(tei_layers, "newton_roots", counted(rule))
        scans[rule] = family.scan(7 / 0.12)
    with_rule, without = scans[True], scans[False]
    assert (with_rule.speeds, with_rule.counts, with_rule.maxima, with_rule.certified) == (
        without.speeds, without.counts, without.maxima, without.certified)
    ((v1, w1, k1),), ((v0, w0, k0),) = with_rule.crossings, without.crossings
    assert k1 == k0 and _rel(v1, v0) < 1e-14 and _rel(w1, w0) < 1e-14
    assert work[True, "given up"] > 0 and work[True] < work[False]


def test_a_maximum_below_zero_left_unlocated_changes_nothing_but_the_work(monkeypatch):
    """An interior maximum of a growth rate is located only where the values and slopes
    at its step's ends allow it to reach 0 (derivation, the speed scan): the scan of the
    disc's symmetric family at n = 7 on R = 120 mm, with the bound and with every
    maximum located (``PEAK_RISE`` infinite), has the same crossings, speeds, counts,
    maxima and certificate to the last bit, and follows its modes fewer times."""
    from thermocontact.studies import tei_layers

    bounded, located, work, work_located = _scan_with_and_without(
        monkeypatch, ("PEAK_RISE", tei_layers.PEAK_RISE), math.inf,
        (tei_layers, "_polish"))
    assert bounded == located and bounded.maxima > 0         # the same arithmetic
    assert work < work_located


def _disc(name="symmetric"):
    """A family of the worked disc: grey iron 12 mm, organic pads 10 mm on a backing."""
    return _family(name, IRON, PAD, dundurs=False, slider_thickness=0.012,
                   counterface_thickness=0.010)


def _scan_with_and_without(monkeypatch, rule, off, counted, points=None):
    """The disc's symmetric family scanned at n = 7 on R = 120 mm with the module
    setting ``rule = (name, value)`` and with ``off`` in its place, and the work of
    each: the calls of ``counted = (owner, name)``, or with ``points`` the sum of the
    sizes of their ``points``-th argument."""
    from thermocontact.studies import tei_layers

    family = _disc()
    owner, method = counted
    plain = getattr(owner, method)
    scans, work = {}, {}
    for key, value in (("rule", rule[1]), ("off", off)):
        work[key] = 0

        def tally(*args, key=key, **kwargs):
            work[key] += 1 if points is None else np.size(args[points])
            return plain(*args, **kwargs)
        monkeypatch.setattr(owner, method, tally)
        monkeypatch.setattr(tei_layers, rule[0], value)
        scans[key] = family.scan(7 / 0.12)
    monkeypatch.setattr(owner, method, plain)
    return scans["rule"], scans["off"], work["rule"], work["off"]


def _same_scan(a, b, crossing=1e-13):
    """The same scan: its steps, counts, maxima and certificate, its crossings to
    ``crossing`` (the same evaluations in batches of other sizes: not bitwise on every
    CPU)."""
    assert (a.speeds, a.counts, a.maxima, a.start) == (b.speeds, b.counts, b.maxima, b.start)
    _same_crossings(a, b, crossing)
    assert _rel(a.end, b.end) < crossing


def _same_crossings(a, b, tol):
    """Both scans certified, with the same crossings to ``tol``."""
    assert len(a.crossings) == len(b.crossings) > 0 and a.certified and b.certified
    for (v1, w1, k1), (v0, w0, k0) in zip(a.crossings, b.crossings):
        assert k1 == k0 and _rel(v1, v0) < tol and _rel(w1, w0) < tol


def test_steps_grown_by_how_near_their_bands_edge_the_modes_came(monkeypatch):
    """After an accepted step the scan grows the next by less where a mode came near the
    edge of its band (derivation, the speed scan), instead of always doubling its
    excess (``STEP_TARGET`` infinite): the same crossing (to 1e-12), certified both
    ways, in fewer steps tried."""
    from thermocontact.studies import tei_layers

    new, old, tried, tried_old = _scan_with_and_without(
        monkeypatch, ("STEP_TARGET", tei_layers.STEP_TARGET), math.inf,
        (tei_layers, "_follow"))
    _same_crossings(new, old, 1e-12)
    assert tried < tried_old


def test_the_counts_paired_frequencies_once_change_nothing_but_the_work(monkeypatch):
    """Far from both frames the count's two grids pair up, each pair closer than a
    hundredth of their spacing: one of each is left out (derivation, the count). The
    scan with every frequency (``COUNT_MERGE = 0``) is the same (its crossing to
    rounding), its count's ratio taken at fewer frequencies; and the count where a
    growing mode is near the moving frame (where an earlier draft, measuring the
    spacing about 0, lost it) is the same with and without the rule."""
    from thermocontact.studies import tei_layers
    from thermocontact.studies.tei_layers import unstable_count

    new, old, points, points_old = _scan_with_and_without(
        monkeypatch, ("COUNT_MERGE", tei_layers.COUNT_MERGE), 0.0,
        (Layered, "dispersion_ratio"), points=1)
    _same_scan(new, old)
    assert points < 0.9 * points_old
    anti, m = _disc("antisymmetric"), 284.02411370222836
    counts = [unstable_count(anti, m, 47.196)]
    monkeypatch.setattr(tei_layers, "COUNT_MERGE", 0.0)
    counts.append(unstable_count(anti, m, 47.196))
    assert counts == [(1, True), (1, True)]


def test_a_crossing_from_the_cubic_through_its_step_is_brents(monkeypatch):
    """A step's crossing is the neutral point polished from the zero of the cubic
    through the growth rate's values and slopes at the step's ends, kept where the mode
    followed there lands on it (derivation, the speed scan): the scan finds it without
    Brent's method, and the same crossing (to 1e-12) as with Brent's method first (the
    cubic's zero made NaN)."""
    import scipy.optimize

    from thermocontact.studies import tei_layers

    nan = (lambda lo, hi: (math.nan, complex(math.nan, math.nan)))
    new, old, brent, brent_old = _scan_with_and_without(
        monkeypatch, ("_hermite_zero", tei_layers._hermite_zero), nan,
        (scipy.optimize, "brentq"))
    _same_crossings(new, old, 1e-12)
    assert brent == 0 and brent_old > 0


def test_a_neutral_point_whose_step_cannot_be_taken_is_not_converged():
    """Newton's method on a neutral point: where finite logarithmic derivatives (D not 0)
    make a singular system, the point is given up at once, not converged; where they
    are not finite (M singular, D = 0 at the point itself) it is converged there."""
    family = _family("symmetric", IRON, PAD, slider_thickness=0.012)

    class Stub:
        def __init__(self, value):
            self.value, self.calls = value, 0

        def scale(self, m):
            return family.scale(m)

        def log_derivatives(self, b, m, V):
            self.calls += 1
            return np.broadcast_to(np.asarray(self.value, dtype=complex),
                                   np.shape(b) + (2,))
    # A singular system with d ln D/db = 0, and one with both derivatives nonzero (the
    # frame at rest: d/ds = i sigma d/db, d/dV as given, det 0).
    for value, converged in (([0.0, 1.0], False), ([1.0, 1j], False),
                             ([np.nan, 1.0], True), ([np.inf, 1.0], True)):
        stub = Stub(value)
        V, w, ok = neutral_point(stub, M, 3.0, -2.0)
        assert bool(ok) is converged and stub.calls == 1, value       # ended at once
        assert V == 3.0 and abs(w + 2.0) <= 1e-15                     # no step taken


def test_the_zero_of_a_steps_cubic():
    """The cubic through a cubic's values and slopes is that cubic: its zero, and b
    there, exactly."""
    from thermocontact.studies.tei_layers import _hermite_zero

    def b(v):
        return (v - 2.0) * (1.0 + 0.5j) + 0.2 * (v - 2.0) ** 3 + 3.0j

    def slope(v):
        return (1.0 + 0.5j) + 0.6 * (v - 2.0) ** 2
    v, at = _hermite_zero((1.0, b(1.0), slope(1.0)), (3.5, b(3.5), slope(3.5)))
    assert abs(v - 2.0) < 1e-14 and abs(at - 3.0j) < 1e-14


def test_seeds_of_followed_modes_need_no_polishing(monkeypatch):
    """A reseeding that only looks for the modes yet to grow leaves unpolished each
    seed that is alone near one followed mode (derivation, the speed scan): the scan,
    and with every seed polished (``SEED_MATCH = 0``), is the same (its crossing to
    rounding), and polishes fewer seeds."""
    from thermocontact.studies import tei_layers

    new, old, seeds, seeds_old = _scan_with_and_without(
        monkeypatch, ("SEED_MATCH", tei_layers.SEED_MATCH), 0.0,
        (tei_layers, "_polish"), points=3)
    _same_scan(new, old)
    assert seeds < seeds_old


def test_which_seeds_are_followed_modes():
    """A seed within SEED_MATCH of one followed mode (of that mode's size in its frame),
    alone there and in its frame, is that mode; two seeds near one mode, a seed near two
    modes, one near a mode of the other frame and one near none are polished."""
    from thermocontact.studies.tei_layers import SEED_MATCH, _seeds_followed

    family = _disc()
    m, V = 50.0, 200.0
    assert family.scale(m) < 1e-2                 # the sizes below: 100, 100 and 5000
    # A mode at rest on the pads, one at rest on the disc (frequency -m V = -1e4: its
    # size in its frame 100), a fast one (its band 50 wide).
    b = np.array([-100.0 + 0j, -100.0 - 1j * m * V, -5000.0 + 0j])
    near = 0.5 * SEED_MATCH * 100.0
    seeds = np.array([b[0] + near, b[1] - 1j * near, b[1] + 30.0 * near, -2000.0,
                      b[2] + 50.0 * near, b[2] - 50.0 * near])
    assert _seeds_followed(family, m, V, seeds, b).tolist() == [True, True, False, False,
                                                                False, False]
    pair = np.array([-100.0 + 0j, -100.0 + 1j * near])             # two modes side by side
    assert not _seeds_followed(family, m, V, np.array([-100.0 + 0.5j * near]), pair).any()
    # A fast mode at rest on the pads and a seed of one at rest on the disc within its
    # band (m V = 25 at V = 0.5): of the other frame, not that mode's.
    fast, slow_v = np.array([-3000.0 + 0j]), 0.5
    other = np.array([-2999.0 - 1j * m * slow_v])
    assert not _seeds_followed(family, m, slow_v, other, fast).any()
    assert _seeds_followed(family, m, slow_v, np.array([-2999.0 + 0j]), fast).all()
    assert not _seeds_followed(family, m, V, seeds[:0], b).size


def test_chains_that_meet_stop_and_change_nothing_but_the_work(monkeypatch):
    """A curve's chain of neutral points stops where it reaches the point another chain
    has reached (derivation, L15): the disc's symmetric family over hot-spot numbers 4
    to 12 on R = 120 mm, scanned at both ends, with the rule and with every chain run to
    the next scanned wavenumber, is the same to 1e-12, in fewer steps."""
    from thermocontact.studies import tei_layers

    family = _disc()
    ms = np.arange(4, 13) / 0.12
    plain_crossing, plain_start = tei_layers.first_crossing, tei_layers._Continuation.start
    scanned, steps = {}, {}

    def crossing(family, m, *args, **kwargs):       # each scan once, for both runs
        if m not in scanned:
            scanned[m] = plain_crossing(family, m, *args, **kwargs)
        return scanned[m]
    monkeypatch.setattr(tei_layers, "first_crossing", crossing)
    same, curves = tei_layers._same_point, {}
    for rule in (False, True):
        def start(self, *args, rule=rule, **kwargs):
            steps[rule] = steps.get(rule, 0) + 1
            return plain_start(self, *args, **kwargs)
        monkeypatch.setattr(tei_layers._Continuation, "start", start)
        monkeypatch.setattr(tei_layers, "_same_point", same if rule else lambda *a: False)
        curves[rule] = tei_layers.neutral_curves([family], ms, scan_every=8)[0]
    (v1, w1), (v0, w0) = curves[True], curves[False]
    assert np.isfinite(v0).all() and len(scanned) == 2
    assert np.max(np.abs(v1 - v0) / v0) < 1e-12
    assert np.max(np.abs(w1 - w0) / (np.abs(w0) + ms * v0)) < 1e-12
    assert steps[True] < steps[False], steps


def test_thick_disc_scan_finds_the_half_planes_critical_speed():
    vc, _ = critical_speed(SlidingPair(STEEL, PAD, 0.4), M)
    # m d/2 = 19: the faces see each other through e^{-2 m d/2} = 4e-17.
    got, b = _family("antisymmetric", STEEL, PAD, slider_thickness=0.3).critical(M)
    assert _rel(got, vc) < 1e-10 and abs(b.real) < 1e-9 * abs(b)


# --- a layer between non-conducting pads: the closed form (L11) -----------------------

@pytest.mark.parametrize("family", ["symmetric", "antisymmetric"])
@pytest.mark.parametrize("pad, pad_model", [(NC_PAD, NC_PAD), (RIGID, None)])
def test_layer_between_non_conducting_pads_closed_form(family, pad, pad_model):
    """The neutral speed K m t (C_layer + C_pad)/(f W), the mode at rest on the layer,
    to 1e-10; the first crossing of the scan at m = 84/m."""
    fam = _family(family, IRON, pad, dundurs=False, slider_thickness=0.012)
    for k, m in enumerate((20.0, 84.0, 300.0)):
        exact = layer_neutral_speed(IRON, 0.012, m, 0.4, family, pad_model)
        if k == 1:
            V, b = fam.critical(m)
            w = b.imag
        else:
            V, w, ok = neutral_point(fam, m, 1.2 * exact, -1.2 * exact * m)
            assert ok
        assert _rel(V, exact) < 1e-10
        assert abs(w + m * V) < 1e-10 * m * V          # at rest on the layer


def test_closed_form_limits():
    """The layer's compliances tend to the half-plane's for a thick layer and to the
    plate's 12 (1 - nu)/(mu m^4 d^3) for a thin one; a pad on a frictionless backing is
    the symmetric half of a free layer twice as thick."""
    half = (1 - IRON.nu) / (IRON.mu * 84.0)
    for fam in ("symmetric", "antisymmetric"):
        assert _rel(layer_compliance(IRON, 1.0, 84.0, fam), half) < 1e-14
    plate = 12 * (1 - IRON.nu) / (IRON.mu * 84.0**4 * 1e-5**3)
    # The plate's relative error is of order (m d)^2 = 7e-7 (shear).
    assert _rel(layer_compliance(IRON, 1e-5, 84.0, "antisymmetric"), plate) < 1e-5
    # Thermal: a thick layer's face moves out as the half-plane's 2 alpha (1 + nu)/(2 m).
    W = layer_thermal_displacement(IRON, 1.0, 84.0, "symmetric")
    assert _rel(W, IRON.alpha * (1 + IRON.nu) / 84.0) < 1e-12


def test_pad_layer_on_a_slipping_backing_closed_form():
    """A non-conducting pad layer on a rigid plate it slips on: its compliance is the
    symmetric one of a free layer of twice its thickness (the plate a plane of
    symmetry), so V = K m t (C_layer + C_S(2h))/(f W)."""
    h = 0.004
    for family in ("symmetric", "antisymmetric"):
        fam = _family(family, IRON, NC_PAD, dundurs=False, slider_thickness=0.012,
                      counterface_thickness=h)
        m = 84.0
        t = math.tanh(0.006 * m) if family == "symmetric" else 1 / math.tanh(0.006 * m)
        exact = (IRON.K * m * t * (layer_compliance(IRON, 0.012, m, family)
                                   + layer_compliance(NC_PAD, 2 * h, m, "symmetric"))
                 / (0.4 * layer_thermal_displacement(IRON, 0.012, m, family)))
        V, w, ok = neutral_point(fam, m, 1.2 * exact, -1.2 * exact * m)
        assert ok and _rel(V, exact) < 1e-10


def test_antisymmetric_minimum_over_wavelength_closed_form():
    """The family's minimum over the wavelength (the curve bracketed on 40 wavelengths,
    refined by bounded minimisation) against the closed form's, to 1e-10 in speed."""
    fam = _family("antisymmetric", IRON, NC_PAD, dundurs=False, slider_thickness=0.012)
    got, wl, end = family_minimum(fam, (0.0024, 2.0))
    assert end is False
    res = minimize_scalar(lambda x: layer_neutral_speed(IRON, 0.012, math.exp(x), 0.4,
                                                        "antisymmetric", NC_PAD),
                          bracket=(3.0, 4.0, 5.0), tol=1e-12)
    assert _rel(got, res.fun) < 1e-10
    assert _rel(2 * math.pi / wl, math.exp(res.x)) < 1e-4


# --- two methods for every geometry ---------------------------------------------------

TWO_METHODS = [
    # (slider, counterface, dundurs, geometry, family, speed)
    (IRON, SINTERED, False, dict(slider_thickness=0.012), "antisymmetric", 28.2),
    (IRON, SINTERED, True, dict(slider_thickness=0.012), "symmetric", 19.9),
    (IRON, SINTERED, True, dict(slider_thickness=0.012, faces=1), "all", 68.5),
    (IRON, SINTERED, True, dict(slider_thickness=0.012, counterface_thickness=0.008),
     "antisymmetric", 4.2),
    (IRON, SINTERED, False, dict(slider_thickness=0.012, counterface_thickness=0.008,
                                 backing="bonded-insulated"), "antisymmetric", 10.0),
    (IRON, SINTERED, True, dict(slider_thickness=0.012, counterface_thickness=0.008,
                                backing="slip-isothermal"), "symmetric", 508.0),
    (IRON, SINTERED, True, dict(counterface_thickness=0.008), "all", 9.8),
    (IRON, SINTERED, True, dict(slider_thickness=0.012, plane="stress"), "antisymmetric",
     34.0),
] + [(STEEL, SINTERED, True, dict(slider_thickness=0.002, counterface_thickness=0.001,
                                   separator=STEEL, separator_thickness=0.002), name, 20.0)
     for name in ("symmetric in-phase", "antisymmetric in-phase", "symmetric anti-phase",
                  "antisymmetric anti-phase")]


@pytest.mark.parametrize("slider, counterface, dundurs, geometry, family, speed", TWO_METHODS,
                         ids=[f"{c[4]}-{'-'.join(map(str, c[3].values()))}"[:60]
                              for c in TWO_METHODS])
def test_root_search_against_depth_discretisation(slider, counterface, dundurs, geometry,
                                                  family, speed):
    """The rightmost mode by Newton's method on det M(b) and the eigenvalue of the
    Chebyshev discretisation in depth (elasticity and heat collocated, plane stress
    written directly) agree to 1e-8 of |b| + kappa m^2 at n = 64, the error falling
    tenfold or more from n = 32."""
    fam = _family(family, slider, counterface, dundurs=dundurs, **geometry)
    b = fam.modes(M, speed)
    assert b.size
    scale = abs(b[0]) + fam.scale(M)
    errs = [np.min(np.abs(layup_modes(fam.layup, M, speed, n) - b[0])) / scale
            for n in (32, 64)]
    assert errs[1] < 1e-8 and (errs[1] < errs[0] / 10 or errs[0] < 1e-9)


def test_plane_stress_substitution():
    """(L9): with nu' = nu/(1 + nu), E' = E(1 + 2 nu)/(1 + nu)^2, alpha' = alpha(1 + nu)/
    (1 + 2 nu), the plane-strain compliance and expansion are plane stress's 2/E and
    alpha; the shear modulus is unchanged."""
    s = plane_stress_material(IRON)
    assert _rel(s.compliance, 2 / IRON.E) < 1e-15
    assert _rel(s.alpha * (1 + s.nu), IRON.alpha) < 1e-15
    assert _rel(s.mu, IRON.mu) < 1e-15
    stress = _family("antisymmetric", IRON, SINTERED, slider_thickness=0.012, plane="stress")
    strain = _family("antisymmetric", IRON, SINTERED, slider_thickness=0.012)
    assert stress.critical(M)[0] > 1.5 * strain.critical(M)[0]


# --- no unstable root below the critical speed: the argument principle ------------------

def _count_zeros(func, re_max, im_lo, im_hi, n=800):
    """Zeros of ``func`` in the rectangle [0, re_max] x [im_lo, im_hi], by the winding
    of its argument along the boundary (each side on n points, refined where the
    argument jumps by more than 1)."""
    corners = [0 + 1j * im_lo, re_max + 1j * im_lo, re_max + 1j * im_hi, 0 + 1j * im_hi]
    total = 0.0
    for a, b in zip(corners, corners[1:] + corners[:1]):
        z = a + (b - a) * np.linspace(0.0, 1.0, n)
        for _ in range(6):
            ph = np.angle(func(z))
            jump = np.abs(np.diff(np.unwrap(ph)))
            if jump.max() < 1.0:
                break
            bad = np.repeat(jump > 0.5, 1)
            mids = 0.5 * (z[:-1] + z[1:])[bad]
            z = np.sort_complex(np.concatenate([z, mids])) if a.imag == b.imag else \
                np.concatenate([z, mids])[np.argsort(np.abs(np.concatenate([z, mids]) - a))]
        total += np.sum(np.diff(np.unwrap(np.angle(func(z)))))
    return total / (2 * math.pi)


def test_no_unstable_root_below_the_critical_speed():
    """The winding number of det M over a box of the right half-plane (growth rates to
    10 V m, frequencies within 3 V m of either body's frame) is 0 just below the
    critical speed and 1 just above it."""
    fam = _family("antisymmetric", IRON, SINTERED, slider_thickness=0.012)
    vc, b = fam.critical(M)
    for factor, expect in ((0.99, 0), (1.01, 1)):
        V = factor * vc

        def D(z):
            return fam.dispersion(z, M, V)

        count = _count_zeros(D, 10 * V * M, -4 * V * M, 3 * V * M)
        assert abs(count - expect) < 1e-6, (factor, count)


# --- exact scalings ------------------------------------------------------------------

def test_scalings_at_fixed_m_d():
    """Only m d, m h and V/(kappa m) enter once b is scaled by kappa m^2: halving every
    thickness and doubling m doubles the critical speed and quadruples the growth
    rate at twice the speed."""
    a = _family("antisymmetric", IRON, SINTERED, slider_thickness=0.012,
                counterface_thickness=0.008)
    b = _family("antisymmetric", IRON, SINTERED, slider_thickness=0.006,
                counterface_thickness=0.004)
    v1, b1 = a.critical(M)
    v2, w2, ok = neutral_point(b, 2 * M, 2 * v1, 4 * b1.imag)
    assert ok and _rel(v2, 2 * v1) < 1e-10
    r1 = a.modes(M, 1.5 * v1)[0]
    r2 = b.modes(2 * M, 3 * v1)[0]
    assert abs(r2 - 4 * r1) < 1e-10 * abs(4 * r1)


# --- the brake stop against a time integration ----------------------------------------

def test_stop_amplification_against_time_integration():
    """A slow stop of a disc between non-conducting pads (no thermal layer to
    re-grid): the frozen-coefficient log amplification (L13) of the most amplified
    hot-spot number against the linearised equations discretised in depth and
    integrated in time with the speed falling (exponential midpoint steps), started
    from the mode at the top speed: to 1e-3 of the log amplification."""
    from thermocontact.studies.brake_stop import stop_amplification, stop_history

    radius, n = 0.12, 7
    lay = layups(IRON, NC_PAD, 0.4, dundurs=False, slider_thickness=0.012)
    systems = tuple(Layered(k, v) for k, v in lay.items())
    # From 3 to 2 m/s (above every critical speed of n = 7) in 40 s: the growth rate
    # falls from 2.8 to 1.7 1/s, the mode's shape changes by a few per cent (the part
    # of the amplification that the frozen coefficients leave out).
    t_end = 40.0
    hist = stop_history("3:0.025", None, None)
    hist = type(hist)(np.array([0.0, t_end]), np.array([3.0, 2.0]), hist.threshold)
    got = stop_amplification(systems, radius, (n, n), hist).log_amplification[0]
    m = n / radius
    A_of = {}

    def A(v):
        if v not in A_of:
            A_of[v] = layup_operator(lay["antisymmetric"], m, v, 24)
        return A_of[v]

    w, vecs = np.linalg.eig(A(3.0))
    x = vecs[:, np.argmax(w.real)]
    logs = []
    for steps in (100, 200):
        y = x.copy()
        h = t_end / steps
        log = 0.0
        for k in range(steps):
            y = expm(h * A(3.0 - (k + 0.5) * h / t_end)) @ y
            s = np.linalg.norm(y)
            log += math.log(s)
            y /= s
        logs.append(log)
    assert abs(logs[1] - logs[0]) < 1e-4 * abs(logs[1])     # converged in the step
    assert got > 50.0 and abs(got - logs[1]) < 1e-3 * abs(logs[1]), (got, logs)


# --- the call and the command ----------------------------------------------------------

@pytest.fixture(scope="module")
def disc_run():
    """The disc's analysis and what it told its progress, ``[(stage, done, total)]``."""
    told = []
    res = tei("cast-iron", "organic-composite-brake-block", 0.4, "75mm", speed=10,
              dundurs=False, slider_thickness="12mm", disc_radius="120mm", hot_spots="4:10",
              brake_stop="3:1", progress=lambda *a: told.append(a))
    return res, told


@pytest.fixture(scope="module")
def disc(disc_run):
    return disc_run[0]


def test_disc_tells_its_progress(disc_run):
    """A layup's analysis (seconds to minutes) tells each stage in order: each family's
    critical speed and curve over the wavelength, the families' hot-spot curves (one
    stage, their scans run together), the stop; each stage's count starts at 0 and rises to its total."""
    _, told = disc_run
    families = ("antisymmetric", "symmetric")
    stages = list(dict.fromkeys(stage for stage, _, _ in told))
    assert stages == ([f"{f}: {what}" for f in families
                       for what in ("critical speed", "minimum over the wavelength")]
                      + ["hot spots", "the stop's growth rates"])
    for stage in stages:
        counts = [(done, total) for s, done, total in told if s == stage]
        assert counts[0][0] == 0 and counts[-1][0] == counts[-1][1]
        assert len({total for _, total in counts}) == 1
        assert all(a[0] <= b[0] for a, b in zip(counts, counts[1:]))
    with pytest.raises(InputError, match="progress"):
        tei("cast-iron", "organic-composite-brake-block", 0.4, "75mm",
            slider_thickness="12mm", progress="yes")


def test_disc_record(disc):
    d = disc.to_dict()
    json.dumps(d, allow_nan=False)
    assert [f["family"] for f in d["families"]] == ["antisymmetric", "symmetric"]
    assert d["critical_speed"] == min(f["critical_speed"] for f in d["families"])
    for f in d["families"]:
        assert f["minimum_critical_speed"] <= f["critical_speed"]
    # At 10 m/s every family is listed: its growing modes, or its least stable one.
    assert {m["family"] for m in d["modes"]} == {"antisymmetric", "symmetric"}
    for name in ("antisymmetric", "symmetric"):
        rates = [m["growth_rate"] for m in d["modes"] if m["family"] == name]
        assert all(r > 0 for r in rates) or len(rates) == 1
    spots = d["hot_spots"]
    assert [h["n"] for h in spots] == list(range(4, 11))
    best = min(spots, key=lambda h: h["critical_speed"])
    assert d["governing_hot_spots"] == best["n"] == 7
    # The table's continuation against a scan at one n; its scan at n = 4 (run with
    # the other scans of both families, their evaluations batched) against one alone.
    fam = next(s for s in disc.systems if s.name == spots[5]["family"])
    vc, _ = fam.critical(9 / 0.12)
    assert _rel(spots[5]["critical_speed"], vc) < 1e-9
    fam = next(s for s in disc.systems if s.name == spots[0]["family"])
    assert _rel(spots[0]["critical_speed"], fam.critical(4 / 0.12)[0]) < 1e-12
    assert _rel(spots[5]["wavelength"], 2 * math.pi * 0.12 / 9) < 1e-15
    stop = d["stop"]
    assert [a["n"] for a in stop["amplification"]] == list(range(4, 11))
    assert stop["threshold"] == math.exp(5.0)


def test_command_json_is_the_record(capsys, disc):
    """The command prints the call's record (a disc rubbing on one face: one family),
    and its text report the numbers of the record."""
    from thermocontact.cli.tei import report_lines

    args = ["tei", "--slider", "cast-iron", "--counterface", "organic-composite-brake-block",
            "--friction", "0.4", "--wavelength", "75mm", "--no-dundurs", "--faces", "1",
            "--slider-thickness", "12mm", "--plane-stress", "--json"]
    assert main(args) == 0
    rec = json.loads(capsys.readouterr().out)
    assert rec == tei("cast-iron", "organic-composite-brake-block", 0.4, "75mm",
                      dundurs=False, faces=1, slider_thickness="12mm",
                      plane_stress=True).to_dict()
    assert rec["plane"] == "stress" and [f["family"] for f in rec["families"]] == ["all"]
    out = "\n".join(report_lines(disc))
    assert "antisymmetric: 2.5913 m/s; minimum 1.936" in out and "governing n = 7" in out
    assert "stop from 3 m/s in 3 s" in out and "most unstable wavelength" in out


def test_pictures(tmp_path, disc):
    import matplotlib

    matplotlib.use("Agg")
    from matplotlib.figure import Figure

    from thermocontact.plotting.tei import modes_figure, plot_hot_spots, plot_tei, tei_figure

    ax = plot_tei(disc, ax=Figure().subplots(), wavelengths=[0.05, 0.075, 0.1])
    assert len(ax.get_lines()) >= 3
    ax = plot_hot_spots(disc, ax=Figure().subplots())
    assert ax.get_lines()
    tei_figure(disc, str(tmp_path / "a.png"), wavelengths=[0.05, 0.075, 0.1])
    modes_figure(disc, str(tmp_path / "b.png"))
    for name in ("a.png", "b.png"):
        assert (tmp_path / name).stat().st_size > 1000


def test_bad_input_before_any_work():
    with pytest.raises(InputError, match="slider must be a material name") as err:
        tei(None, "steel", 0.3, 0.05)
    assert err.value.parameters == ("slider",)
    with pytest.raises(InputError, match="dundurs must be True or False"):
        tei("steel", "steel", 0.3, 0.05, dundurs="no")
    with pytest.raises(InputError, match="plane_stress must be True or False"):
        tei("steel", "steel", 0.3, 0.05, plane_stress="yes")
    with pytest.raises(InputError, match="friction must be 0 or in"):
        tei("steel", "steel", "1e-400", 0.05)
    with pytest.raises(InputError, match="not end above its start"):
        import tempfile

        with tempfile.NamedTemporaryFile("w", suffix=".csv", delete=False) as f:
            f.write("time,speed\n0,10\n1,12\n")
        tei("steel", "steel", 0.3, 0.05, slider_thickness=0.01, disc_radius=0.1,
            stop_history=f.name)
    with pytest.raises(InputError, match="faces must be an integer in"):
        tei("steel", "steel", 0.3, 0.05, slider_thickness=0.01, faces=3)


def test_stable_at_all_speeds_is_a_claim_it_can_prove():
    """Issue: steel on the organic pad, f = 0.01, no Dundurs term, L = 1 km was called
    stable at all speeds while a mode grows at 1e4 m/s.  The high-speed limit (H10)
    has a growing root there (Re X = 1.5e-8, the mode nearly at rest on the steel),
    so the scan goes on and finds the critical speed."""
    r = tei("steel", "organic-composite-brake-block", 0.01, "1km", speed=1e4, dundurs=False)
    assert r.modes[0].growth_rate > 0
    assert r.stable_at_all_speeds is False and r.critical_speed < 1e4
    assert tei("steel", "organic-composite-brake-block", 0.01, "1km", speed=0.999 *
               r.critical_speed, dundurs=False).modes[0].growth_rate < 0


def test_a_root_at_the_rounding_of_the_determinant_is_kept():
    """A clutch's antisymmetric in-phase mode: Newton's steps on det M stall at 7e-11
    (4e-13 of |b|), above 1e-13 |b|; the root is kept (it was dropped, and the scan
    then missed the first crossing).  The critical speed found is the crossing: decaying
    just below, growing just above."""
    fam = _family("antisymmetric in-phase", STEEL, get_material("paper-based-clutch-facing"),
                  0.12, slider_thickness=0.0012, counterface_thickness=0.0005,
                  separator=STEEL, separator_thickness=0.0016)
    b = fam.modes(M, 1060.0)
    assert b.size and b[0].real > 0.5
    vc, w = fam.critical(M)
    assert fam.modes(M, 0.999 * vc)[0].real < 0 < fam.modes(M, 1.001 * vc)[0].real


def test_stop_history_file_is_the_same_stop(tmp_path, disc):
    """A CSV history of the same stop (3 m/s to rest in 3 s, a header line) gives the
    amplifications of --stop 3:1."""
    from thermocontact.studies.brake_stop import stop_amplification, stop_history

    path = tmp_path / "stop.csv"
    path.write_text("time,speed\n0,3\n1.5,1.5\n3,0\n")
    hist = stop_history(None, str(path), None)
    got = stop_amplification(disc.systems, 0.12, (4, 10), hist)
    assert np.allclose(got.log_amplification, disc.stop.log_amplification, rtol=1e-9,
                       atol=1e-9)
    assert got.first_unstable == disc.stop.first_unstable


def test_the_command_offers_the_backings_of_the_physics():
    from thermocontact.cli.tei import tei_cmd
    from thermocontact.physics.tei_layers import BACKINGS, FACE_CONDITIONS

    choice = next(p for p in tei_cmd.params if p.name == "backing").type.choices
    assert tuple(choice) == BACKINGS and set(BACKINGS) <= set(FACE_CONDITIONS)


@pytest.mark.parametrize("dundurs", [False, True])
def test_whole_disc_is_its_two_families(dundurs):
    """The whole disc between a pad below and a pad above (no symmetry used: the upper
    interface's sliding sign and shear the other way) has the modes of both families
    (L7): its critical speed is the lower of theirs, and each family's neutral mode is
    one of its zeros, to 1e-10."""
    from thermocontact.physics.tei_layers import Body, Layup

    whole = Layered("whole", Layup(
        (Body(SINTERED, None, False), Body(IRON, 0.012, True), Body(SINTERED, None, False)),
        ("sliding", "sliding"), "infinite", "infinite", 0.4, dundurs))
    speeds = []
    for name in ("symmetric", "antisymmetric"):
        fam = _family(name, IRON, SINTERED, dundurs=dundurs, slider_thickness=0.012)
        vc, b = fam.critical(M)
        if vc is None:
            continue
        V, w, ok = neutral_point(whole, M, vc * (1 + 1e-6), b.imag)
        assert ok and _rel(V, vc) < 1e-10 and abs(w - b.imag) < 1e-9 * abs(b.imag)
        speeds.append(vc)
    vc, _ = whole.critical(M)
    assert _rel(vc, min(speeds)) < 1e-10


def test_clutch_cell_with_any_floquet_phase():
    """A whole clutch cell (separator, facing, core, facing), the next cell's fields
    e^{i phi} times its own (L7): at phi = 0 its critical speed is the lower of the two
    in-phase families', at phi = pi of the two anti-phase ones', to 1e-10; at phi = pi/2
    it is stable below the lowest of the four (observed over phi = 0, pi/4, pi/2,
    3 pi/4, pi: 81.79, 138.5, 133.4, 132.5, 132.3 m/s at L = 50 mm), and the depth
    discretisation agrees with the root search on the periodic cell to 1e-8."""
    from thermocontact.physics.tei_layers import Body, Layup

    facing = get_material("paper-based-clutch-facing")
    kw = dict(slider_thickness=0.0012, counterface_thickness=0.0005, separator=STEEL,
              separator_thickness=0.0016)
    crit = {name: _family(name, STEEL, facing, 0.12, **kw).critical(M)[0]
            for name in ("symmetric in-phase", "antisymmetric in-phase",
                         "symmetric anti-phase", "antisymmetric anti-phase")}

    def cell(phi):
        bodies = (Body(STEEL, 0.0016, False), Body(facing, 0.0005, True),
                  Body(STEEL, 0.0012, True), Body(facing, 0.0005, True))
        return Layered("cell", Layup(bodies, ("sliding", "bonded", "bonded"), "periodic",
                                     "periodic", 0.12, True, "strain", phi))

    finite = [v for v in crit.values() if v is not None]
    in_phase = min(v for k, v in crit.items() if "in-phase" in k and v is not None)
    anti = min(v for k, v in crit.items() if "anti-phase" in k and v is not None)
    assert _rel(cell(0.0).critical(M)[0], in_phase) < 1e-10
    assert _rel(cell(math.pi).critical(M)[0], anti) < 1e-10
    fam = cell(math.pi / 2)
    assert fam.modes(M, 0.99 * min(finite))[0].real < 0
    b = fam.modes(M, 1.3 * in_phase)[0]
    got = np.min(np.abs(layup_modes(fam.layup, M, 1.3 * in_phase, 32) - b))
    assert got < 1e-8 * (abs(b) + fam.scale(M))


def test_most_unstable_wavelength_is_a_maximum(disc):
    """At 10 m/s the disc's most unstable wavelength has the largest growth rate of its
    neighbours 5 % shorter and longer."""
    wl, rate = disc.most_unstable_wavelength, disc.most_unstable_growth_rate
    assert rate > 0

    def best(m):
        return max(s.modes(m, 10.0)[0].real for s in disc.systems if len(s.modes(m, 10.0)))

    m = 2 * math.pi / wl
    assert _rel(best(m), rate) < 1e-9
    assert best(0.95 * m) < rate and best(1.05 * m) < rate


def test_plane_stress_half_planes_are_thick_layers_in_plane_stress():
    """Two half-planes in plane stress (the substituted materials in H7) and a thick disc
    in plane stress (the layers' solutions with the substituted constants) agree to
    1e-10: the substitution is made the same way in both."""
    r = tei(STEEL, PAD, 0.4, 0.05, plane_stress=True)
    fam = _family("antisymmetric", STEEL, PAD, slider_thickness=1.0, plane="stress")
    V, w, ok = neutral_point(fam, M, r.critical_speed, -r.migration_speed * M)
    assert ok and _rel(V, r.critical_speed) < 1e-10
    assert _rel(fam.critical(M)[0], r.critical_speed) < 1e-10
    assert r.critical_speed > tei(STEEL, PAD, 0.4, 0.05).critical_speed


def test_conditions_and_batches_against_the_dense_product():
    """The face conditions applied field by field (a weight of 1 taken as a copy, the
    terms of zero weight left out) against the product of the whole coefficient matrix
    (L5-L8) with every body's face fields; and the families of a disc, with the Dundurs
    term (the friction's weight in the shear rows), and of a clutch pack evaluated
    together, the count's ratio and the derivatives, against each family alone: to
    rounding."""
    from thermocontact.physics.tei_layers import (condition_matrix, condition_terms,
                                                  dispersion_log_derivatives,
                                                  dispersion_ratio, face_fields)

    rng = np.random.default_rng(7)
    groups = [layups(IRON, PAD, 0.4, slider_thickness=0.012, counterface_thickness=0.010),
              layups(STEEL, SINTERED, 0.12, slider_thickness=0.0012,
                     counterface_thickness=0.0005, separator=STEEL,
                     separator_thickness=0.0016)]
    for group in groups:
        fams = list(group.values())
        n = 12
        b = rng.normal(size=n) * 300.0 + 1j * rng.normal(size=n) * 3e3
        m = rng.uniform(20.0, 900.0, n)
        V = rng.uniform(0.1, 60.0, n)
        for lay in fams:
            C0, C1 = condition_matrix(lay)
            blocks = [face_fields(body, b, m, V, lay.references(), j == len(lay.bodies) - 1,
                                  lay.elastic(body)) for j, body in enumerate(lay.bodies)]
            dense = [np.concatenate([np.einsum("rfk,nfkc->nrc", C[:, j], F)
                                     for j, F in enumerate(blocks)], axis=-1)
                     for C in (C0, C1)]
            for got, want in zip(condition_terms(lay, b, m, V), dense):
                assert np.allclose(got, want, rtol=1e-14, atol=1e-14 * np.abs(want).max())
        which = rng.integers(0, len(fams), n)
        ratio = dispersion_ratio(fams, b, m, V, which=which)
        logd = dispersion_log_derivatives(fams, b, m, V, which=which)
        for k, lay in enumerate(fams):
            at = which == k
            assert np.allclose(ratio[at], dispersion_ratio(lay, b[at], m[at], V[at]),
                               rtol=1e-13, atol=0.0)
            assert np.allclose(logd[at], dispersion_log_derivatives(lay, b[at], m[at], V[at]),
                               rtol=1e-13, atol=0.0)
