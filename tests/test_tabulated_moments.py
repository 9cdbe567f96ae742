"""The kernel table of the linearised contact (``numerics.tabulated_moments``) across a
moving body's wake at large ``|b|``, against an independent quadrature."""

import json

import numpy as np
import pytest

from conftest import DATA
from thermocontact.discretisation.representations import EdgeGraded
from thermocontact.numerics.tabulated_moments import kernel_nodes, kernel_table
from thermocontact.physics.transient_green_functions import transient_temperature

#: Per case (c, b): the table's accuracy for the temperature kernel across the wake,
#: relative to the largest moment (derivation S9: 1e-10 and 1e-7 for panels of ratio
#: sqrt 2, observed 1.1e-10 and 1.2e-7 with the flux's weight, 1.5e-11 and 2.0e-8 with
#: the pressure's; panels of ratio 2 gave 6e-7 and 2e-4).
TOLERANCE = {(50.0, 3000j): 2e-10, (200.0, 1e4j): 2e-7}


@pytest.fixture(scope="module")
def stored():
    return json.loads((DATA / "wake_moments.json").read_text())


@pytest.mark.parametrize("c, b", list(TOLERANCE))
def test_a_moving_bodys_wake_at_large_rates(stored, c, b):
    """The moments the linearised assembly takes from the table for a moving body's
    temperature kernel exp(-c u) K0(sqrt(c^2 + b)|u|) (eq. T3), both weights, n = 8, at
    the projection points, where the wake is a barely damped oscillation of wavenumber
    about |b|/(2c): to the table's stated accuracy (:data:`TOLERANCE`) of adaptive
    quadrature in tau of the closed form (tests/data/make_wake_moments.py, itself
    accurate to 1e-13 of the largest moment)."""
    case = next(k for k in stored["cases"] if (k["c"], complex(*k["b"])) == (c, b))
    assert case["reference_change"] < 1e-13
    n, tau = stored["n"], np.array(stored["tau"])
    rep = EdgeGraded(n)
    # The stored cosine moments, to the nodal bases' moments the table gives.
    reference = (np.array(case["real"]) + 1j * np.array(case["imag"])) @ rep.to_cos
    tabled = kernel_table(tau, n, rep.to_cos).moments(transient_temperature(kernel_nodes(), c, b))
    for w in range(2):
        error = np.abs(tabled[w] - reference[w]).max() / np.abs(reference[w]).max()
        assert error < TOLERANCE[c, b], (w, error)


@pytest.mark.parametrize("n, alpha", [(8, 0.5), (12, 0.62)])
def test_small_cells_by_their_product_rule(monkeypatch, n, alpha):
    """The cells small against their distance from the edges, on the 8-point product
    rule in the panel's variable (derivation S9), give the table Gauss-Legendre in tau
    gives them (every cell so, the rule switched off): the same entries to 1e-14 of the
    largest of their weight's and point's row (observed at most 3.8e-16, also next to
    the edges, whose rows are small), the pressure's weight with the Dundurs term's edge
    exponents too."""
    from thermocontact.numerics import tabulated_moments as tm
    from thermocontact.numerics.moment_engine import graded_map

    rep = EdgeGraded(n, alpha=alpha)
    tau = np.pi * (np.arange(2 * n, 0, -1) - 0.5) / (2 * n)
    built = tm.KernelTable(tau, n, rep.to_cos, graded_map(alpha))
    monkeypatch.setattr(tm, "_TINY_RHO", np.inf)
    gauss = tm.KernelTable(tau, n, rep.to_cos, graded_map(alpha))
    for got, want in ((built.matrix, gauss.matrix), (built.coarse, gauss.coarse)):
        # Per weight and point (the map's first two axes): a row's largest entry.
        rows = (2, 3)
        assert np.all(np.abs(got - want).max(axis=rows) < 1e-14 * np.abs(want).max(axis=rows))
