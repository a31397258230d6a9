"""The virtual UVP: potential-flow kinematics, phase convention, instrument model."""

from __future__ import annotations

import numpy as np
import pytest

from flumekit.io.mfprof import read_mfprof
from flumekit.synth.uvp import (
    incident_upcrossing,
    true_field,
    uvp_beams,
    wave_kinematics,
    write_beam,
)
from flumekit.synth.waves import Beach, regular_wave_field

T, H, DEPTH = 3.5, 0.25, 0.825
WAVE = dict(period=T, height=H, depth=DEPTH, reflection=0.2, reflection_phase=0.6)


@pytest.mark.parametrize("theory", ["linear", "stokes2", "stream", "stream+beach"])
def test_kinematics_is_potential_flow(theory):
    """Continuity and irrotationality by central differences (error O(k³ d²) ~ 1e-9)."""
    rng = np.random.default_rng(1)
    x, z, t = rng.uniform(-0.4, -0.1, 50), rng.uniform(0.0, 0.6, 50), rng.uniform(100, 200, 50)
    d = 1e-4
    beach = Beach(transmission=0.9) if theory.endswith("beach") else None
    kw = dict(WAVE, theory=theory.split("+")[0], beach=beach, ramp_waves=None)
    ux1, wx1, _ = wave_kinematics(x + d, z, t, **kw)
    ux0, wx0, _ = wave_kinematics(x - d, z, t, **kw)
    uz1, wz1, _ = wave_kinematics(x, z + d, t, **kw)
    uz0, wz0, _ = wave_kinematics(x, z - d, t, **kw)
    div = (ux1 - ux0 + wz1 - wz0) / (2 * d)
    curl = (uz1 - uz0 - (wx1 - wx0)) / (2 * d)
    scale = np.pi * H / T * 2 * np.pi / 9.5  # U0 k
    assert np.max(np.abs(div)) < 1e-6 * scale
    assert np.max(np.abs(curl)) < 1e-6 * scale


def test_linear_kinematic_surface_condition():
    """Linear theory: w at the still-water level equals dη/dt."""
    t = np.linspace(50, 60, 200)
    kw = dict(WAVE, second_order=False, ramp_waves=None)
    _, w, _ = wave_kinematics(-0.2, DEPTH - 0.10, t, **kw)
    dt = 1e-5
    deta = (wave_kinematics(-0.2, 0.0, t + dt, **kw)[2]
            - wave_kinematics(-0.2, 0.0, t - dt, **kw)[2]) / (2 * dt)
    np.testing.assert_allclose(w, deta, atol=1e-8)


@pytest.mark.parametrize("beach", [None, Beach(transmission=0.9, phase=0.4)])
def test_same_surface_and_phase_as_the_wave_synth(beach):
    """η and the incident up-crossing agree with flumekit.synth.waves (one flow per run)."""
    t = np.arange(0, 400, 0.04)
    x = np.array([-0.3, 0.0])
    ref = regular_wave_field(t, x, beach=beach, **WAVE)
    _, _, eta = wave_kinematics(x[:, None], 0.0, t[None, :], beach=beach, **WAVE)
    np.testing.assert_allclose(eta, ref["eta"].values, atol=1e-12)
    t_up = incident_upcrossing(period=T, height=H, depth=DEPTH)
    tt = t_up + 100 * T + np.array([-1e-4, 0.0, 1e-4])
    inc = regular_wave_field(tt, np.array([0.0]), **{**WAVE, "reflection": 0.0})["eta"].values[0]
    # at t ≈ 360 s the wave synth's ramp envelope is 1 - 2e-7: |η| ~ 1e-8 m is its residue
    assert abs(inc[1]) < 1e-7 and inc[2] > 0 > inc[0]


def test_virtual_beams_are_quantised_projections(campaign, tmp_path):
    u = campaign.uvp
    t = np.arange(int(30 * T * u.sampling_rate)) / u.sampling_rate
    beams = uvp_beams(t, u, 0.3, noise=0.0, ramp_waves=None, rng=0, **WAVE)
    for b in u.beams:
        ds = beams[b.name]
        dv = ds.attrs["velocity_resolution"]
        v = ds["beam_velocity"].values
        np.testing.assert_array_equal(np.rint(v / dv) * dv, v)  # whole counts of dv
        x = b.x + ds["distance"].values * np.cos(b.angle)
        z = 0.3 + ds["distance"].values * np.sin(b.angle)
        uu, ww, _ = wave_kinematics(x[None, :], z[None, :], t[:, None], ramp_waves=None, **WAVE)
        truth = uu * np.cos(b.angle) + ww * np.sin(b.angle)
        seen = (ds["amplitude"].values > 100) & (ds["amplitude"].values < 1000)
        assert seen.mean() > 0.9
        assert np.max(np.abs(v - truth)[seen]) <= dv / 2 + 1e-12
    # UP2's last channel (x = -0.0843 m) lies behind the flap face at x = -0.085 m
    assert np.all(beams["UP2"]["amplitude"].values[:, -1] > 1000)
    # the lead's call: write with the campaign UVP settings, read back exactly
    p = write_beam(tmp_path / "UP1.mfprof", beams["UP1"], u)
    back = read_mfprof(p)
    np.testing.assert_array_equal(back["beam_velocity"].values,
                                  beams["UP1"]["beam_velocity"].values)
    np.testing.assert_allclose(back["time"].values, t, atol=5e-8)  # 100 ns ticks
    np.testing.assert_allclose(back["distance"].values, beams["UP1"]["distance"].values, atol=1e-15)


def test_true_field_reference_and_masks(campaign):
    f = true_field(campaign, period=T, height=H, reflection=0.2, reflection_phase=0.6)
    t_up = float(f["phase_reference"])
    p, z, x = 0.27, 0.40, -0.2
    u, w, _ = wave_kinematics(x, z, t_up + p * T, ramp_waves=None, **WAVE)
    sel = f.sel(phase=p, z=z, x=x, method="nearest")
    assert float(sel["u"]) == pytest.approx(float(u), abs=1e-12)
    assert float(sel["w"]) == pytest.approx(float(w), abs=1e-12)
    assert float(sel["u_normalised"]) == pytest.approx(float(u) / (np.pi * H / T), abs=1e-12)
    # above the free surface: masked; always-submerged points: never
    swl = DEPTH - 0.10
    above = f["z"].values[None, :, None] > swl + f["eta"].values[:, None, :]
    assert np.all(np.isnan(f["u"].values[above])) and np.all(np.isfinite(f["u"].values[~above]))


def test_first_harmonic_reference(campaign):
    """Phase 0 at the first harmonic's up-crossing: θ_I = ωt + k x_wm = -π/2 at x = 0, k the
    (nonlinear) wavenumber of the stream-function wave."""
    from flumekit.waves.stream_function import stream_function_wave

    f = true_field(campaign, period=T, height=H, reference="first_harmonic", x=[-0.2], z=[0.3])
    w = 2 * np.pi / T
    k = stream_function_wave(T, H, DEPTH, current="stokes").wavenumber
    expected = ((-np.pi / 2 + k * 32.7) / w) % T
    assert float(f["phase_reference"]) == pytest.approx(expected, abs=1e-12)
    full = true_field(campaign, period=T, height=H, x=[-0.2], z=[0.3])
    # the harmonics (the second 0.39 of the first) move the total up-crossing by ~0.05 T
    shift = (float(f["phase_reference"]) - float(full["phase_reference"])) / T
    assert 0.03 < abs(shift) < 0.1
    with pytest.raises(ValueError, match="reference"):
        true_field(campaign, period=T, height=H, reference="crest")
