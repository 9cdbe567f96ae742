"""One evaluator of a contact's fields: a contact set's temperatures against independent
quadrature, and the physical results' records (frozen, picklable, equal by value,
to_dict the command line's JSON)."""

import dataclasses
import io
import json
import pickle
from contextlib import redirect_stdout

import numpy as np
import pytest
from scipy.special import k0

from thermocontact.analysis.fields import contact_fields, surface_temperatures
from thermocontact.cli import main
from thermocontact.problem.materials import get_material
from thermocontact.problem.parameters import Parameters
from thermocontact.solvers.zones import ZoneModel, ZoneSolution
from thermocontact.studies.contact_sets import PhysicalContactSet, physical_contact_set
from thermocontact.studies.physical_contact import PhysicalProblem, contact


def _two_zones():
    """Two zones with fluxes of no particular solution (the integrals hold for any) on
    the edge-graded representation, n = 32: nodal values of functions smooth in ``r``."""
    rep = ZoneModel(10.0, n=32).representation()
    r = rep.pressure_rule.nodes
    phi = np.array([0.4 + 0.1 * r, 0.3 - 0.05 * r**2])
    psi = np.array([0.2 * r - 0.05, 0.1 + 0.1 * r])
    return ZoneSolution(Parameters(3.0, 0.2, 10.0), 1.0, np.array([[-2.6, -1.1], [1.2, 2.5]]),
                        phi, psi, rep, "graded", 0.0, 0, 1.0)


def _graded_quadrature(f, lo, hi, at, nodes=120):
    """``integral f(theta) d theta`` over ``(lo, hi)`` by Gauss-Legendre on each side of
    ``at`` (None: no singular point), graded as ``at + t^3 L`` so that a logarithm at
    ``at`` becomes ``t^2 ln t`` (error of order nodes^-6); ``f`` vectorised."""
    x, w = np.polynomial.legendre.leggauss(nodes)
    t, w = 0.5 * (x + 1.0), 0.5 * w
    total = 0.0
    for a, b in ([(lo, hi)] if at is None else [(at, lo), (at, hi)]):
        # theta = a + (b - a) t^3, d theta = 3 (b - a) t^2 dt.
        th = a + (b - a) * t**3
        part = np.sum(w * 3.0 * t**2 * (b - a) * f(th))
        # From the singular point toward lo the orientation is reversed.
        total += part if at is None or b > a else -part
    return total


def test_contact_set_temperatures_against_quadrature():
    """Both surfaces' temperatures of two zones, each point taking every zone's heat:
    the cylinder's Carslaw-Jaeger integral (D8) and the stationary half-plane's logarithm
    (D12) over the zones' own fluxes by Gauss-Legendre quadrature in theta (which takes
    the fluxes' edge singularities away), graded at the point's own logarithm, to 1e-9
    relative (observed 2e-11); with the temperature units of the default, T2 carries 1/rho = K1/K2."""
    sol = _two_zones()
    par, rep, eta = sol.parameters, sol.representation, sol.parameters.eta
    c, rho = par.cylinder_scale, par.K2_over_K1
    for zone, s in ((0, np.array([-0.7, 0.2, 0.9])), (1, np.array([-0.4, 0.6]))):
        t1, t2 = surface_temperatures(sol, s, zone=zone)
        X = sol.centres[zone] + sol.half_widths[zone] * s
        for Xi, a, b in zip(X, t1, t2):
            q1 = q2 = 0.0
            for C, h, ph, ps in zip(sol.centres, sol.half_widths, sol.phi, sol.psi):
                def flux(th, sign):
                    r = np.cos(th)
                    # ((1 +- eta) p +- q') sin(theta) / 2, q' sin(theta) = psi(r).
                    return 0.5 * ((1 + sign * eta) * rep.pressure_at(ph, r) * np.sin(th)
                                  + sign * rep.psi_at(ps, r))

                def cyl(th):
                    u = c * (Xi - C - h * np.cos(th))
                    return flux(th, 1.0) * np.exp(-u) * k0(np.abs(u)) * h

                def log(th):
                    return -flux(th, -1.0) * np.log(np.abs(Xi - C - h * np.cos(th))) * h / rho
                at = np.arccos((Xi - C) / h) if abs(Xi - C) < h else None
                q1 += _graded_quadrature(cyl, 0.0, np.pi, at)
                q2 += _graded_quadrature(log, 0.0, np.pi, at)
            assert a == pytest.approx(q1, rel=1e-9)
            assert b == pytest.approx(q2, rel=1e-9)
    # The flash temperature: the greatest of T1, the closed form's maximum.
    f = contact_fields(sol)
    assert f.flash_temperature >= np.nanmax(f.temperature_cylinder)
    assert f.flash_temperature - np.nanmax(f.temperature_cylinder) < 1e-6 * f.flash_temperature
    assert f.x.size == 2 * 201 and f.extent == pytest.approx(2.55, rel=1e-14)


def _problem(**kw):
    args = dict(cylinder=get_material("steel"), half_plane=get_material("copper"),
                radius=0.01, load=2e5, speed=2.0, friction=0.3, lam=1.0)
    return PhysicalProblem(**{**args, **kw})


def _cli_json(argv):
    out = io.StringIO()
    with redirect_stdout(out):
        assert main(argv) == 0
    return json.loads(out.getvalue())


ARGS = ["--cylinder", "steel", "--half-plane", "copper", "--radius", "0.01", "--load", "2e5",
        "--speed", "2", "--lam", "1", "--json"]


def test_physical_contact_record_is_the_command_line_json():
    """`contact --json` prints `PhysicalContact.to_dict()`; the result is frozen, equal to
    itself unpickled (arrays by value), unequal to another contact, with a short repr
    (without friction: Hertz's contact, exact at any n, and fast)."""
    res = contact(_problem(friction=0.0))
    assert _cli_json(["contact", *ARGS, "--friction", "0"]) == json.loads(
        json.dumps(res.to_dict()))
    again = pickle.loads(pickle.dumps(res))
    assert again == res and again.primary == res.primary
    assert contact(_problem(friction=0.0, load=1e5)) != res
    assert res.primary != dataclasses.replace(res.primary, x=res.primary.x + 1.0)
    with pytest.raises(dataclasses.FrozenInstanceError):
        res.primary.half_width = 1.0
    assert len(repr(res)) < 400 and "array" not in repr(res)


def test_physical_contact_set_record_is_the_command_line_json():
    """`contact --zones --json` prints `PhysicalContactSet.to_dict()`: today's record (the
    zones in SI units and the dimensionless answer) with the temperatures and the full
    applicability; frozen, equal by value after pickling, short repr."""
    found = physical_contact_set(_problem(friction=0.0))
    assert isinstance(found, PhysicalContactSet)
    rec = found.to_dict()
    assert _cli_json(["contact", *ARGS, "--friction", "0", "--zones"]) == json.loads(
        json.dumps(rec))
    assert {"status", "message", "valid", "theory_applicable", "theory_reasons",
            "theory_checked", "hertz_half_width", "zones", "dimensionless",
            "flash_temperature", "peak_pressure", "applicable", "applicability_reasons",
            "max_slope", "max_strain", "temperature_range"} <= set(rec)
    assert rec["flash_temperature"] == 0.0 and rec["theory_reasons"] == rec[
        "applicability_reasons"]
    # Hertz's zone: peak pressure 2P/(pi l) in the zone and in the fields.
    p0 = 2 * 2e5 / (np.pi * found.hertz_half_width)
    assert rec["peak_pressure"] == pytest.approx(p0, rel=1e-10)
    assert rec["zones"][0]["peak_pressure"] == pytest.approx(p0, rel=1e-10)
    assert pickle.loads(pickle.dumps(found)) == found
    with pytest.raises(dataclasses.FrozenInstanceError):
        found.fields = None
    assert len(repr(found)) < 200
