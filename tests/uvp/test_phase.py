"""Per-run filter + phase average of the beams, against analytic beam signals."""

from __future__ import annotations

import numpy as np
import pytest
import xarray as xr

from flumekit.uvp.phase import fill_gaps, phase_average_beams, uniform

T = 3.5


def _beams(campaign, v_of_t, n_waves=20, positive="away_from_transducer", amplitude=None):
    u = campaign.uvp
    t = np.arange(int(n_waves * T * u.sampling_rate)) / u.sampling_rate
    out = {}
    for k, b in enumerate(u.beams):
        v = v_of_t(t[:, None], np.arange(u.n_channels)[None, :], k)
        data = {"beam_velocity": (("time", "channel"), v, {"positive": positive})}
        if amplitude is not None:
            data["amplitude"] = (("time", "channel"), amplitude(t[:, None], v.shape))
        out[b.name] = xr.Dataset(data, coords={
            "time": t, "distance": ("channel", u.start_channel
                                    + np.arange(u.n_channels) * u.channel_distance)})
    return out


def _wave(t, ch, k):
    """Steady two-harmonic along-beam velocity, a phase lag per channel and beam [m s-1]."""
    w = 2 * np.pi / T
    return 0.3 * np.cos(w * t - 0.002 * ch - k) + 0.1 * np.sin(2 * w * t - 0.003 * ch)


def _truth(phase, ch, k):
    return _wave(phase[None, :] * T, ch[:, None], k)


def test_phase_average_recovers_a_steady_signal(campaign):
    """2 Hz filter (gain 1 - 1e-6 at 0.57 Hz) + cubic interpolation: error < 1e-3 of the
    amplitude."""
    beams = _beams(campaign, _wave)
    ds = phase_average_beams(beams, campaign.uvp, 0.4, period=T, start=2 * T, n_cycles=15)
    ch = np.arange(campaign.uvp.n_channels)
    for k, name in enumerate(ds["beam"].values):
        err = ds["beam_velocity"].sel(beam=name).values - _truth(ds["phase"].values, ch, k)
        assert np.max(np.abs(err)) < 4e-4
    assert np.max(ds["beam_velocity_std"].values) < 1e-3  # steady: no cycle-to-cycle spread
    np.testing.assert_allclose(ds["z"].sel(beam="UP2"), 0.4)
    assert float(ds["phase_reference"]) == 2 * T and int(ds["n_cycles"]) == 15


def test_linear_interpolation_bias_and_cubic_fix(campaign):
    """Linear interpolation over random sub-sample offsets scales a harmonic by about
    1 - (ω dt)²/12 (signal.resample_cycles); the cubic kernel removes it."""
    fs = campaign.uvp.sampling_rate
    w = 2 * np.pi / T
    beams = _beams(campaign, lambda t, ch, k: np.cos(w * t) + 0 * ch)
    kw = dict(period=T, start=2 * T, n_cycles=15, cutoff=None)
    lin = phase_average_beams(beams, campaign.uvp, 0.4, interpolation="linear", **kw)
    cub = phase_average_beams(beams, campaign.uvp, 0.4, interpolation="cubic", **kw)
    truth = np.cos(2 * np.pi * lin["phase"].values)
    gain_lin = np.dot(lin["beam_velocity"].values[1, 0], truth) / np.dot(truth, truth)
    gain_cub = np.dot(cub["beam_velocity"].values[1, 0], truth) / np.dot(truth, truth)
    expected = (w / fs) ** 2 / 12
    assert 1 - gain_lin == pytest.approx(expected, rel=0.15)
    assert abs(1 - gain_cub) < 0.05 * expected


def test_sign_convention_is_honoured(campaign):
    a = phase_average_beams(_beams(campaign, _wave), campaign.uvp, 0.4, period=T, start=2 * T,
                            n_cycles=10)
    b = phase_average_beams(_beams(campaign, lambda t, c, k: -_wave(t, c, k),
                                   positive="towards_transducer"),
                            campaign.uvp, 0.4, period=T, start=2 * T, n_cycles=10)
    np.testing.assert_allclose(a["beam_velocity"], b["beam_velocity"], atol=1e-15)
    bad = _beams(campaign, _wave)
    del bad["UP1"]["beam_velocity"].attrs["positive"]
    with pytest.raises(ValueError, match="positive"):
        phase_average_beams(bad, campaign.uvp, 0.4, period=T, start=2 * T, n_cycles=10)


def test_bad_requests(campaign):
    beams = _beams(campaign, _wave)
    with pytest.raises(ValueError, match="does not cover"):
        phase_average_beams(beams, campaign.uvp, 0.4, period=T, start=2 * T, n_cycles=30)
    with pytest.raises(ValueError, match="missing"):
        phase_average_beams({"UP1": beams["UP1"]}, campaign.uvp, 0.4, period=T, start=2 * T)


def test_masks_no_echo_and_flap(campaign):
    """Samples without echo (every cycle at phases 0.4-0.6 for channels >= 300) and channels
    inside the moving flap are masked at those phases; elsewhere the average is unharmed."""
    w = 2 * np.pi / T

    def amp(t, shape):
        ph = (t / T) % 1.0
        lost = (ph > 0.4) & (ph < 0.6)
        a = np.full(shape, 400.0)
        a[:, 300:] = np.where(lost, 5.0, 400.0)
        return a

    def v(t, ch, k):
        ph = (t / T) % 1.0
        clean = _wave(t, ch, k)
        return np.where(((ph > 0.4) & (ph < 0.6)) & (ch >= 300), 0.7 * np.sin(997 * t), clean)

    theta_t = np.arange(0, 20 * T, 0.01)
    theta = xr.DataArray(0.15 * np.sin(w * theta_t), coords={"time": theta_t}, dims="time")
    beams = _beams(campaign, v, amplitude=amp)
    ds = phase_average_beams(beams, campaign.uvp, 0.6, period=T, start=2 * T, n_cycles=15,
                             min_amplitude=100, theta=theta, flap_thickness=0.17, margin=0.01)
    m = ds["beam_velocity"].sel(beam="UP1").values
    ph = ds["phase"].values
    assert np.all(np.isnan(m[300:, (ph > 0.41) & (ph < 0.59)]))
    ok = np.isfinite(m)
    ch = np.arange(campaign.uvp.n_channels)
    assert np.max(np.abs((m - _truth(ph, ch, 0))[ok])) < 2e-3  # gap filling keeps it clean
    # channels inside the flap (with margin) at a phase are masked; channels 5 cm in front of
    # the face at every phase are not (UP1 and UP3 lose channel >= 300 to the no-echo phases)
    th = 0.15 * np.sin(2 * np.pi * ph)
    for name in ("UP1", "UP2", "UP3"):
        m = ds["beam_velocity"].sel(beam=name).values
        x, z = ds["x"].sel(beam=name).values, ds["z"].sel(beam=name).values
        face = z[:, None] * np.tan(th[None, :]) - 0.085 / np.cos(th[None, :])
        inside = x[:, None] > face - 0.01
        assert inside.any() and np.all(np.isnan(m[inside]))
        far = np.broadcast_to((x[:, None] < face.min(axis=1, keepdims=True) - 0.05), m.shape)
        if name != "UP2":
            far = far & (ch < 300)[:, None]
        assert far.any() and np.all(np.isfinite(m[far]))


def test_uniform_and_fill_gaps():
    t = np.arange(100) / 11.6
    jitter = np.rint(t * 1e7) / 1e7  # 100 ns ticks
    g, v = uniform(jitter, np.sin(jitter))
    np.testing.assert_allclose(g, np.linspace(t[0], t[-1], 100))
    irregular = np.sort(np.random.default_rng(0).uniform(0, 10, 50))
    g, v = uniform(irregular, 3 * irregular + 1)  # linear: interpolation is exact
    np.testing.assert_allclose(v, 3 * g + 1, atol=1e-12)
    x = np.arange(10.0)[None, :] * np.array([[1.0], [2.0]])
    valid = np.ones_like(x, bool)
    valid[:, [0, 4, 5, 9]] = False
    f = fill_gaps(np.where(valid, x, 99.0), valid)
    np.testing.assert_allclose(f[:, 1:9], x[:, 1:9])  # interior gaps: exact for a line
    np.testing.assert_allclose(f[:, 0], x[:, 1])  # ends: held
    np.testing.assert_allclose(f[:, 9], x[:, 8])
