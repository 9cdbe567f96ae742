"""The thermoelastic instability of layers against an independent reference
(``tests/data/tei_layer_reference.json``, made by ``tests/data/make_tei_layer_reference.py``:
a derivation and a code of its own, by surface admittances, a Nyquist count and a scan of
the largest growth rate; docs/derivation.md, L15): a 12 mm disc between half-plane pads
(A), rigid non-conducting pads (B), a 1 km disc (C, the half-planes) and pad layers on
backings (D); every neutral crossing, the windows of growth below a critical speed, the
minima over the wavelength, the modes at a speed."""

import json
import math
from pathlib import Path

import numpy as np
import pytest
from scipy.optimize import minimize_scalar

from thermocontact.api import tei
from thermocontact.cli.tei import report_lines
from thermocontact.discretisation.tei_depth import layup_modes
from thermocontact.physics.tei_layers import layups
from thermocontact.problem.materials import Material
from thermocontact.studies.tei_layers import Layered, neutral_point, speed_scan, unstable_count

REF = json.loads((Path(__file__).parent / "data" / "tei_layer_reference.json").read_text())
DISC = Material("reference-disc", *(REF["materials"]["disc"][k]
                                    for k in ("E", "nu", "alpha", "K", "kappa")))
PAD = Material("reference-pad", *(REF["materials"]["pad"][k]
                                  for k in ("E", "nu", "alpha", "K", "kappa")))
#: Rigid (its compliance 1e-30 of the disc's) and non-conducting.
RIGID = Material("rigid", 1e30, 0.3, 1e-5, 0.0, 0.0)
FAMILY = {"sym": "symmetric", "anti": "antisymmetric"}
F = REF["friction"]


def _geometry(case):
    c = REF["cases"][case]
    pad = RIGID if c["pads"] == "rigid_nonconducting" else PAD
    return pad, dict(slider_thickness=c["d"], counterface_thickness=c["pad_h"])


def _family(case, fam):
    pad, kw = _geometry(case)
    return Layered(FAMILY[fam], layups(DISC, pad, F, dundurs=False, **kw)[FAMILY[fam]])


def _rel(a, b):
    return abs(a - b) / abs(b)


def test_the_reference_checks_itself():
    """The reference's closed forms against the determinant of its own boundary
    conditions (each family, and the whole disc as the product of both)."""
    for errs in REF["checks"].values():
        assert max(errs.values()) < 1e-9


def _points():
    for case, c in REF["cases"].items():
        for row in c["per_wavelength"]:
            for fam in ("sym", "anti"):
                yield case, row["L"], fam, row[fam]


def test_every_neutral_point_of_the_reference():
    """Every crossing of the reference (cases A-D, every wavelength and family, up to 3
    V_c): Newton's method on the package's det M(i omega; V), from 1e-6 away on the side
    where the mode decays and the frequency of the package's mode nearest the axis there,
    lands on the same speed to 1e-10; the critical one's migration speed to 1e-10 V;
    between rigid non-conducting pads, the closed form.  (From inside a narrow window of
    growth, Newton's method may land on the window's other end: the two neutral points
    meet at a fold, where the speed is the ill-conditioned unknown.)"""
    for case, L, fam, r in _points():
        family, m = _family(case, fam), 2 * math.pi / L
        for c in r["crossings"]:
            V0 = c["speed"]
            b = family.modes(m, V0)
            w0 = b[np.argmin(np.abs(b.real))].imag
            V, w, ok = neutral_point(family, m, V0 * (1 - 1e-6 * c["direction"]), w0)
            assert ok and _rel(V, V0) < 1e-10, (case, L, fam, V, V0)
        V, w, ok = neutral_point(family, m, r["V"] * (1 - 1e-6), r["omega"])
        assert ok and abs(-w / m - r["migration_speed"]) < 1e-10 * r["V"]
        if "closed_form" in r:
            assert _rel(r["V"], r["closed_form"]) < 1e-12


SCANNED = [("A", 0.05, "sym"), ("A", 0.05, "anti"), ("B", 0.2, "anti"), ("C", 0.05, "sym"),
           ("C", 0.05, "anti"), ("D", 0.2, "sym")]


@pytest.mark.parametrize("case, L, fam", SCANNED)
def test_the_scan_finds_every_crossing(case, L, fam):
    """The speed scan from the lowest speed (L15) finds every crossing of the reference up
    to 3 V_c, in order and direction, to 1e-10, and certifies its counts; the growing
    modes are counted 0 just below the critical speed and 1 just above."""
    r = next(p[3] for p in _points() if p[:3] == (case, L, fam))
    family, m = _family(case, fam), 2 * math.pi / L
    scan = family.scan(m, beyond=3.0)
    assert scan.certified
    assert [c[2] for c in scan.crossings] == [c["direction"] for c in r["crossings"]]
    for got, want in zip(scan.crossings, r["crossings"]):
        assert _rel(got[0], want["speed"]) < 1e-10, (got, want)
    assert _rel(scan.first[0], r["V"]) < 1e-10
    assert unstable_count(family, m, 0.999 * r["V"]) == (0, True)
    assert unstable_count(family, m, 1.001 * r["V"]) == (1, True)


@pytest.mark.parametrize("window", REF["windows"], ids=lambda w: f"{w['case']}-{w['L']}")
def test_windows_of_growth_below_the_critical_speed(window):
    """Where a family grows on a narrow window of speed below another branch's critical
    speed (a 12 mm disc on organic half-planes at L = 50 mm: 458.70 < V < 465.78 m/s, then
    from 927.40; on organic pad layers at L = 1.15 m: 0.000853 < V < 0.00110 m/s, then from
    0.400), every crossing up to V_high is found, to 1e-10, the first the critical speed."""
    family = _family(window["case"], window["family"])
    m = 2 * math.pi / window["L"]
    scan = speed_scan(family, m, window["V_high"], every=True)
    want = window["crossings"]
    assert [c[2] for c in scan.crossings] == [c["direction"] for c in want] == [1, -1, 1]
    for got, c in zip(scan.crossings, want):
        assert _rel(got[0], c["speed"]) < 1e-10, (got, c)
    assert scan.certified and _rel(family.critical(m)[0], want[0]["speed"]) < 1e-10
    # Growing inside the window, decaying between it and the next branch.
    inside = math.sqrt(want[0]["speed"] * want[1]["speed"])
    between = math.sqrt(want[1]["speed"] * want[2]["speed"])
    assert family.modes(m, inside)[0].real > 0 > family.modes(m, between)[0].real


@pytest.mark.parametrize("case", ["A", "D"])
def test_interior_minima_over_the_wavelength(case):
    """The reference's interior minima of the critical speed over L in [d, 200 d]: the
    package's neutral speed, continued in ln L from the reference's minimum (the pattern's
    speed held: omega = -c m) and minimised there, has the same least value to 1e-10 (the
    wavelength to 1e-4: the minimum is flat)."""
    for fam, r in REF["cases"][case]["minimum"].items():
        if r["boundary"]:
            continue
        family = _family(case, fam)
        m0 = 2 * math.pi / r["L_min"]
        V0, w0, ok = neutral_point(family, m0, r["V_min"] * (1 + 1e-6),
                                   -r["migration_speed_at_min"] * m0)
        assert ok

        def vc(x):
            V, w, ok = neutral_point(family, math.exp(x), V0, w0 * math.exp(x) / m0)
            return V if ok else math.inf

        res = minimize_scalar(vc, bounds=(math.log(m0) - 0.02, math.log(m0) + 0.02),
                              method="bounded", options={"xatol": 1e-9})
        assert _rel(res.fun, r["V_min"]) < 1e-10, (case, fam)
        assert abs(res.x - math.log(m0)) < 1e-4


def test_minimum_at_the_end_of_the_range_is_flagged():
    """Between rigid non-conducting pads the symmetric critical speed falls without end as
    L grows (the reference: least at 200 d, 'boundary'); the study's minimum is there and
    says so (`minimum_at_range_end`, in the record and the text), while the
    antisymmetric family's is interior and equals the reference's to 1e-10."""
    ref = REF["cases"]["B"]["minimum"]
    assert ref["sym"]["boundary"] and not ref["anti"]["boundary"]
    r = tei(DISC, RIGID, F, 0.05, dundurs=False, slider_thickness=REF["cases"]["B"]["d"])
    fams = {f.family: f for f in r.families}
    sym, anti = fams["symmetric"], fams["antisymmetric"]
    assert sym.minimum_at_range_end is True and anti.minimum_at_range_end is False
    assert _rel(sym.minimum_wavelength, r.wavelength_range[1]) < 1e-12
    assert _rel(sym.minimum_critical_speed, ref["sym"]["V_min"]) < 1e-10
    assert _rel(anti.minimum_critical_speed, ref["anti"]["V_min"]) < 1e-10
    assert r.to_dict()["families"][1]["minimum_at_range_end"] is True
    text = "\n".join(report_lines(r))
    assert text.count("the end of the range searched") == 1


def test_a_thick_disc_is_the_half_planes_through_the_call():
    """A disc 1 km thick (case C) through the call: both families at the reference's
    half-plane limit, to 1e-10, no minimum sought (no wavelength range), no error."""
    ref = REF["cases"]["C"]["per_wavelength"][0]
    r = tei(DISC, PAD, F, 0.05, dundurs=False, slider_thickness=1e3)
    assert r.wavelength_range is None
    for f in r.families:
        want = ref["sym" if f.family == "symmetric" else "anti"]
        assert _rel(f.critical_speed, want["V"]) < 1e-10 and f.certified
        assert f.minimum_critical_speed is None


@pytest.mark.parametrize("speed", ["400.0", "459.0", "600.0", "800.0", "930.0"])
def test_every_mode_at_a_speed(speed):
    """Case A, L = 50 mm, symmetric family: the modes listed at a speed include the
    reference's roots next to the imaginary axis (to 1e-10 of kappa m^2 of the disc, in the
    frame of each), below the pads' continuous spectrum too (Re b < -kappa m^2 of the pad
    at 600 and 800 m/s), and the rightmost is the reference's; each of the first two is
    an eigenvalue of the depth discretisation, which converges to it (a mode at rest on
    the disc to rounding by n = 32; one at rest on the pads algebraically, as the
    half-plane's mapped depth does: 1e-4 at n = 32, 1e-6 to 3e-8 at n = 96)."""
    V, m = float(speed), 2 * math.pi / 0.05
    family = _family("A", "sym")
    got = family.modes(m, V)
    want = np.array([complex(*z) for z in REF["roots_A_50mm"]["sym"][speed]])
    scale = DISC.k * m * m
    for z in want:
        assert np.min(np.abs(got - z)) < 1e-10 * scale, (z, got)
    assert abs(got[0] - want[np.argmax(want.real)]) < 1e-10 * scale
    assert got[0].real < -PAD.k * m * m or V in (400.0, 459.0, 930.0)
    for b in got[:2]:
        errs = [np.min(np.abs(layup_modes(family.layup, m, V, n) - b)) / (abs(b) + scale)
                for n in (32, 96)]
        assert errs[1] < 1e-5 and (errs[1] < errs[0] / 10 or max(errs) < 1e-8), errs
