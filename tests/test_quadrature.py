"""Gauss–Chebyshev rules: weights, polynomial exactness, exact Cauchy values, series."""

import numpy as np
import pytest
from numpy.polynomial import chebyshev as C
from scipy.special import beta, eval_chebyt, eval_chebyu

from thermocontact.numerics.quadrature import (
    bounded_rule,
    singular_rule,
    t_series_coefficients,
    u_series_coefficients,
    u_series_value,
)

NS = [4, 7, 32, 101]


@pytest.mark.parametrize("n", NS)
def test_weights_sum(n):
    """Bounded weights sum to pi/2, singular weights to pi (to 1e-14)."""
    assert abs(bounded_rule(n).weights.sum() - np.pi / 2) < 1e-14
    assert abs(singular_rule(n).weights.sum() - np.pi) < 1e-14


@pytest.mark.parametrize("n", NS)
def test_polynomial_exactness(n):
    """Both rules integrate even monomials to degree 2n - 2 exactly (rel. 1e-13).

    Reference: integral sqrt(1-r^2) r^(2k) dr = B(k + 1/2, 3/2) and
    integral r^(2k)/sqrt(1-r^2) dr = B(k + 1/2, 1/2).
    """
    br, sr = bounded_rule(n), singular_rule(n)
    for k in range(n):
        exact_b = beta(k + 0.5, 1.5)
        exact_s = beta(k + 0.5, 0.5)
        assert abs(br.weights @ br.nodes ** (2 * k) / exact_b - 1) < 1e-13
        assert abs(sr.weights @ sr.nodes ** (2 * k) / exact_s - 1) < 1e-13


@pytest.mark.parametrize("n", NS)
def test_bounded_cauchy_exact(n):
    """sum W_i U_j(r_i)/(pi(s_k - r_i)) = T_{j+1}(s_k) for j < n (abs. 1e-12).

    The exact finite Hilbert transform (1/pi) PV int sqrt(1-r^2) U_j(r)/(s-r) dr
    is T_{j+1}(s).
    """
    r = bounded_rule(n)
    s = r.collocation
    for j in range(n):
        approx = (r.weights * eval_chebyu(j, r.nodes) / (np.pi * (s[:, None] - r.nodes))).sum(1)
        assert np.max(np.abs(approx - eval_chebyt(j + 1, s))) < 1e-12 * max(1, n / 10)


@pytest.mark.parametrize("n", NS)
def test_singular_cauchy_exact(n):
    """sum (1/n) T_j(r_i)/(s_k - r_i) = -U_{j-1}(s_k) for 1 <= j < n, 0 for j = 0 (abs. 1e-12)."""
    r = singular_rule(n)
    s = r.collocation
    for j in range(n):
        approx = (eval_chebyt(j, r.nodes) / n / (s[:, None] - r.nodes)).sum(1)
        exact = -eval_chebyu(j - 1, s) if j else np.zeros_like(s)
        assert np.max(np.abs(approx - exact)) < 1e-12 * max(1, n / 10)


@pytest.mark.parametrize("n", NS)
def test_series_round_trip(n):
    """Values -> U/T coefficients -> values reproduces the data (abs. 1e-12)."""
    rng = np.random.default_rng(n)
    a = rng.standard_normal(n)
    br, sr = bounded_rule(n), singular_rule(n)
    values = sum(a[j] * eval_chebyu(j, br.nodes) for j in range(n))
    assert np.allclose(u_series_coefficients(values), a, atol=1e-12)
    s = np.linspace(-1, 1, 9)
    assert np.allclose(u_series_value(a, s), sum(a[j] * eval_chebyu(j, s) for j in range(n)),
                       atol=1e-11)
    tv = C.chebval(sr.nodes, a)
    assert np.allclose(t_series_coefficients(tv), a, atol=1e-12)
