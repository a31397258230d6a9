"""The QC figure of a run draws every channel with its flags and passes the figure checks."""

import numpy as np
import xarray as xr

from flumekit.figures.check import assert_passes
from flumekit.figures.qc import figure_qc
from flumekit.qc.record import Thresholds, qc_dataset


def test_qc_figure_marks_the_failed_samples():
    rng = np.random.default_rng(0)
    t = np.arange(2500) / 25.0
    v = 2.5 + 0.8 * np.sin(2 * np.pi * t / 2.0)[None] + 0.005 * rng.standard_normal((2, t.size))
    v[0, 700] += 0.6
    raw = xr.Dataset({"probe_voltage": (("probe", "time"), v, {"units": "V",
                                                               "long_name": "voltage"})},
                     coords={"probe": ["WP1", "WP2"], "time": t}, attrs={"sampling_rate": 25.0})
    probes = qc_dataset(raw, "probe_voltage", Thresholds(), channel_dim="probe")
    assert int(probes["probe_voltage_qc"].sel(probe="WP1")[700]) == 4
    fig = figure_qc(probes)
    assert_passes(fig, "qc figure")
    titles = [ax.get_title(loc="left") for ax in fig.axes]
    assert titles[0].startswith("WP1") and "1 fail" in titles[0]
    assert "0 fail" in titles[1]
