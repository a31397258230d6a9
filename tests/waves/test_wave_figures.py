"""Figures 5a and 6a from a processed virtual-flume run."""

import matplotlib
import numpy as np
import pytest
import xarray as xr

from flumekit.figures.waves import figure_5a, figure_6a
from flumekit.synth.waves import regular_wave_field
from flumekit.waves import analyse_run, probe_spacing

matplotlib.use("Agg")
H = 0.825


@pytest.fixture(scope="module")
def waves(regular_waves):
    return regular_waves


def test_figure_5a_normalised_series_scale_line_and_steady_start(waves):
    import matplotlib.pyplot as plt

    before = plt.get_fignums()
    fig = figure_5a(waves)
    assert plt.get_fignums() == before  # no pyplot state
    ax = fig.axes[0]
    line, scale, steady, *analysis = ax.lines
    # probe closest to x_ref = 0 is WP4; η normalised by its amplitude scale
    y = line.get_ydata()
    expect = waves.eta.sel(probe="WP4").values / float(waves.amplitude_scale.sel(probe="WP4"))
    np.testing.assert_allclose(y, expect)
    assert np.median(np.abs(y[len(y) // 2:]).max()) == pytest.approx(1.0, abs=0.05)
    np.testing.assert_allclose(scale.get_ydata(), 1.0)
    # the paper's quasi-steady start (crests); the analysis window's, dashed, where later
    period = float(waves.measured_period)
    assert steady.get_xdata()[0] == pytest.approx(float(waves.crest_steady_start) / period)
    late = float(waves.steady_start) > float(waves.crest_steady_start) + 0.5 * period
    assert len(analysis) == int(late)
    if late:
        assert analysis[0].get_xdata()[0] == pytest.approx(float(waves.steady_start) / period)
    assert "$t/T$" in ax.get_xlabel() and "[-]" in ax.get_xlabel()


def test_figure_6a_five_waves_into_given_axes(waves):
    from matplotlib.figure import Figure

    fig = Figure()
    ax = fig.subplots()
    out = figure_6a(waves, probe="WP1", ax=ax)
    assert out is fig
    x = ax.lines[0].get_xdata()
    assert x.min() >= 65 and x.max() <= 70 and x.max() - x.min() > 4.9
    with pytest.raises(ValueError, match="outside the record"):
        figure_6a(waves, start=78.0)
    with pytest.raises(ValueError, match="probe"):
        figure_5a(waves, probe="WP9")


def test_figure_5a_marks_the_analysis_window_where_the_reflection_settles_later():
    from flumekit.synth.waves import Beach

    T = 1.5
    x12, x23 = probe_spacing(T, H)
    x = np.array([-4.0, -4.0 + x12, -4.0 + x12 + x23])
    t = np.arange(int(120 * T * 25)) / 25.0
    f = regular_wave_field(t, x, period=T, height=0.1, depth=H, reflection=0.14,
                           beach=Beach(transmission=0.9))
    da = xr.DataArray(f.eta.values, dims=("probe", "time"),
                      coords={"probe": ["a", "b", "c"], "x": ("probe", x), "time": t})
    w = analyse_run(da, H, T)
    ax = figure_5a(w).axes[0]
    crest, analysis = ax.lines[2:]
    period = float(w.measured_period)
    assert crest.get_xdata()[0] == pytest.approx(float(w.crest_steady_start) / period)
    assert analysis.get_xdata()[0] == pytest.approx(float(w.steady_start) / period)
    assert analysis.get_linestyle() == "--"
    assert analysis.get_xdata()[0] > crest.get_xdata()[0] + 5
