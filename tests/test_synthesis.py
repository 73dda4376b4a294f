"""Synthesis over orders against closed forms (issue 14): one order gives back its amplitude,
two orders with known phases their analytic extremes, to round-off (not to the sampling)."""

import numpy as np
import pytest

from fetorsion.response.synthesis import BATCH, extremes, half_peak_to_peak, largest_half_peak_to_peak

CYCLE = 4 * np.pi  # a four-stroke cycle


@pytest.mark.parametrize("order", [0.5, 6.0, 11.5])
def test_one_order_gives_back_its_amplitude(order):
    z = np.array([[2.5 * np.exp(1.234j)], [0.7 * np.exp(-2.0j)]])  # two signals, one order each
    top, bottom = extremes(z, np.array([order]), CYCLE)
    np.testing.assert_allclose(top, [2.5, 0.7], rtol=1e-13)
    np.testing.assert_allclose(bottom, [-2.5, -0.7], rtol=1e-13)
    np.testing.assert_allclose(half_peak_to_peak(z, np.array([order]), CYCLE), [2.5, 0.7], rtol=1e-13)


def test_two_orders_with_known_phases_give_the_analytic_extremes():
    # x = cos 2θ + 0.3 cos 4θ: max 1.3 at θ = 0; min where cos 2θ = -1/1.2, x = c + 0.6 c² - 0.3.
    c = -1 / 1.2
    z = np.array([1.0, 0.3]) * np.exp(1j * 0.0)
    top, bottom = extremes(z, np.array([2.0, 4.0]), CYCLE)
    assert top == pytest.approx(1.3, rel=1e-13)
    assert bottom == pytest.approx(c + 0.6 * c**2 - 0.3, rel=1e-13)
    # The same signal delayed by any angle has the same extremes (phases of the orders q·δ).
    delay = 0.37
    shifted = z * np.exp(-1j * np.array([2.0, 4.0]) * delay)
    np.testing.assert_allclose(extremes(shifted, np.array([2.0, 4.0]), CYCLE), (top, bottom), rtol=1e-13)


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_largest_half_peak_to_peak_is_the_max_of_the_whole_synthesis(seed):
    """The pruned maximum (signals taken by their bound Σ|z_q| until it falls below the best found)
    equals the maximum over every signal's synthesis, weights included: random signals whose
    bound order differs from their peak-to-peak order, a few of them strong (a resonance), more
    signals than one batch."""
    rng = np.random.default_rng(seed)
    orders = np.arange(0.5, 12.01, 0.5)
    z = (rng.normal(size=(300, 7, len(orders))) + 1j * rng.normal(size=(300, 7, len(orders))))
    z *= rng.uniform(0.2, 1.0, size=(300, 7, 1))
    z[rng.integers(0, 300, 5), rng.integers(0, 7, 5)] *= 6.0
    weights = rng.uniform(0.5, 2.0, size=7)
    assert z.shape[0] * z.shape[1] > BATCH
    full = (half_peak_to_peak(z, orders, CYCLE) * weights[None, :]).max()
    assert largest_half_peak_to_peak(z, orders, CYCLE, weights[None, :]) == pytest.approx(full, rel=1e-13)
    assert largest_half_peak_to_peak(z[:, 0], orders, CYCLE) == pytest.approx(
        half_peak_to_peak(z[:, 0], orders, CYCLE).max(), rel=1e-13)
