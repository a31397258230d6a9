"""Probe calibration against the virtual flume's true gains and offsets."""

import warnings

import numpy as np
import pytest
import xarray as xr

from flumekit.io.instruments import read_calibration
from flumekit.synth.campaign import Truth, _probe_gains, _write_calibration
from flumekit.waves import calibration

NAMES = ("WP1", "WP2", "WP3", "WP4")


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_recovers_true_gain_and_offset_within_0p1_percent(tmp_path, seed):
    rng = np.random.default_rng(seed)
    a, b = _probe_gains(NAMES, rng)
    _write_calibration(tmp_path, NAMES, a, b, 25.0, Truth(), rng)  # 0.5 mm noise, 30 s per level
    cal = calibration.fit(read_calibration(tmp_path / "calibration" / "probes.csv", NAMES))
    np.testing.assert_allclose(cal.gain, 1 / b, rtol=1e-3)
    np.testing.assert_allclose(cal.offset, -a / b, rtol=1e-3)
    assert np.all(cal.calibration_r2 > 0.999)
    # residual RMS is the noise level
    np.testing.assert_allclose(cal.calibration_rms_residual, 0.5e-3, rtol=0.1)


def _cal(levels, volts):
    return xr.Dataset({"calibration_voltage": (("sample", "probe"), volts)},
                      coords={"level": ("sample", levels), "probe": ["P"]})


def test_second_order_fit_is_exact_for_a_quadratic_sensor():
    v = np.linspace(1, 3, 5)
    levels = 0.02 - 0.05 * v + 0.01 * v**2
    cal = calibration.fit(_cal(levels, v[:, None]), order=2)
    np.testing.assert_allclose(cal.calibration_coefficients.sel(probe="P"), [0.02, -0.05, 0.01],
                               atol=1e-12)


def test_poor_fit_warns():
    rng = np.random.default_rng(0)
    levels = np.repeat([-0.1, -0.05, 0, 0.05, 0.1], 10)
    volts = 2 + 10 * levels + rng.normal(0, 0.2, levels.size)
    with pytest.warns(calibration.CalibrationWarning, match=r"R² = 0\.9"):
        calibration.fit(_cal(levels, volts[:, None]))


def test_order_needs_enough_levels():
    with pytest.raises(ValueError, match="at least 3 distinct levels"):
        calibration.fit(_cal(np.array([0.0, 0.1]), np.array([[1.0], [2.0]])), order=2)


def test_non_monotonic_polynomial_over_the_recorded_range_warns():
    v = np.linspace(0, 4, 9)
    levels = -(v - 2.0) ** 2 / 10  # peak at 2 V
    cal = calibration.fit(_cal(levels, v[:, None]), order=2)
    volts = xr.DataArray(np.array([[1.0, 2.5, 3.0]]), dims=("probe", "time"),
                         coords={"probe": ["P"], "time": [0.0, 0.04, 0.08]})
    with pytest.warns(calibration.CalibrationWarning, match="not monotonic"):
        calibration.apply(volts, cal)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        calibration.apply(volts.where(volts > 2.1, 2.2), cal)  # the falling branch only
