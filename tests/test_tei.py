"""Thermoelastic instability of sliding half-planes (docs/derivation.md, "Thermoelastic
instability of sliding half-planes", H1-H12): closed forms, two independent methods,
limits and symmetries, the command and the API."""

import json
import math
import pickle
import warnings

import numpy as np
import pytest
from scipy.integrate import IntegrationWarning, quad
from scipy.optimize import brentq

from thermocontact.cli import main
from thermocontact.discretisation.tei_depth import depth_modes
from thermocontact.physics.green_functions import cylinder_slope
from thermocontact.physics.tei import (SlidingPair, dispersion, high_speed_unstable, modes,
                                       speed_lower_bound, surface_kernels)
from thermocontact.problem.materials import Material, MaterialError, get_material
from thermocontact.problem.validation import InputError
from thermocontact.api import tei
from thermocontact.studies.tei import (TEIResult, critical_speed, critical_speeds,
                                       growth_rate, most_unstable_wavelength)

STEEL = get_material("steel")
PAD = get_material("organic-composite-brake-block")
IRON = get_material("cast-iron")
COPPER = get_material("copper")
BRONZE = get_material("bronze")
#: The pad as a non-conductor: K -> 0 at fixed heat capacity.
INSULATOR = Material("insulator", PAD.E, PAD.nu, PAD.alpha, 0.0, 0.0)
M = 2.0 * math.pi / 0.05


def _rel(a, b):
    return abs(a - b) / abs(b)


# --- closed forms -----------------------------------------------------------------

def _non_conductor_neutral(conductor, pair, m, slider_conducts):
    """(H12): the neutral speed and migration speed of a conductor against a
    non-conductor: z(z + 1) = G/c, z = a + iq on the neutral line, with
    (a - 1)(1 + 2a)^2 = beta'^2 (1 + a), G = (1 + beta'^2)(1 + a)."""
    bp = 0.5 * pair.beta * pair.friction  # sgn U = +1
    roots = np.roots([4.0, 0.0, -(3.0 + bp * bp), -(1.0 + bp * bp)])  # (a-1)(1+2a)^2 - bp^2(1+a)
    a = max(r.real for r in roots if abs(r.imag) < 1e-12 and r.real >= 1.0 - 1e-12)
    q = -bp * (1.0 + a) / (1.0 + 2.0 * a)
    G = (1.0 + bp * bp) * (1.0 + a)
    vc = G * pair.compliance * m / (2.0 * pair.friction * conductor.distortivity)
    drift = -2.0 * conductor.k * m * a * q   # pattern speed relative to the conductor
    return vc, (vc + drift if slider_conducts else drift)


@pytest.mark.parametrize("dundurs", [False, True])
@pytest.mark.parametrize("slider_conducts", [False, True])
def test_conductor_against_non_conductor_closed_form(dundurs, slider_conducts):
    """Burton's neutral speed A m/(f delta) (no Dundurs term; the mode is fixed on the
    conductor) and its extension with beta f (a cubic), against the general search."""
    pair = (SlidingPair(STEEL, INSULATOR, 0.4, dundurs) if slider_conducts
            else SlidingPair(INSULATOR, STEEL, 0.4, dundurs))
    vc, mode = critical_speed(pair, M)
    exact, migration = _non_conductor_neutral(STEEL, pair, M, slider_conducts)
    assert _rel(vc, exact) < 1e-11
    assert abs(mode.migration_speed - migration) < 1e-9 * exact
    if not dundurs:
        assert _rel(exact, pair.compliance * M / (0.4 * STEEL.distortivity)) < 1e-15
        assert mode.migration_speed == pytest.approx(exact if slider_conducts else 0.0,
                                                     abs=1e-9 * exact)
        # The bound (H9) is sharp here: equality at the neutral speed.
        assert _rel(speed_lower_bound(pair, M), exact) < 1e-14
    else:
        burton = pair.compliance * M / (0.4 * STEEL.distortivity)
        assert abs(pair.beta) > 0.5 and _rel(vc, burton) > 1e-3


def _identical(phi):
    """Steel on steel with the friction that makes 2 f kappa delta/A = phi."""
    A = 2.0 * STEEL.compliance
    f = phi * A / (2.0 * STEEL.k * STEEL.distortivity)
    return SlidingPair(STEEL, STEEL, f)


@pytest.mark.parametrize("phi", [0.55, 0.8, 2.0, 10.0])
def test_identical_materials_above_threshold(phi):
    """(H11b) V_c = kappa m 8 phi/(4 phi^2 - 1), the mode migrating at V_c/2."""
    pair = _identical(phi)
    vc, mode = critical_speed(pair, M)
    exact = STEEL.k * M * 8.0 * phi / (4.0 * phi * phi - 1.0)
    assert _rel(vc, exact) < 1e-11
    assert _rel(mode.migration_speed, exact / 2.0) < 1e-11
    assert high_speed_unstable(pair)


@pytest.mark.parametrize("phi", [0.2, 0.45, 0.499])
def test_identical_materials_below_threshold_stable_at_all_speeds(phi):
    """Below 2 f kappa delta/A = 1/2 no mode grows at any speed."""
    pair = _identical(phi)
    assert not high_speed_unstable(pair)
    assert critical_speed(pair, M) == (None, None)
    for v in np.geomspace(speed_lower_bound(pair, M), 1e9 * STEEL.k * M, 40):
        assert growth_rate(pair, M, v) < 0.0
    r = tei(STEEL, STEEL, pair.friction, 0.05, speed=10.0)
    assert r.stable_at_all_speeds and r.critical_speed is None and r.migration_speed is None
    assert r.most_unstable_wavelength is None
    assert all(mode.growth_rate < 0 for mode in r.modes)


# --- two methods ----------------------------------------------------------------------

DISSIMILAR = [
    (SlidingPair(STEEL, PAD, 0.4), 60.0),
    (SlidingPair(STEEL, IRON, 0.3), 1100.0),
    (SlidingPair(COPPER, STEEL, 0.3), 5.0),
    (SlidingPair(BRONZE, STEEL, 0.5, dundurs=False), 40.0),
]


@pytest.mark.parametrize("pair, speed", DISSIMILAR)
def test_root_search_against_depth_discretisation(pair, speed):
    """Every mode right of the continuous spectrum agrees with the depth
    discretisation, whose error falls by at least 30 from n = 24 to 64 (observed:
    1e-4 to 2e-8 ... 4e-6 to 2e-10 of |b|), to 2e-7 at n = 64."""
    b = modes(pair, M, speed)
    edge = min(mat.k for mat in pair.bodies) * M * M
    b = b[b.real > -0.5 * edge]
    assert b.size
    for x in b:
        assert abs(dispersion(pair, x, M, speed)) < 1e-10
    errs = []
    for n in (24, 64):
        bd = depth_modes(pair, M, speed, n)
        errs.append(max(np.min(np.abs(bd - x)) / abs(x) for x in b))
    assert errs[1] < 2e-7 and errs[1] < errs[0] / 30


@pytest.mark.parametrize("case, tol", [(0, 1e-4), (1, 1e-6), (2, 2e-6)])
def test_critical_speed_by_depth_discretisation(case, tol):
    """The neutral speed where the depth discretisation's largest growth rate changes
    sign equals the root search's (n = 64).  Observed relative differences at
    n = 32, 48, 64: steel/pad 4.1e-4, 5.5e-5, 3.7e-5 (the pattern crosses the pad at a
    Péclet number near 1e6: a layer 30 times thinner than the map's scale);
    steel/iron 1.5e-4, 9.0e-6, 3.5e-7; copper/steel 8.0e-5, 1.2e-5, 9.4e-7."""
    pair = DISSIMILAR[case][0]
    vc, mode = critical_speed(pair, M)

    def sigma(v):
        return depth_modes(pair, M, v, 64)[0].real

    v2 = brentq(sigma, vc * (1.0 - 10 * tol), vc * (1.0 + 10 * tol), rtol=1e-12)
    assert _rel(v2, vc) < tol
    bd = depth_modes(pair, M, v2, 64)[0]
    assert abs(-bd.imag / M - mode.migration_speed) < 10 * tol * vc


# --- limits, bounds and symmetries ----------------------------------------------------

def test_steady_limit_of_the_kernels():
    """b -> 0: the stationary body's displacement per heat is delta/m^2 (D4) and its
    temperature 1/(K m); the moving body's (material at -v, the cylinder of section 3)
    equals the Fourier transform of the slope kernel (D7), delta N(u) H(u)."""
    for m in (3.0, 40.0):
        heat, disp = surface_kernels(0.0, m, 0.0, STEEL)
        assert _rel(disp / heat, STEEL.distortivity / m**2) < 1e-12
        assert _rel(1.0 / heat, 1.0 / (STEEL.K * m)) < 1e-12
    v, m = 0.3, 2.0e3
    heat, disp = surface_kernels(0.0, m, -v, STEEL)
    kernel = complex(disp / heat)          # w / q for e^{imx}
    scale = v / (2.0 * STEEL.k)
    with warnings.catch_warnings():   # QAWF's cycles near u = 0, where N H jumps
        warnings.simplefilter("ignore", IntegrationWarning)
        cos, sin = (quad(cylinder_slope, 0.0, np.inf, weight=w, wvar=m / scale,
                         epsabs=1e-15)[0] for w in ("cos", "sin"))
    # Fourier transform of dw/dx per unit line heat, x = u/scale.
    slope_ft = -STEEL.distortivity * (cos - 1j * sin) / scale
    assert abs(1j * m * kernel - slope_ft) < 1e-12 * abs(slope_ft)


def test_no_mode_grows_below_the_bound():
    for pair, _ in DISSIMILAR:
        low = speed_lower_bound(pair, M)
        for v in np.geomspace(low * 1e-3, low, 7):
            assert growth_rate(pair, M, v) < 0.0


@pytest.mark.parametrize("pair, speed", DISSIMILAR)
def test_reversing_the_sliding_direction(pair, speed):
    """The mirror image x -> -x: b(-U) is the conjugate of b(U)."""
    b, r = modes(pair, M, speed), modes(pair, M, -speed)
    assert b.size == r.size
    assert np.max(np.abs(np.sort_complex(np.conj(r)) - np.sort_complex(b))) < 1e-9 * np.max(abs(b))


@pytest.mark.parametrize("pair, speed", DISSIMILAR)
def test_exchanging_the_bodies(pair, speed):
    """The counterface sliding on the slider is the same motion seen from the slider,
    mirrored: b' = conj(b + i m V); growth rates equal, migration speeds add to V."""
    swapped = SlidingPair(pair.counterface, pair.slider, pair.friction, pair.dundurs)
    assert swapped.beta == -pair.beta
    b = modes(pair, M, speed)
    expect = np.sort_complex(np.conj(b + 1j * M * speed))
    got = np.sort_complex(modes(swapped, M, speed))
    assert np.max(np.abs(got - expect)) < 1e-9 * M * speed
    vc, mode = critical_speed(pair, M)
    vc2, mode2 = critical_speed(swapped, M)
    assert _rel(vc2, vc) < 1e-11
    assert abs(mode.migration_speed + mode2.migration_speed - vc) < 1e-9 * vc


def test_critical_speed_is_proportional_to_the_wavenumber():
    """(H11): only V/(kappa m) enters, so V_c L is the same at every wavelength."""
    pair = SlidingPair(STEEL, IRON, 0.3)
    wl = np.array([0.01, 0.05, 0.4])
    direct = [critical_speed(pair, 2.0 * math.pi / x)[0] for x in wl]
    assert np.ptp(np.array(direct) * wl) < 1e-10 * direct[0] * wl[0]
    assert np.allclose(critical_speeds(pair, wl), direct, rtol=1e-10, atol=0)


def test_most_unstable_wavelength_is_a_maximum():
    pair = SlidingPair(STEEL, PAD, 0.4)
    wl, rate = most_unstable_wavelength(pair, 60.0, M)
    m = 2.0 * math.pi / wl
    assert rate > 0.0 and _rel(growth_rate(pair, m, 60.0), rate) < 1e-12
    for factor in (0.9, 1.1):
        assert growth_rate(pair, m * factor, 60.0) < rate


# --- results, the call and the command --------------------------------------------

def test_result_record_equality_pickle_repr():
    r = tei("steel", "organic-composite-brake-block", 0.4, "50mm", speed="60 m/s")
    assert isinstance(r, TEIResult)
    d = r.to_dict()
    assert set(d) == {"slider", "counterface", "friction", "wavelength", "dundurs", "beta",
                      "critical_speed", "stable_at_all_speeds", "migration_speed", "speed",
                      "modes", "most_unstable_wavelength", "most_unstable_growth_rate",
                      "plane", "slider_thickness", "faces", "counterface_thickness",
                      "backing", "separator", "separator_thickness", "families",
                      "wavelength_range", "status", "message", "success", "units"}
    assert d["status"] == "solved" and d["success"] and d["units"]["critical_speed"] == "m/s"
    assert d["plane"] == "strain" and d["families"] == [
        {"family": "all", "critical_speed": d["critical_speed"],
         "migration_speed": d["migration_speed"], "minimum_critical_speed": None,
         "minimum_wavelength": None, "minimum_at_range_end": None, "crossings": [],
         "certified": None}]
    assert d["wavelength"] == 0.05 and d["speed"] == 60.0
    rates = [mode["growth_rate"] for mode in d["modes"]]
    assert rates == sorted(rates, reverse=True) and rates[0] > 0   # 60 > V_c = 55.4
    for mode in d["modes"]:
        assert _rel(mode["frequency"], mode["migration_speed"] / 0.05) < 1e-14
    json.dumps(d, allow_nan=False)
    assert pickle.loads(pickle.dumps(r)) == r
    assert r == tei(STEEL, PAD, 0.4, 0.05, speed=60.0)
    assert r != tei(STEEL, PAD, 0.4, 0.05, speed=60.0, dundurs=False)
    assert "\n" not in repr(r) and len(repr(r)) < 200 and "55.37" in repr(r)
    assert repr(r).startswith("TEIResult(carbon-steel on organic-composite-brake-block")
    assert r != r.replace(critical_speed=r.critical_speed + 1.0)
    assert r.modes[0] == pickle.loads(pickle.dumps(r.modes[0]))
    from thermocontact.io.results import Result

    for cls in (TEIResult, type(r.modes[0])):   # the package's result protocol
        assert issubclass(cls, Result) and cls.__repr__ is Result.__repr__
        assert cls.__eq__ is Result.__eq__ and cls.__hash__ is None
    plain = tei(STEEL, PAD, 0.4, 0.05).to_dict()
    assert "modes" not in plain and plain["critical_speed"] == d["critical_speed"]


def test_command_json_is_the_record(capsys, tmp_path):
    args = ["tei", "--slider", "steel", "--counterface", "organic-composite-brake-block",
            "--friction", "0.4", "--wavelength", "50mm", "--speed", "60"]
    assert main(args + ["--json"]) == 0
    rec = json.loads(capsys.readouterr().out)
    assert rec == tei("steel", "organic-composite-brake-block", 0.4, "50mm", speed=60).to_dict()
    assert main(args) == 0
    out = capsys.readouterr().out
    assert "critical speed  55.37" in out and "most unstable wavelength" in out
    assert main(args[:-2] + ["--no-dundurs", "--json"]) == 0
    rec = json.loads(capsys.readouterr().out)
    assert rec["dundurs"] is False and rec["beta"] == 0.0
    toml = tmp_path / "m.toml"
    toml.write_text('[felt]\nE = 1e9\nnu = 0.3\nalpha = 1e-5\nK = 0\nk = 0\n')
    assert main(["tei", "--slider", "steel", "--counterface", "felt", "--friction", "0.4",
                 "--wavelength", "0.05", "--materials", str(toml), "--json"]) == 0
    rec = json.loads(capsys.readouterr().out)
    felt = get_material("felt", toml)
    burton = (STEEL.compliance + felt.compliance) * M / (0.4 * STEEL.distortivity)
    assert rec["counterface"] == "felt"
    assert _rel(rec["critical_speed"], burton) < 0.05   # beta f moves it a little


@pytest.mark.parametrize("change, flag, fragment", [
    (["--wavelength", "0"], "--wavelength", "must be in [1e-09, 1000], got 0.0"),
    (["--wavelength", "-3mm"], "--wavelength", "must be in [1e-09, 1000]"),
    (["--wavelength", "1e-300"], "--wavelength", "must be in [1e-09, 1000], got 1e-300"),
    (["--wavelength", "1e300", "--speed", "10"], "--wavelength", "must be in [1e-09, 1000]"),
    (["--speed", "-1"], "--speed", "must be 0 or in [1e-09, 10000], got -1.0"),
    (["--speed", "1e300"], "--speed", "must be 0 or in [1e-09, 10000]"),
    (["--speed", "1e-200"], "--speed", "must be 0 or in [1e-09, 10000]"),
    (["--friction", "-0.1"], "--friction", "must be 0 or in [1e-06, 10], got '-0.1'"),
    (["--friction", "1e-400"], "--friction", "must be 0 or in [1e-06, 10], got '1e-400'"),
    (["--slider-thickness", "0"], "--slider-thickness", "must be in [1e-09, 1000], got 0.0"),
    (["--slider-thickness", "-2mm"], "--slider-thickness", "must be in [1e-09, 1000]"),
    (["--slider-thickness", "12kg"], "--slider-thickness", "cannot read '12kg'"),
    (["--counterface-thickness", "0mm"], "--counterface-thickness", "must be in [1e-09"),
    (["--disc-radius", "0.1", "--hot-spots", "5:2"], "--hot-spots", "N1 <= N2 (not empty)"),
    (["--disc-radius", "0.1", "--hot-spots", "1.5:3"], "--hot-spots", "integers"),
    (["--disc-radius", "0.1", "--hot-spots", "a"], "--hot-spots", "N1:N2"),
    (["--hot-spots", "1:3"], "--hot-spots", "needs --disc-radius"),
    (["--stop", "30:8"], "--stop", "needs --disc-radius"),
    (["--disc-radius", "0.1", "--stop", "30:-8"], "--stop", "must be in [1e-09, 1e+06]"),
    (["--disc-radius", "0.1", "--stop", "30"], "--stop", "V0:DECEL"),
    (["--separator", "steel"], "--separator", "MATERIAL:THICKNESS"),
    (["--separator", "steel:2mm"], "--separator", "needs --slider-thickness"),
    (["--slider", "E=1e9,nu=0.3,alpha=1e-5,K=0,k=0", "--slider-thickness", "5mm",
      "--counterface", "E=1e9,nu=0.3,alpha=1e-5,K=0,k=0"], "--slider", "non-conducting"),
    (["--friction", "1e-300"], "--friction", "must be 0 or in [1e-06, 10]"),
    (["--friction", "1e300"], "--friction", "must be 0 or in [1e-06, 10]"),
    (["--slider", "E=1e9,nu=0.3,alpha=1e-5,K=0,k=0",
      "--counterface", "E=1e9,nu=0.3,alpha=1e-5,K=0,k=0"], "--slider", "non-conducting"),
])
def test_bad_input_is_refused_in_one_line(capsys, change, flag, fragment):
    base = {"--slider": "steel", "--counterface": "steel", "--friction": "0.4",
            "--wavelength": "50mm"}
    for k, v in zip(change[::2], change[1::2]):
        base[k] = v
    argv = ["tei"] + [x for kv in base.items() for x in kv]
    assert main(argv) == 2
    err = capsys.readouterr().err.strip()
    assert "\n" not in err and flag in err and fragment in err


def test_api_refuses_bad_input():
    with pytest.raises(InputError, match=r"wavelength must be in \[1e-09, 1000\]"):
        tei("steel", "steel", 0.3, 0.0)
    with pytest.raises(InputError, match=r"speed must be 0 or in \[1e-09, 10000\]"):
        tei("steel", "steel", 0.3, 0.05, speed="-2 m/s")
    with pytest.raises(InputError, match=r"friction must be 0 or in \[1e-06, 10\]"):
        tei("steel", "steel", -0.3, 0.05)
    with pytest.raises(InputError, match="both be non-conducting"):
        tei(INSULATOR, INSULATOR, 0.3, 0.05)


def test_non_conductor_material_and_the_steady_contact():
    """K = 0 is accepted as a material (k may then be 0), does not distort, and the
    steady contact refuses it in one line naming the body."""
    m = get_material("E=2e9,nu=0.25,alpha=2.5e-5,K=0,rho=2100,c=1000")
    assert m.K == 0.0 and m.k == 0.0 and not m.conducts and m.distortivity == math.inf
    heat, disp = surface_kernels(1.0 + 2.0j, M, 3.0, m)
    assert heat == 0 and disp == 0
    with pytest.raises(MaterialError, match="k must be > 0"):
        Material("x", 1e9, 0.3, 1e-5, 1.0, 0.0)
    from thermocontact import contact

    with pytest.raises(InputError) as err:
        contact(STEEL, m, radius="10mm", load=1e5, speed=1.0, friction=0.3, lam=0.0)
    assert "half_plane must conduct heat (K > 0)" in str(err.value)
    assert "\n" not in str(err.value)


def test_plot_returns_axes(tmp_path):
    import matplotlib

    matplotlib.use("Agg")
    from matplotlib.figure import Figure

    from thermocontact.plotting.tei import plot_tei, tei_figure

    r = tei("steel", "cast-iron", 0.3, "50mm", speed=2000)
    ax = plot_tei(r, ax=Figure().subplots(), wavelengths=[0.01, 0.05, 0.2])
    line = ax.get_lines()[0]
    assert np.allclose(line.get_ydata(), r.critical_speed * 0.05 / line.get_xdata(), rtol=1e-10)
    path = tmp_path / "tei.png"
    tei_figure(r, str(path))
    assert path.stat().st_size > 1000


def test_docstring_example():
    import doctest

    from thermocontact.studies import tei as module

    result = doctest.testmod(module)
    assert result.attempted > 0 and result.failed == 0


def test_public_call_and_edge_inputs():
    """The package exports the call; no friction or no speed makes no heat: nothing grows."""
    import thermocontact

    assert thermocontact.tei is tei
    r = tei("steel", "cast-iron", 0.0, 0.05, speed=10.0)
    assert r.stable_at_all_speeds and r.critical_speed is None
    assert r.modes == () and r.most_unstable_wavelength is None
    r = tei("steel", "cast-iron", 0.3, 0.05, speed=0.0)
    assert r.modes == () and r.most_unstable_wavelength is None and r.critical_speed > 0
    assert not high_speed_unstable(SlidingPair(STEEL, IRON, 0.0))


NC = "E=2e9,nu=0.25,alpha=2e-5,K=0,k=0"


@pytest.mark.parametrize("argv, flag", [
    (["contact", "--cylinder", "steel", "--half-plane", NC, "--radius", "10mm", "--load", "1e5",
      "--speed", "1", "--friction", "0.3", "--lam", "0"], "--half-plane"),
    (["map", "--cylinder", NC, "--half-plane", "steel", "--radius", "10mm", "--friction", "0.2",
      "--lam", "-1", "--x", "load:1e2:1e6:5:log", "--y", "speed:0.01:100:5:log", "--out",
      "op.nc"], "--cylinder"),
    (["boundary", "--along", "load", "--from", "10kN/m", "--to", "1MN/m", "--cylinder", "steel",
      "--half-plane", NC, "--radius", "450mm", "--speed", "1", "--friction", "0.35", "--lam",
      "1", "-n", "16"], "--half-plane"),
])
def test_steady_commands_refuse_a_non_conductor(capsys, tmp_path, monkeypatch, argv, flag):
    monkeypatch.chdir(tmp_path)
    assert main(argv) == 2
    err = capsys.readouterr().err.strip()
    assert "\n" not in err and f"{flag} must conduct heat (K > 0)" in err
    assert not (tmp_path / "op.nc").exists()
