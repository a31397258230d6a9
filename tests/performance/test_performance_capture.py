"""Capture width, capture width ratio and motion statistics against hand computations."""

import numpy as np
import pytest

from flumekit.performance import capture_width, capture_width_ratio, motion_statistics
from flumekit.waves.theory import G, group_velocity


def test_capture_width_and_ratio_by_hand():
    # J of a regular wave by hand: H = 0.1 m, T = 2 s, h = 0.5 m, rho = 1000
    cg = float(group_velocity(2.0, 0.5))
    j = 1000.0 * G * 0.1**2 / 8 * cg
    p = 3.7
    assert float(capture_width(p, j)) == pytest.approx(p / j, rel=1e-15)
    assert float(capture_width_ratio(p, j, 1.31)) == pytest.approx(p / j / 1.31, rel=1e-15)
    # arrays broadcast, one value per run
    np.testing.assert_allclose(capture_width_ratio([1.0, 2.0], [4.0, 8.0], 0.5), [0.5, 0.5])


@pytest.mark.parametrize("flux, width", [(0.0, 1.0), (-1.0, 1.0), (np.nan, 1.0), (1.0, 0.0)])
def test_no_flux_or_width_is_an_error(flux, width):
    with pytest.raises(ValueError):
        capture_width_ratio(1.0, flux, width)


def test_motion_statistics_of_a_sum_of_sines():
    # two sines on an offset: m0 = sum a^2/2 exactly over whole periods
    fs, dur = 100.0, 400.0
    t = np.arange(int(fs * dur)) / fs
    a1, a2 = 0.10, 0.02
    x = 0.05 + a1 * np.cos(2 * np.pi * 0.25 * t) + a2 * np.cos(2 * np.pi * 0.75 * t)
    ds = motion_statistics(x, fs, name="theta")
    m0 = (a1**2 + a2**2) / 2
    assert float(ds.theta_mean) == pytest.approx(0.05, abs=1e-9)
    assert float(ds.theta_rms) == pytest.approx(np.sqrt(m0), rel=1e-6)
    assert float(ds.theta_significant_amplitude) == pytest.approx(2 * np.sqrt(m0), rel=1e-6)
    # the small third harmonic rides on the slow wave: one up-crossing per slow period, its
    # crests and troughs on the slow wave's, every height 2 (a1 + a2)
    assert int(ds.theta_cycles) == 99
    assert float(ds.theta_maximum_amplitude) == pytest.approx(a1 + a2, rel=1e-3)
    assert float(ds.theta_significant_amplitude_zero_crossing) == pytest.approx(a1 + a2,
                                                                              rel=1e-3)
    assert ds.theta_rms.attrs["units"] == "rad"


def test_motion_statistics_refuses_what_it_cannot_measure():
    with pytest.raises(ValueError, match="zero up-crossing"):
        motion_statistics(np.linspace(0, 1, 1000), 100.0)
    with pytest.raises(ValueError, match="finite"):
        motion_statistics(np.r_[np.sin(np.arange(1000) / 10), np.nan], 100.0)
    with pytest.raises(ValueError, match="sampling_rate"):
        motion_statistics(np.sin(np.arange(1000) / 10))
