"""Still-water level rules: each removes what it says, and the level is reported."""

import numpy as np
import pytest
import xarray as xr

from flumekit.waves.still_water import remove_still_water


@pytest.fixture
def record():
    t = np.arange(0, 60, 0.01)
    wave = np.where(t > 20, 0.02 * np.sin(2 * np.pi * t / 1.5), 0.0)  # still before 20 s
    level = np.array([0.1, 0.09])
    return xr.DataArray(level[:, None] + wave, dims=("probe", "time"),
                        coords={"probe": ["A", "B"], "time": t}), level


def test_still_segment_recovers_the_level_exactly(record):
    elev, level = record
    eta, removed = remove_still_water(elev, [0.0, 19.0])
    np.testing.assert_allclose(removed, level, rtol=1e-12)
    assert np.abs(eta.sel(time=slice(0, 19))).max() < 1e-12
    assert removed.attrs["rule"] == "mean of the still segment 0-19 s"


def test_given_levels_mean_and_none(record):
    elev, level = record
    np.testing.assert_allclose(remove_still_water(elev, {"A": 0.1, "B": 0.09})[1], level)
    np.testing.assert_allclose(remove_still_water(elev, 0.1)[1], [0.1, 0.1])
    # the record mean differs from the level by the mean of the waves (not whole periods here)
    mean = remove_still_water(elev, "mean")[1].values
    np.testing.assert_allclose(mean, level + float(elev[0].mean() - 0.1), rtol=1e-12)
    np.testing.assert_array_equal(remove_still_water(elev, "none")[0], elev)
    with pytest.raises(ValueError, match="fewer than two samples"):
        remove_still_water(elev, [100.0, 200.0])
    with pytest.raises(ValueError, match=r"probe\(s\) \['B'\]"):
        remove_still_water(elev, {"A": 0.1})
