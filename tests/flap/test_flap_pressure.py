"""Eqs. (13)-(14): signed chamber-pressure model with the cavitation clamp, and its fit."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from flumekit.flap.pressure import (
    chamber_pressure_model,
    fit_pressure_model,
    pressure_force,
    thoma_coefficient,
)

PATM, PV = 101325.0, 2339.0
CLAMP = PV - PATM


def _motion(n=2000, period=3.0, amp=0.6):
    t = np.linspace(0, 4 * period, n)
    w = 2 * np.pi / period
    thd = amp * np.cos(w * t) + 0.1 * amp * np.cos(2 * w * t + 1.0)
    thdd = -amp * w * np.sin(w * t) - 0.2 * amp * w * np.sin(2 * w * t + 1.0)
    return thd, thdd


def test_signed_model_compression_suction_and_clamp():
    thd = np.array([0.3, -0.05, -0.6, 0.0])
    p = chamber_pressure_model(thd, np.zeros(4), 1e6, 2e4)
    assert p[0] == pytest.approx(1e6 * 0.09)  # compression: above the atmosphere
    assert p[1] == pytest.approx(-1e6 * 0.0025)  # suction: below it
    assert p[2] == CLAMP  # -3.6 bar would be below the vapour pressure: clamped
    assert p[3] == 0.0
    # at the clamp the Thoma coefficient is exactly sigma_c = 0 (Eq. 14)
    assert thoma_coefficient(p[2], PATM, PV) == pytest.approx(0.0, abs=1e-15)
    assert np.all(thoma_coefficient(p, PATM, PV) >= 0)
    # the mirrored cylinder
    assert chamber_pressure_model(0.3, 0.0, 1e6, 0.0, compression_sign=-1) < 0


def test_fit_recovers_the_truth_with_cavitation():
    thd, thdd = _motion()
    p = chamber_pressure_model(thd, thdd, 1.0e6, 2.4e4)
    assert np.mean(p == CLAMP) > 0.1  # the clamp is exercised
    fit = fit_pressure_model(p, thd, thdd)
    assert fit.pressure_loss_coefficient == pytest.approx(1.0e6, rel=1e-10)
    assert fit.fluid_inertia == pytest.approx(2.4e4, rel=1e-10)
    assert fit.r2 == pytest.approx(1.0, abs=1e-12)
    assert np.array_equal(fit.cavitating, p == CLAMP)


@settings(max_examples=30, deadline=None)
@given(kp=st.floats(1e5, 5e6), ip=st.floats(0, 5e4), amp=st.floats(0.05, 0.8))
def test_fit_exact_on_noise_free_data(kp, ip, amp):
    thd, thdd = _motion(amp=amp)
    p = chamber_pressure_model(thd, thdd, kp, ip)
    fit = fit_pressure_model(p, thd, thdd)
    assert fit.pressure_loss_coefficient == pytest.approx(kp, rel=1e-8)
    assert fit.fluid_inertia == pytest.approx(ip, rel=1e-6, abs=1e-6 * kp)


def test_fit_with_sensor_noise_within_one_percent():
    # 1 kPa noise (0.2 % of a 5 bar rated output) on 2000 samples: K_p and I_p within 1 %
    thd, thdd = _motion()
    p = chamber_pressure_model(thd, thdd, 1.0e6, 2.4e4)
    noisy = p + np.random.default_rng(3).normal(0, 1000.0, p.size)
    fit = fit_pressure_model(noisy, thd, thdd)
    assert fit.pressure_loss_coefficient == pytest.approx(1.0e6, rel=0.01)
    assert fit.fluid_inertia == pytest.approx(2.4e4, rel=0.01)
    assert 0.99 < fit.r2 < 1.0


def test_fit_rejects_bad_input():
    thd, thdd = _motion(n=50)
    with pytest.raises(ValueError, match="non-finite"):
        fit_pressure_model(np.full(50, np.nan), thd, thdd)
    with pytest.raises(ValueError, match="shapes"):
        fit_pressure_model(np.zeros(49), thd, thdd)
    with pytest.raises(ValueError, match="cavitation"):
        fit_pressure_model(np.full(50, CLAMP), thd, thdd)
    with pytest.raises(ValueError, match="constant"):
        fit_pressure_model(np.full(50, 1e5), thd, thdd)


def test_pressure_force():
    assert pressure_force(2e5, np.pi * 0.05**2 / 4) == pytest.approx(2e5 * 1.9634954e-3)
    with pytest.raises(ValueError):
        pressure_force(1.0, 0.0)


def test_fit_is_bounded_at_zero_inertia_when_the_free_fit_is_negative():
    """A pressure from Eq. (13) with I_p < 0 (what a lagging, compliant chamber looks like to
    the fit): the free optimum is unphysical, so I_p is held at 0 and K_p is the
    least-squares optimum given I_p = 0 (the normal equation of K_p alone, on the samples off
    the cavitation branch), and the fit says it is bounded."""
    thd, thdd = _motion()
    p = chamber_pressure_model(thd, thdd, 1.0e6, -3.0e4)
    fit = fit_pressure_model(p, thd, thdd)
    assert fit.bounded and fit.fluid_inertia == 0.0
    x = thd * np.abs(thd)
    on = ~fit.cavitating
    kp = float(x[on] @ p[on] / (x[on] @ x[on]))
    assert fit.pressure_loss_coefficient == pytest.approx(kp, rel=1e-10)
    assert fit.r2 < 1.0
    free = fit_pressure_model(chamber_pressure_model(thd, thdd, 1.0e6, 2.4e4), thd, thdd)
    assert not free.bounded
