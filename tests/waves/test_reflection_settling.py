"""The analysis window waits for the separated reflection to settle (waves.steady)."""

import numpy as np
import pytest
import xarray as xr

from flumekit.synth.waves import Beach, regular_wave_field
from flumekit.waves import SeparationWarning, analyse_run, probe_spacing, wavenumber
from flumekit.waves.steady import reflection_settling

H, FS = 0.825, 25.0


def beach_run(period, height, n_periods=120, seed=1):
    """Three probes 4 m before a flap (Kr 0.14) with the flume's beach wave behind it."""
    x12, x23 = probe_spacing(period, H)
    x = np.array([-4.0, -4.0 + x12, -4.0 + x12 + x23])
    t = np.arange(int(n_periods * period * FS)) / FS
    field = regular_wave_field(t, x, period=period, height=height, depth=H, reflection=0.14,
                               reflection_phase=0.6, beach=Beach(transmission=0.9))
    eta = field.eta.values + np.random.default_rng(seed).normal(0, 5e-4, field.eta.shape)
    da = xr.DataArray(eta, dims=("probe", "time"),
                      coords={"probe": ["a", "b", "c"], "x": ("probe", x), "time": t})
    return da, field.attrs["reflection_coefficient"]


@pytest.mark.parametrize("period, height", [(1.5, 0.1), (2.0, 0.15), (3.5, 0.25)])
def test_beach_wave_settles_before_the_window_opens(period, height):
    # the beach's wave (K_b K_t² = 6.5 % of the incident amplitude) reaches the probes after
    # the crests have settled; the truth is the steady reflection with it
    da, kr = beach_run(period, height)
    ds = analyse_run(da, H, period)
    # acceptance: within 0.0005 of the steady Kr (0.5 mm probe noise)
    assert abs(float(ds.reflection_coefficient) - kr) < 5e-4
    assert float(ds.steady_start) > float(ds.crest_steady_start)
    assert float(ds.reflection_drift) > float(ds.reflection_drift.attrs["tolerance"])
    assert int(ds.steady_cycles) >= 40


def test_window_opened_at_the_crests_alone_is_biased_there():
    # what the test guards against: the paper's crest criterion alone opens the window while
    # the beach's wave still ramps up, and Kr is 0.005 low at T = 1.5 s
    da, kr = beach_run(1.5, 0.1)
    ds = analyse_run(da, H, 1.5, reflection_tolerance=0.0)
    assert float(ds.reflection_coefficient) - kr < -0.003
    assert float(ds.steady_start) == pytest.approx(float(ds.crest_steady_start), abs=0.05)


def _two_waves(r, t, x, period=2.0, a=0.05, depth=0.8):
    k = float(wavenumber(2 * np.pi / period, depth))
    w = 2 * np.pi / period
    return a * np.cos(w * t - k * x[:, None]) + a * r * np.cos(w * t + k * x[:, None] + 0.3)


def test_settling_finds_a_step_of_the_reflection_and_its_value():
    t = np.arange(0.0, 150.0, 0.04)
    x = np.array([-3.0, -2.6, -2.0])
    r = np.where(t < 60.0, 0.10, 0.16)
    s = reflection_settling(_two_waves(r, t, x), t, x, 2.0, 0.8, 0.0, 150.0)
    assert 60.0 <= s.start <= 66.0
    assert abs(s.reflection) == pytest.approx(0.16, abs=1e-6)
    assert s.drift == pytest.approx(0.06, abs=1e-3)
    assert s.end == pytest.approx(150.0, abs=6.0)


def test_settling_keeps_a_steady_noisy_window_whole():
    # probe noise of 1 mm on a 5 cm wave: no block is cut (4 sigma of the blocks' own scatter)
    t = np.arange(0.0, 240.0, 0.04)
    x = np.array([-3.0, -2.6, -2.0])
    rng = np.random.default_rng(3)
    eta = _two_waves(np.full(t.size, 0.2), t, x) + rng.normal(0, 1e-3, (3, t.size))
    s = reflection_settling(eta, t, x, 2.0, 0.8, 0.0, 240.0)
    assert s.start == 0.0
    assert s.end == pytest.approx(240.0)
    assert s.drift == 0.0
    assert abs(s.reflection) == pytest.approx(0.2, abs=2e-3)


def test_reflection_that_never_settles_is_a_warning_naming_the_drift():
    # the reflection grows all along the record: no long settled run, the crests' window is
    # kept and the warning says by how much Kr changes
    t = np.arange(0.0, 100.0, 0.04)
    x = np.array([-3.0, -2.6, -2.0])
    r = 0.05 + 0.003 * t / 2.0  # +0.003 per period
    da = xr.DataArray(_two_waves(r, t, x, depth=H), dims=("probe", "time"),
                      coords={"probe": ["a", "b", "c"], "x": ("probe", x), "time": t})
    with pytest.warns(SeparationWarning, match=r"reflection does not settle.*changes by 0\.\d+"):
        ds = analyse_run(da, H, 2.0)
    assert float(ds.steady_start) == pytest.approx(float(ds.crest_steady_start), abs=0.05)
