"""Whether the theory applies: each measure against a closed form, and the verdicts
of the worked examples."""

import numpy as np
import pytest

from thermocontact import solve
from thermocontact.analysis.applicability import (MAX_HALF_WIDTH_OVER_RADIUS, applicability,
                                                   surface_slopes)
from thermocontact.problem.materials import get_material
from thermocontact.studies.physical_contact import PhysicalProblem, contact


def test_hertz_slopes_and_strain_are_the_closed_forms():
    """fHPe = 0 (Hertz): the elastic slope term of (D14) is (2/pi) s, so the surfaces'
    elastic slope is (Delta/R) s, the rigid profile's own (to 1e-13); the strain bound
    A p0 equals Delta/R exactly (p0 = 2P/(pi Delta), Delta^2 = 2ARP/pi); with equal
    compliances each body carries half the elastic slope."""
    sol = solve(5, 0.0, 10, lam=-1)
    s, elastic, t1, t2 = surface_slopes(sol)
    assert np.max(np.abs(elastic - 2 / np.pi * s)) < 1e-13
    assert np.all(t1 == 0) and np.all(t2 == 0)
    ratio = 1e-3
    app = applicability(sol, ratio)
    assert app.applicable and app.reasons == ()
    assert app.max_strain == pytest.approx((ratio, ratio), rel=1e-12)
    # Rigid profile at the edge (Delta/R) plus the whole elastic slope (a bound).
    assert app.max_slope[0] == pytest.approx(2 * ratio, rel=1e-4)
    half = applicability(sol, ratio, compliance_fractions=(0.5, 0.5))
    assert half.max_slope[1] == pytest.approx(1.5 * ratio, rel=1e-4)
    assert half.max_strain == pytest.approx((ratio / 2, ratio / 2), rel=1e-12)


def test_large_contact_is_not_applicable():
    sol = solve(5, 0.2, 10, lam=-1)
    app = applicability(sol, 0.3)
    assert not app.applicable and any("half-width/radius 0.3" in r for r in app.reasons)
    assert 0.3 > MAX_HALF_WIDTH_OVER_RADIUS


def test_electrical_contact_applicable_brake_block_not():
    """Copper on steel at 5 kN/m (docs/examples/electrical_contact.md) is within every
    assumption; the brake block (docs/examples/brake_block.md) is far outside: slopes
    and strains of order 1 and beyond, temperatures below absolute zero and above what
    the materials survive."""
    cu = contact(PhysicalProblem(get_material("copper"), get_material("steel"), 0.05, 5e3,
                                 10.0, 0.3, 0.0)).primary
    assert cu.applicable and cu.applicability.temperature_range[1] < 400
    brake = contact(PhysicalProblem(get_material("wheel-steel"),
                                    get_material("organic-composite-brake-block"), 0.46,
                                    3.1e5, 30.0, 0.3, -1.0)).primary
    reasons = " ".join(brake.applicability.reasons)
    assert not brake.applicable
    for words in ("not small slopes", "not small strains", "below absolute zero",
                  "material's limit 623 K"):
        assert words in reasons
