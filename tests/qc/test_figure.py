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
    assert "probe_voltage_raw" not in probes  # the figure reads the raw record itself
    fig = figure_qc(probes, probes_raw=raw)
    assert_passes(fig, "qc figure")
    titles = [ax.get_title(loc="left") for ax in fig.axes]
    assert titles[0].startswith("WP1") and "1 fail" in titles[0]
    assert "0 fail" in titles[1]
    # the raw record (grey) is drawn with the spike, the QC'd one (black) without it; the
    # grey line only where QC changed the record, joined to the samples either side
    grey, black = fig.axes[0].lines[:2]
    assert grey.get_ydata()[700] - black.get_ydata()[700] > 0.5
    assert np.flatnonzero(np.isfinite(grey.get_ydata())).tolist() == [699, 700, 701]
    assert [line.get_label() for line in fig.axes[1].lines] == ["after QC"]  # WP2: unchanged


def test_qc_figure_of_a_uvp_run_shows_the_beam_flags():
    t = np.arange(200) / 25.0
    raw = xr.Dataset({"probe_voltage": (("probe", "time"), 2.5 + np.sin(t)[None], {"units": "V"})},
                     coords={"probe": ["WP1"], "time": t}, attrs={"sampling_rate": 25.0})
    probes = qc_dataset(raw, "probe_voltage", Thresholds(), channel_dim="probe")
    # two beams of 10 channels, evaluated over profiles 20-79; beam UP2 fails 6 samples in
    # channel 7 and 3 samples of profile 50
    uvp = xr.Dataset(coords={"beam": ["UP1", "UP2"], "evaluated_span": ("bound", [0.8, 3.2])})
    for b in ("UP1", "UP2"):
        f = np.full((10, 100), 2, dtype=np.int8)
        f[:, 20:80] = 1
        if b == "UP2":
            f[7, 30:36] = 4
            f[:3, 50] = 4
        uvp[f"beam_velocity_qc_{b}"] = (("channel", f"time_{b}"), f)
        uvp = uvp.assign_coords({f"time_{b}": np.arange(100) / 25.0})
    fig = figure_qc(probes, uvp=uvp)
    assert_passes(fig, "qc figure of a UVP run")
    ax_time, ax_bin = fig.axes[-2:]
    assert "UP1 0" in ax_time.get_title(loc="left") and "UP2 9" in ax_time.get_title(loc="left")
    per_bin = ax_bin.lines[1].get_ydata()  # UP2: percent of each channel's 60 evaluated samples
    np.testing.assert_allclose(per_bin[7], 100 * 6 / 60)
    np.testing.assert_allclose(per_bin[0], 100 * 1 / 60)
    assert per_bin[8] == 0
    profile = ax_time.lines[1]  # UP2 over the evaluated profiles only
    assert profile.get_xdata().size == 60 and np.max(profile.get_ydata()) == 30.0
