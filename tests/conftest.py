"""Fixtures that tests of several folders share: the default campaign and one regular run."""

from __future__ import annotations

import shutil
from importlib import resources

import numpy as np
import pytest
import xarray as xr

#: still-water depth of the default campaign's flume [m]
DEPTH = 0.825


@pytest.fixture(scope="session")
def campaign(tmp_path_factory):
    """The default campaign (``flumekit/data/default_campaign.toml``), loaded from a copy."""
    from flumekit.campaign import load_campaign

    root = tmp_path_factory.mktemp("campaign")
    src = resources.files("flumekit.data").joinpath("default_campaign.toml")
    with resources.as_file(src) as path:
        shutil.copy(path, root / "campaign.toml")
    return load_campaign(root)


@pytest.fixture(scope="session")
def regular_waves():
    """The waves analysis of a 2 s, 0.15 m regular wave of the virtual flume: four probes, the
    first three spaced for the separation, 80 periods at 25 Hz."""
    from flumekit.synth.waves import regular_wave_field
    from flumekit.waves import analyse_run, probe_spacing

    period = 2.0
    x12, x23 = probe_spacing(period, DEPTH)
    x = np.array([-7.0, -7.0 + x12, -7.0 + x12 + x23, -1.0])
    t = np.arange(int(80 * period * 25)) / 25.0
    f = regular_wave_field(t, x, period=period, height=0.15, depth=DEPTH)
    da = xr.DataArray(f.eta.values, dims=("probe", "time"),
                      coords={"probe": ["WP1", "WP2", "WP3", "WP4"], "x": ("probe", x),
                              "time": t})
    return analyse_run(da, DEPTH, period, x_ref=0.0, separation_probes=["WP1", "WP2", "WP3"])
