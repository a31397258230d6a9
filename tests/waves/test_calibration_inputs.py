"""Probe calibration from plain arrays and DataFrames, against known gains and offsets."""

import numpy as np
import pandas as pd
import pytest
import xarray as xr

from flumekit.waves import calibration

GAIN = np.array([0.048, 0.052])  # [m V-1]
OFFSET = np.array([-0.11, -0.09])  # [m]
LEVELS = np.array([-0.1, -0.05, 0.0, 0.05, 0.1])  # [m]
VOLTS = (LEVELS[:, None] - OFFSET) / GAIN  # (sample, probe) [V], exact


@pytest.mark.parametrize("voltage", [VOLTS, pd.DataFrame(VOLTS, columns=["WP1", "WP2"])])
def test_fit_takes_an_array_or_a_dataframe(voltage):
    cal = calibration.fit(voltage, levels=LEVELS)
    np.testing.assert_allclose(cal.gain.values, GAIN, rtol=1e-12)
    np.testing.assert_allclose(cal.offset.values, OFFSET, rtol=1e-12)
    np.testing.assert_allclose(cal.calibration_r2.values, 1.0, rtol=1e-12)
    ds = xr.Dataset({"calibration_voltage": (("sample", "probe"), VOLTS)},
                    coords={"level": ("sample", LEVELS), "probe": ["WP1", "WP2"]})
    np.testing.assert_allclose(cal.calibration_coefficients.values,
                               calibration.fit(ds).calibration_coefficients.values, rtol=1e-12)


def test_one_probe_as_a_vector_and_bad_input():
    cal = calibration.fit(VOLTS[:, 0], levels=LEVELS)
    assert cal.gain.shape == (1,) and cal.gain.values[0] == pytest.approx(GAIN[0], rel=1e-12)
    with pytest.raises(ValueError, match="levels"):
        calibration.fit(VOLTS)
    with pytest.raises(ValueError, match="one level per sample"):
        calibration.fit(VOLTS, levels=LEVELS[:3])
