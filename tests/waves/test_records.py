"""Probe records from numpy/pandas/xarray; a regular record is recognised by ``separate``."""

from pathlib import Path

import numpy as np
import pandas as pd
import pytest
import xarray as xr

from flumekit.synth.waves import irregular_wave_field, regular_wave_field
from flumekit.waves import (
    REGULAR_FRACTION,
    harmonic_energy_fraction,
    probe_record,
    probe_spacing,
    refine_frequency,
    separate,
)

H = 0.825
FS = 25.0
ROOT = Path(__file__).resolve().parents[2]
# shared/ beside the clone (CI), or beside the folder of work trees (a developer's worktree)
WAVELABX = next((p for p in (r / "shared" / "data" / "wavelabx" / "wavedata.csv"
                             for r in ROOT.parents[:2]) if p.exists()), ROOT / "absent")


def _layout(period):
    x12, x23 = probe_spacing(period, H)
    return np.array([-6.0, -6.0 + x12, -6.0 + x12 + x23])


def _steep_regular(period=2.5, height=0.2, kr=0.1, n_periods=48.3):
    # a non-whole number of periods, as in a real record
    t = 300 * period + np.arange(int(n_periods * period * FS)) / FS
    field = regular_wave_field(t, _layout(period), period=period, height=height, depth=H,
                               reflection=kr, second_order=True)
    eta = field.eta.values + np.random.default_rng(3).normal(0.0, 5e-4, field.eta.shape)
    return eta, field


def test_probe_record_from_numpy_pandas_and_xarray_is_one_record():
    eta = np.random.default_rng(0).normal(size=(3, 50))
    x = [0.0, 0.6, 0.9]
    a = probe_record(eta, x=x, sampling_rate=10.0)
    assert a.dims == ("probe", "time") and a.attrs["units"] == "m"
    np.testing.assert_array_equal(a.time.values, np.arange(50) / 10.0)
    b = probe_record(pd.DataFrame(eta.T, columns=["G1", "G2", "G3"]), x=x, sampling_rate=10.0)
    assert b.probe.values.tolist() == ["G1", "G2", "G3"]
    np.testing.assert_array_equal(a.values, b.values)
    # a time index [s] is used as the time axis; the row counter is not
    c = probe_record(pd.DataFrame(eta.T, index=np.arange(50) / 10.0 + 5.0), x=x)
    assert float(c.time[0]) == 5.0
    with pytest.raises(ValueError, match="sampling_rate"):
        probe_record(pd.DataFrame(eta.T), x=x)
    d = probe_record(a.transpose("time", "probe").drop_vars("x"), x=[1.0, 2.0, 3.0])
    np.testing.assert_array_equal(d.x.values, [1.0, 2.0, 3.0])
    with pytest.raises(ValueError, match="3 probes"):
        probe_record(eta, x=[0.0, 1.0], sampling_rate=10.0)
    with pytest.raises(ValueError, match="positions x"):
        probe_record(eta, sampling_rate=10.0)
    with pytest.raises(ValueError, match="two-dimensional"):
        probe_record(eta[0], x=[0.0], sampling_rate=10.0)


def test_steep_regular_record_is_separated_as_regular_without_an_option():
    period, kr = 2.5, 0.1
    eta, field = _steep_regular(period, kr=kr)
    x = field.x.values
    auto = separate(eta, H, x=x, sampling_rate=FS)
    assert auto.attrs["regular"] == 1 and auto.attrs["bound_harmonics"] == 1
    assert auto.attrs["regular_detection"].startswith("regular")
    # truth of the virtual flume: first-harmonic Kr = 0.1 (±0.01 as the regular-wave tests)
    assert abs(float(auto.reflection_coefficient) - kr) < 0.01
    assert float(auto.incident_amplitude) == pytest.approx(field.attrs["incident_amplitude"],
                                                           rel=0.01)
    # the refined fundamental, not the peak bin 0.3976 Hz of this 48.3-period record
    assert auto.attrs["fundamental_frequency"] == pytest.approx(1 / period, rel=1e-4)
    # the bin-wise free-wave fit (what the default used to do) is far outside ±0.01 (0.149)
    free = separate(eta, H, x=x, sampling_rate=FS, regular=False)
    assert free.attrs["regular_detection"] == "given"
    assert float(free.reflection_coefficient) - kr > 0.03


def test_irregular_sea_stays_irregular():
    t = np.arange(int(600 * FS)) / FS
    field = irregular_wave_field(t, _layout(2.5), hm0=0.1, peak_period=2.5, depth=H,
                                 gamma=7.0, reflection=0.3, rng=1)
    f1, share = harmonic_energy_fraction(field.eta.values, 1 / FS)
    assert share < 0.5 * REGULAR_FRACTION  # a narrow JONSWAP (γ = 7) is far from the threshold
    auto = separate(field.eta.values, H, x=field.x.values, sampling_rate=FS)
    assert auto.attrs["regular"] == 0 and auto.attrs["regular_detection"].startswith("irregular")
    ref = separate(field.eta.values, H, x=field.x.values, sampling_rate=FS, regular=False)
    assert float(auto.reflection_coefficient) == float(ref.reflection_coefficient)
    assert abs(float(auto.reflection_coefficient) - 0.3) < 0.03


def test_harmonic_fraction_of_a_pure_tone_and_white_noise():
    t = np.arange(2000) / FS
    f1, share = harmonic_energy_fraction(np.cos(2 * np.pi * 0.4 * t), 1 / FS)
    assert f1 == pytest.approx(0.4) and share == pytest.approx(1.0)
    _, share = harmonic_energy_fraction(np.random.default_rng(0).normal(size=(3, 4000)), 1 / FS)
    assert share < 0.1


@pytest.mark.parametrize(("n", "f", "offset"), [(3001, 0.31234567, 5.0), (40, 1.7, 0.0),
                                                 (15000, 1 / 3.5, 2e3)])
def test_refine_frequency_is_exact_for_a_pure_tone(n, f, offset):
    # a non-whole number of periods, the peak bin off the frequency, one or three probes and a
    # large mean (removed): the nonlinear least-squares frequency is the tone's to 1e-9
    t = np.arange(n) / FS
    phase = np.array([[0.3], [2.0], [-1.1]])
    v = offset + np.cos(2 * np.pi * f * t + phase) * np.array([[1.0], [0.7], [0.2]])
    freq = np.fft.rfftfreq(n, 1 / FS)
    for rows in (v[:1], v):
        f_bin = freq[np.argmax(np.abs(np.fft.rfft(rows - rows.mean(axis=1, keepdims=True),
                                                  axis=1)).sum(axis=0))]
        assert abs(f_bin - f) > 0.05 / (n / FS)  # the peak bin is off
        assert refine_frequency(rows, 1 / FS, f_bin) == pytest.approx(f, rel=1e-9)


@pytest.mark.skipif(not WAVELABX.exists(), reason="../shared/data/wavelabx absent")
def test_wavelabx_record_from_pandas_gets_the_first_harmonic_kr():
    # the real WaveLabX record (regular waves, T ≈ 1.33 s, h = 0.25 m, gauges at 0/0.6/0.9 m)
    data = pd.read_csv(WAVELABX)
    auto = separate(data, 0.25, x=[0.0, 0.6, 0.9], sampling_rate=100.0)
    explicit = separate(data, 0.25, x=[0.0, 0.6, 0.9], sampling_rate=100.0, regular=True)
    assert auto.attrs["regular"] == 1
    assert auto.attrs["fundamental_frequency"] == pytest.approx(0.75, rel=1e-4)  # T = 1.333 s
    # the first-harmonic Kr does not depend on how harmonics n ≥ 2 are fitted
    assert float(auto.reflection_coefficient) == pytest.approx(
        float(explicit.reflection_coefficient), rel=1e-9)
    free = separate(data, 0.25, x=[0.0, 0.6, 0.9], sampling_rate=100.0, regular=False)
    assert float(free.reflection_coefficient) > 3 * float(auto.reflection_coefficient)
    # the same record as a DataArray gives the same numbers
    da = xr.DataArray(data.to_numpy().T, dims=("probe", "time"),
                      coords={"x": ("probe", [0.0, 0.6, 0.9]),
                              "time": np.arange(len(data)) / 100.0})
    assert float(separate(da, 0.25).reflection_coefficient) == float(auto.reflection_coefficient)


def test_analyse_run_takes_an_array_with_positions_and_rate():
    from flumekit.waves import analyse_run

    period = 2.5
    t = np.arange(int(200 * FS)) / FS  # from the start of generation: ramp-up included
    field = regular_wave_field(t, _layout(period), period=period, height=0.15, depth=H,
                               reflection=0.2, second_order=False)
    da = xr.DataArray(field.eta.values, dims=("probe", "time"),
                      coords={"probe": ["0", "1", "2"], "x": ("probe", field.x.values),
                              "time": t})
    ref = analyse_run(da, H, period)
    arr = analyse_run(field.eta.values, H, period, x=field.x.values, sampling_rate=FS)
    assert float(arr.reflection_coefficient) == float(ref.reflection_coefficient)
    assert abs(float(arr.reflection_coefficient) - 0.2) < 0.01  # the virtual flume's truth
