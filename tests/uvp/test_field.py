"""Field assembly: interpolation on the beams' sheared grids, repeats, and the acceptance test
against the virtual flume's truth (⟨u⟩, ⟨w⟩ within 2 % of U0, RMS over the field)."""

from __future__ import annotations

import numpy as np
import pytest
import xarray as xr

from flumekit.synth.uvp import incident_upcrossing, true_field, uvp_beams
from flumekit.uvp import (
    beam_to_grid,
    combine_repeats,
    default_grid,
    phase_average_beams,
    velocity_field,
)

T, H, DEPTH, KR, PHI = 3.5, 0.25, 0.825, 0.2, 0.6
ELEVATIONS = np.round(np.arange(0.20, 0.7201, 0.02), 3)
U0 = np.pi * H / T


def _rms(field, truth, name):
    e = (field[name] - truth[name].sel(x=field.x, z=field.z)).values / U0
    ok = np.isfinite(e)
    return float(np.sqrt(np.mean(e[ok] ** 2))), float(ok.mean())


def _runs(campaign, elevations, n_cycles, seed, **kw):
    u = campaign.uvp
    t = np.arange(int((n_cycles + 4) * T * u.sampling_rate)) / u.sampling_rate
    start = incident_upcrossing(period=T, height=H, depth=DEPTH) + 2 * T
    out = []
    for k, z in enumerate(elevations):
        beams = uvp_beams(t, u, z, period=T, height=H, depth=DEPTH, reflection=KR,
                          reflection_phase=PHI, ramp_waves=None, rng=seed + k,
                          **kw.get("synth", {}))
        out.append(phase_average_beams(beams, u, z, period=T, start=start, n_cycles=n_cycles,
                                       min_amplitude=100.0, flap_thickness=0.17,
                                       **kw.get("process", {})))
    return out


@pytest.fixture(scope="module")
def runs(campaign):
    # every elevation once, three of them repeated (as the paper's 78 runs repeat them)
    elev = list(ELEVATIONS) + [0.30, 0.46, 0.62]
    return _runs(campaign, elev, n_cycles=10, seed=100)


@pytest.fixture(scope="module")
def truth(campaign):
    return true_field(campaign, period=T, height=H, reflection=KR, reflection_phase=PHI)


def test_acceptance_least_squares_within_2_percent(runs, truth, campaign):
    f = velocity_field(runs, campaign.uvp, height=H, period=T, water_depth=DEPTH)
    assert f.attrs["method"] == "least_squares" and f.attrs["n_runs"] == 30
    for name in ("u", "w"):
        rms, cov = _rms(f, truth, name)
        assert rms < 0.02, f"<{name}> RMS error {rms:.4f} U0"
        assert cov > 0.6  # most of (phase, z, x) is resolved
    np.testing.assert_allclose(f["u_normalised"], f["u"] / U0)
    assert float(f["velocity_scale"]) == pytest.approx(U0)
    # the CI is a real CI: the errors stay within ~2.6 x the 95 % half-width almost everywhere
    e = np.abs(f["u"] - truth["u"].sel(x=f.x, z=f.z)).values
    ci = f["u_ci"].values
    ok = np.isfinite(e) & np.isfinite(ci)
    assert np.mean(e[ok] < 2.6 * ci[ok] + 1e-3) > 0.95


def test_eqs_9_10_are_worse_than_least_squares(runs, truth, campaign):
    """Eqs. (9)-(10) assume the flow uniform over the 2 r sin α between the paired channels;
    with kh = 0.55 the vertical gradient of u biases ⟨w⟩ (and u) by several % of U0."""
    ls = velocity_field(runs, campaign.uvp, height=H, period=T)
    pr = velocity_field(runs, campaign.uvp, height=H, period=T, method="paired")
    for name in ("u", "w"):
        assert _rms(pr, truth, name)[0] > 3 * _rms(ls, truth, name)[0]


def test_beam_to_grid_is_exact_for_linear_fields(campaign):
    """x and z are linear in (elevation, distance) along a beam family, so bilinear
    interpolation reproduces any linear field exactly; outside the lines: NaN."""
    e = np.array([0.2, 0.22, 0.26, 0.30])  # unequal spacing (a missing elevation)
    r = 0.02 + np.arange(50) * 0.004
    a, bx, dz = -np.pi / 6, -0.37, 0.01
    xl = bx + r[None, :] * np.cos(a)
    zl = e[:, None] + dz + r[None, :] * np.sin(a)
    vals = (0.3 + 1.5 * xl - 0.7 * zl)[..., None] * np.array([1.0, 2.0])  # 2 "phases"
    x = np.linspace(-0.36, -0.2, 9)
    z = np.linspace(0.1, 0.35, 11)
    g = beam_to_grid(vals, e, r, bx, dz, a, x, z)
    X, Z = np.meshgrid(x, z)
    exact = (0.3 + 1.5 * X - 0.7 * Z)[..., None] * np.array([1.0, 2.0])
    inside = np.isfinite(g)
    assert inside.mean() > 0.3
    np.testing.assert_allclose(g[inside], exact[inside], atol=1e-12)
    rq = (X - bx) / np.cos(a)
    eq = Z - dz - (X - bx) * np.tan(a)
    cover = (rq >= r[0]) & (rq <= r[-1]) & (eq >= e[0]) & (eq <= e[-1])
    np.testing.assert_array_equal(inside[..., 0], cover)


def test_combine_repeats_statistics(runs):
    a, b = runs[ELEVATIONS.tolist().index(0.30)], runs[-3]
    assert float(a["uvp_elevation"]) == float(b["uvp_elevation"]) == 0.30
    b = b.copy(deep=True)
    b["beam_velocity"][0, 5, :] = np.nan  # a masked channel in one repeat
    c = combine_repeats([a, b]).sel(uvp_elevation=0.30)
    assert int(c["n_repeats"]) == 2
    m = (a["beam_velocity"] + b["beam_velocity"]) / 2
    np.testing.assert_allclose(c["beam_velocity"].values[1], m.values[1])
    np.testing.assert_allclose(c["beam_velocity"].values[0, 5], a["beam_velocity"].values[0, 5])
    np.testing.assert_allclose(c["beam_velocity_ci"].values[1],
                               np.hypot(a["beam_velocity_ci"][1], b["beam_velocity_ci"][1]) / 2)
    np.testing.assert_allclose(
        c["beam_velocity_std"].values[1],
        np.sqrt((a["beam_velocity_std"][1] ** 2 + b["beam_velocity_std"][1] ** 2) / 2))
    with pytest.raises(ValueError, match="no run"):
        combine_repeats([])


def test_default_grid(campaign):
    x, z = default_grid(campaign.uvp, ELEVATIONS)
    np.testing.assert_allclose(z, ELEVATIONS)
    assert x[0] == pytest.approx(-0.35) and x[-1] == pytest.approx(-0.09)
    assert np.allclose(np.diff(x), 0.01)


def test_flap_mask_in_the_field(runs, campaign):
    theta = 0.2 * np.sin(2 * np.pi * runs[0]["phase"].values)
    f = velocity_field(runs, campaign.uvp, height=H, period=T, theta=theta,
                       flap_thickness=0.17, margin=0.01)
    X, Z = np.meshgrid(f.x, f.z)
    th = theta[:, None, None]
    inside = X[None] > Z[None] * np.tan(th) - 0.085 / np.cos(th) - 0.01
    assert inside.any()
    assert np.all(np.isnan(f["u"].values[inside])) and np.all(f["inside_flap"].values[inside] == 1)


def test_turbulence_statistics_recovered(campaign):
    """Band-limited fluctuations σu = 0.02, σw = 0.03 m/s, ρ = 0.3, no Doppler noise, no
    filter: field means of ⟨u'²⟩, ⟨w'²⟩, ⟨u'w'⟩ within 4 %, 4 %, 6 %. Over five seeds the
    errors stayed within ±1.3 %, ±1.3 %, ±2.3 % (sampling with 30 cycles; ⟨w'²⟩ is a
    difference of beam variances); quantisation adds ΔV²/12 ≈ 4.5e-6 m²/s² (+1.1 % of ⟨u'²⟩)."""
    su, sw, rho = 0.02, 0.03, 0.3
    runs = _runs(campaign, ELEVATIONS[:14], n_cycles=30, seed=7,
                 synth={"noise": 0.0, "turbulence": (su, sw, rho)}, process={"cutoff": None})
    f = velocity_field(runs, campaign.uvp, height=H, period=T)
    uu, ww, uw = f["uu"].values, f["ww"].values, f["uw"].values  # unclipped estimates
    ok = np.isfinite(uu) & np.isfinite(ww) & np.isfinite(uw)
    assert ok.mean() > 0.3
    assert np.mean(uu[ok]) == pytest.approx(su**2, rel=0.04)
    assert np.mean(ww[ok]) == pytest.approx(sw**2, rel=0.04)
    assert np.mean(uw[ok]) == pytest.approx(rho * su * sw, rel=0.06)
    tke = f["tke"].values[ok]
    assert np.mean(tke) == pytest.approx(0.5 * (su**2 + sw**2), rel=0.04)
    np.testing.assert_allclose(f["u_rms"].values[ok], np.sqrt(np.clip(uu[ok], 0, None)))


def test_bad_arguments(runs, campaign):
    with pytest.raises(ValueError, match="method"):
        velocity_field(runs, campaign.uvp, height=H, period=T, method="magic")
    with pytest.raises(ValueError, match="flap_thickness"):
        velocity_field(runs, campaign.uvp, height=H, period=T,
                       theta=np.zeros(runs[0].sizes["phase"]))
    assert isinstance(combine_repeats(runs[:2]), xr.Dataset)
