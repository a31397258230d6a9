"""The virtual flume's beach reflection against its truth and the pipeline's separation."""

import numpy as np
import pytest
import xarray as xr

from flumekit.synth.campaign import Truth, probe_positions
from flumekit.synth.waves import Beach, regular_wave_field
from flumekit.waves import analyse_run, group_velocity

H = 0.825
FS = 25.0


def _run(period, height, *, reflection, beach, noise=5e-4, seed=0):
    """A virtual run's probe records as the campaign lays them out (Table 1 spacings)."""
    xp = probe_positions(period, H, Truth())
    travel = 32.7 / float(group_velocity(period, H))
    t = np.arange(int(np.ceil(travel + 100 * period) * FS)) / FS
    x = np.array(list(xp.values()))
    field = regular_wave_field(t, x, period=period, height=height, depth=H,
                               reflection=reflection, reflection_phase=0.6, beach=beach)
    eta = field.eta.values + np.random.default_rng(seed).normal(0, noise, field.eta.shape)
    da = xr.DataArray(eta, dims=("probe", "time"),
                      coords={"probe": list(xp), "x": ("probe", x), "time": t})
    return da, field


@pytest.mark.parametrize("period, height", [(2.0, 0.15), (3.5, 0.25), (4.0, 0.3)])
def test_waves_only_run_measures_the_beach_reflection(period, height):
    # Brito et al. 2020, §2.3: without the flap the beach reflects about 8 %. A run without
    # the flap (nothing reflects at x = 0, nothing stands between the probes and the beach),
    # analysed as the pipeline's waves stage does, gives Kr = 0.08 within ±0.003 (0.5 mm probe
    # noise; the separation's own acceptance is ±0.005)
    da, field = _run(period, height, reflection=0.0, beach=Beach())
    assert field.attrs["reflection_coefficient"] == pytest.approx(0.08, abs=1e-12)
    ds = analyse_run(da, H, period, 0.0, separation_probes=["WP1", "WP2", "WP3"])
    assert float(ds.reflection_coefficient) == pytest.approx(0.08, abs=0.003)
    assert float(ds.incident_height) == pytest.approx(height, rel=0.005)
    assert np.all(field.eta_reflected.values == 0)


def test_with_the_flap_the_separation_measures_flap_and_beach_together():
    # what returns towards the wavemaker is the flap's reflection plus the beach's wave that
    # passed the flap twice: the truth's reflection_coefficient is their sum at x = 0
    beach = Beach(transmission=0.9, phase=0.3)
    da, field = _run(3.5, 0.25, reflection=0.2, beach=beach)
    a = field.attrs
    assert a["flap_reflection_coefficient"] == 0.2
    r_b = 0.08 * 0.9**2
    assert abs(a["reflection_coefficient"] - 0.2) <= r_b + 1e-12
    assert abs(a["reflection_coefficient"] - 0.2) > 0.005  # the beach term matters here
    ds = analyse_run(da, H, 3.5, 0.0, separation_probes=["WP1", "WP2", "WP3"])
    assert float(ds.reflection_coefficient) == pytest.approx(a["reflection_coefficient"],
                                                             abs=0.005)


def test_beach_wave_truth_component():
    # the beach's wave: first harmonic K_b K_t² a1, travelling towards -x with its own k,
    # arriving after the path wavemaker -> beach -> x with the group velocity
    T = 3.0
    beach = Beach(reflection=0.08, transmission=0.8, x=24.05, phase=0.4)
    cg = float(group_velocity(T, H))
    t = np.arange(0, 400 * T, 1 / FS)
    x = np.array([-4.0, -3.0])
    ds = regular_wave_field(t, x, period=T, height=0.2, depth=H, reflection=0.2, beach=beach)
    eb = ds.eta_beach.values
    arrival = (2 * 24.05 + 32.7 - x) / cg
    for i in range(2):
        assert np.all(eb[i][t <= arrival[i]] == 0) and np.any(eb[i][t > arrival[i] + T] != 0)
    steady = slice(-int(round(20 * T * FS)), None)  # the last 20 periods, steady
    z = 2 * np.mean(eb[:, steady] * np.exp(-2j * np.pi * t[steady] / T), axis=1)
    a1 = ds.attrs["incident_amplitude"]
    np.testing.assert_allclose(np.abs(z), 0.08 * 0.8**2 * a1, rtol=1e-6)
    kb = ds.attrs["beach_wave_number"]
    assert np.angle(z[1] / z[0]) == pytest.approx(kb * 1.0, abs=1e-9)
    np.testing.assert_array_equal(ds.eta.values,
                                  ds.eta_incident + ds.eta_reflected + ds.eta_beach)
    # off: no beach wave, the reflector's coefficient alone
    off = regular_wave_field(t[:10], x, period=T, height=0.2, depth=H, reflection=0.2)
    assert np.all(off.eta_beach.values == 0) and off.attrs["reflection_coefficient"] == 0.2
    with pytest.raises(ValueError, match="beyond the reflector"):
        regular_wave_field(t[:10], x, period=T, height=0.2, depth=H, beach=Beach(x=-1.0))
    with pytest.raises(ValueError, match="transmission"):
        Beach(transmission=1.5)
