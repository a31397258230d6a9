"""analyse_irregular_run on a synthetic irregular record whose absorbed power is known.

The flap follows θ(t) = θ0 + Σ Θ_i sin(ω_i t + φ_i) (twenty components over 0.3-0.8 Hz, whole
numbers of cycles over the analysed span) and the chamber pressure is that of a linear damper,
P_int Q = B θ̇², so that the mean absorbed power over the span is Σ ½ B ω_i² Θ_i² exactly and
the significant amplitude of θ is 2 sqrt(Σ Θ_i²/2).
"""

import numpy as np
import pytest

from flumekit.flap.analysis import analyse_irregular_run
from flumekit.flap.encoder import counts_from_wire, wire_length
from flumekit.flap.geometry import rod_kinematics

FS = 100.0
START, SPAN = 20.0, 600.0
B = 20.0  # linear damper [N m s]


@pytest.fixture(scope="module")
def irregular(campaign):
    rng = np.random.default_rng(11)
    k = np.sort(rng.choice(np.arange(180, 481), 20, replace=False))  # k / 600 s: 0.3-0.8 Hz
    omega = 2 * np.pi * k / SPAN
    amp = rng.uniform(0.005, 0.02, k.size)  # [rad]
    phase = rng.uniform(0, 2 * np.pi, k.size)
    t = np.arange(int((START + SPAN + 20.0) * FS)) / FS
    arg = omega[:, None] * t + phase[:, None]
    theta = 0.02 + (amp[:, None] * np.sin(arg)).sum(0)
    theta_dot = (amp[:, None] * omega[:, None] * np.cos(arg)).sum(0)
    enc, pto = campaign.encoder, campaign.pto
    counts = counts_from_wire(enc.L7 - wire_length(theta, enc.L5, enc.L7), enc.counts_per_metre)
    # rod extension per unit rotation dl/dtheta: the rod velocity at theta_dot = 1
    dl = rod_kinematics(theta, np.ones_like(theta), pto.bed_anchor, pto.flap_anchor).velocity
    # P_int Q = P_int (-A dl theta_dot) = B theta_dot^2
    pressure = -B * theta_dot / (pto.bore_area * dl)
    truth = {"mean_power": float(np.sum(0.5 * B * omega**2 * amp**2)),
             "theta_significant_amplitude": 2 * np.sqrt(np.sum(amp**2) / 2),
             "pressure": pressure}
    flux = 25.0  # [W m-1], given: the waves stage's J
    ds = analyse_irregular_run(t, counts, pressure, flap=campaign.flap, pto=pto, encoder=enc,
                               analysis_start=START, analysis_end=START + SPAN,
                               energy_flux=flux)
    return ds, truth, flux


def test_mean_power_of_a_linear_damper(irregular):
    ds, truth, _ = irregular
    # within 0.5 % (measured 0.03 %: encoder quantisation, the 4 Hz derivative filter)
    assert float(ds.mean_power) == pytest.approx(truth["mean_power"], rel=5e-3)
    assert np.abs(truth["pressure"]).max() < 9e4  # a damper the chamber could hold


def test_capture_width_and_ratio(irregular, campaign):
    ds, _, flux = irregular
    p = float(ds.mean_power)
    assert float(ds.capture_width) == pytest.approx(p / flux, rel=1e-12)
    assert float(ds.capture_width_ratio) == pytest.approx(p / flux / campaign.flap.width,
                                                           rel=1e-12)
    assert float(ds.energy_flux) == flux
    assert (float(ds.analysis_start), float(ds.analysis_end)) == (START, START + SPAN)


def test_motion_statistics(irregular):
    ds, truth, _ = irregular
    # within 0.5 % (the angle from quantised counts; measured 0.002 %)
    assert float(ds.theta_significant_amplitude) == pytest.approx(
        truth["theta_significant_amplitude"], rel=5e-3)
    assert float(ds.theta_mean) == pytest.approx(0.02, abs=2e-4)
    # a broad spectrum: zero-crossing H1/3 / 2 below and Hmax / 2 above the spectral value
    sig = float(ds.theta_significant_amplitude)
    assert 0.7 * sig < float(ds.theta_significant_amplitude_zero_crossing) < 1.1 * sig
    assert float(ds.theta_maximum_amplitude) > float(ds.theta_significant_amplitude_zero_crossing)
    assert float(ds.torque_significant_amplitude) > 0
    for name in ("mean_power", "capture_width", "capture_width_ratio", "theta_rms",
                 "torque_maximum_amplitude"):
        assert "units" in ds[name].attrs and "long_name" in ds[name].attrs
    assert "phase" not in ds.dims and "capture_factor" not in ds


def test_span_outside_the_record_and_no_flux_are_errors(campaign):
    t = np.arange(6000) / FS
    theta = 0.05 * np.sin(2 * np.pi * 0.5 * t)
    enc = campaign.encoder
    counts = counts_from_wire(enc.L7 - wire_length(theta, enc.L5, enc.L7), enc.counts_per_metre)
    p = 1e3 * np.cos(2 * np.pi * 0.5 * t)
    kw = dict(flap=campaign.flap, pto=campaign.pto, encoder=enc)
    with pytest.raises(ValueError, match="window"):
        analyse_irregular_run(t, counts, p, analysis_start=10.0, analysis_end=80.0,
                              energy_flux=10.0, **kw)
    with pytest.raises(ValueError, match="energy flux"):
        analyse_irregular_run(t, counts, p, analysis_start=10.0, analysis_end=50.0,
                              energy_flux=0.0, **kw)
