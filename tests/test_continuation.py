"""Pseudo-arclength continuation: round a fold, or pass a regular point."""

import numpy as np
import pytest

from thermocontact.numerics.continuation import arclength


def test_finds_the_fold_of_a_parabola():
    """x^2 + t - 1 = 0 from x = -0.9: t grows to the fold at (0, 1), then turns back."""
    def residual(z):
        return np.array([z[0] ** 2 + z[1] - 1.0])

    def jacobian(z, F):
        return np.array([[2.0 * z[0], 1.0]])
    outcome, z = arclength(residual, jacobian, [-0.9, 0.19], until=2.0, ds=0.05)
    assert outcome == "fold"
    assert z[1] == pytest.approx(1.0, abs=1e-4)
    assert z[0] == pytest.approx(0.0, abs=0.05)


def test_passes_where_the_branch_is_regular():
    """A branch without a fold (x^3 + x - t = 0): followed to t = 2 on the solution."""
    def residual(z):
        return np.array([z[0] ** 3 + z[0] - z[1]])

    def jacobian(z, F):
        return np.array([[3.0 * z[0] ** 2 + 1.0, -1.0]])
    outcome, z = arclength(residual, jacobian, [0.0, 0.0], until=2.0, ds=0.1)
    assert outcome == "passed" and z[1] >= 2.0
    assert z[0] ** 3 + z[0] - z[1] == pytest.approx(0.0, abs=1e-10)
