"""Flap figures: built from processed datasets, the plotted data are the dataset's."""

import numpy as np
import pytest
import xarray as xr
from matplotlib.figure import Figure

from flumekit.figures import flap as figs
from flumekit.flap.analysis import analyse_run
from flumekit.waves.theory import stokes2_coefficient, wavenumber


def device(c):
    """What analyse_run takes of a campaign."""
    return dict(flap=c.flap, pto=c.pto, encoder=c.encoder, depth=c.flume.water_depth)


@pytest.fixture(scope="module")
def runs(record, campaign):
    out = []
    for period, height in ((2.0, 0.15), (3.5, 0.15), (2.0, 0.25), (3.5, 0.25)):
        t, eta, truth = record(period, height, n_waves=40)
        ds = analyse_run(t, truth.encoder_counts.values, truth.chamber_pressure.values,
                         **device(campaign), period=period, incident_height=height)
        out.append((ds.assign_coords(wave_height=height), xr.DataArray(eta, coords={"time": t})))
    return out


def test_time_series_figures(runs):
    ds, eta = runs[-1]
    fig = figs.figure_5b(ds)
    assert isinstance(fig, Figure)
    fig = figs.figure_6bcd(ds, start=20, n_waves=5)
    line = fig.axes[0].lines[0]
    # the plotted theta is the dataset's, normalised by the amplitude scale
    scale = 0.5 * np.ptp(ds.theta_phase_mean.values)
    assert np.max(np.abs(line.get_ydata())) == pytest.approx(np.max(np.abs(ds.theta.values[
        np.isin(ds.time.values / float(ds.measured_period), line.get_xdata())])) / scale)
    with pytest.raises(ValueError, match="outside the record"):
        figs.figure_6bcd(ds, start=500)
    fig = figs.figure_7([runs[1][0], runs[3][0]])
    assert len(fig.axes) == 2 and "R²" in fig.axes[0].get_title(loc="left")
    assert fig.axes[0].get_title(loc="left") != fig.axes[1].get_title(loc="left")


def test_summary_figures_group_by_height(runs):
    fig = figs.figure_8([r[0] for r in runs])
    lines = fig.axes[0].lines
    assert len(lines) == 2  # two heights
    assert lines[0].get_xdata().tolist() == [2.0, 3.5]
    assert lines[0].get_ydata()[1] == pytest.approx(float(runs[1][0].torque_amplitude))
    fig = figs.figure_9([r[0] for r in runs])
    assert len(fig.axes) == 2
    assert fig.axes[1].lines[1].get_ydata()[1] == pytest.approx(float(runs[3][0].capture_factor))


def test_figure_10(runs):
    ds, eta = runs[-1]
    fig = figs.figure_10(ds, eta=eta)
    assert len(fig.axes) == 4
    # panel (a): the phase-averaged wave crest / H is (a + B k a^2)/H of the fixture's
    # second-order wave (0.73 at kh = 0.55), within 1 % (100 phase points per cycle)
    k = float(wavenumber(2 * np.pi / 3.5, 0.825))
    crest = (0.125 + float(stokes2_coefficient(k, 0.825)) * k * 0.125**2) / 0.25
    assert np.max(fig.axes[0].lines[0].get_ydata()) == pytest.approx(crest, rel=0.01)
    # panel (b) starts at theta = 0 (zero up-crossing)
    assert abs(fig.axes[1].lines[0].get_ydata()[0]) < 0.01
    fig = figs.figure_10(ds)  # without eta: no wave panel, the others lettered from (a)
    assert [ax.get_title(loc="left").split()[0] for ax in fig.axes] == ["(a)", "(b)", "(c)"]
    with pytest.raises(ValueError, match="lacks"):
        figs.figure_10(ds.drop_vars("theta_phase_mean"))
