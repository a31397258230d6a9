"""Incident/reflected separation against synthetic waves with a known truth."""

import warnings

import numpy as np
import pytest
import xarray as xr
from hypothesis import given, settings
from hypothesis import strategies as st

from flumekit.synth.waves import irregular_wave_field, regular_wave_field
from flumekit.waves import (
    MAX_CONDITION,
    SeparationWarning,
    condition_number,
    probe_spacing,
    separate,
    wavelength,
    wavenumber,
)

H = 0.825
FS = 25.0


def probes(field: xr.Dataset, noise: float = 0.0, seed: int = 0) -> xr.DataArray:
    """Probe records (probe, time) from a synthetic field, with Gaussian noise [m]."""
    eta = field.eta.values
    if noise:
        eta = eta + np.random.default_rng(seed).normal(0.0, noise, eta.shape)
    return xr.DataArray(eta, dims=("probe", "time"),
                        coords={"probe": [f"WP{i + 1}" for i in range(eta.shape[0])],
                                "x": ("probe", field.x.values), "time": field.time.values})


def layout(period, x1=-6.0, n=3):
    x12, x23 = probe_spacing(period, H)
    return np.array([x1, x1 + x12, x1 + x12 + x23, x1 + x12 + x23 + 0.37][:n])


def steady_time(period, n_periods=48, start_periods=300):
    """Whole number of periods of a steady regular wave (ramp finished to 1e-15)."""
    n = int(round(n_periods * period * FS))
    return start_periods * period + np.arange(n) / FS


# --- sign convention -------------------------------------------------------------------------

@pytest.mark.parametrize("method, n", [("mansard_funke", 3), ("goda_suzuki", 2),
                                       ("zelt_skjelbreia", 4)])
def test_a_wave_travelling_towards_plus_x_is_incident(method, n):
    T, a = 2.5, 0.05
    k = wavenumber(2 * np.pi / T, H)
    x = layout(T, n=n)
    t = np.arange(int(40 * T * FS)) / FS
    towards_plus = a * np.cos(2 * np.pi / T * t[None, :] - k * x[:, None])
    da = xr.DataArray(towards_plus, dims=("probe", "time"), coords={"x": ("probe", x), "time": t})
    r = separate(da, H, method=method, x_ref=0.0)
    # truth at x_ref = 0: a cos(ωt); nothing travels towards -x
    np.testing.assert_allclose(r.eta_incident.values, a * np.cos(2 * np.pi / T * t), atol=1e-10)
    np.testing.assert_allclose(r.eta_reflected.values, 0.0, atol=1e-10)
    assert float(r.reflection_coefficient) < 1e-9
    towards_minus = da.copy(data=a * np.cos(2 * np.pi / T * t[None, :] + k * x[:, None]))
    r = separate(towards_minus, H, method=method, x_ref=0.0)
    np.testing.assert_allclose(r.eta_reflected.values, a * np.cos(2 * np.pi / T * t), atol=1e-10)
    np.testing.assert_allclose(r.eta_incident.values, 0.0, atol=1e-10)


# --- regular waves ---------------------------------------------------------------------------

@pytest.mark.parametrize("period, height, kr, phase", [(2.0, 0.15, 0.2, 0.0), (3.0, 0.2, 0.08, 2.0),
                                                       (3.5, 0.25, 0.35, -1.0),
                                                       (4.0, 0.3, 0.0, 0.0)])
def test_regular_linear_with_half_mm_noise_kr_and_height(period, height, kr, phase):
    t = steady_time(period)
    field = regular_wave_field(t, layout(period), period=period, height=height, depth=H,
                               reflection=kr, reflection_phase=phase, second_order=False)
    r = separate(probes(field, noise=5e-4), H, regular=True, period=period, x_ref=0.0,
                 band=(0.5 / period, 4.5 / period))
    # acceptance: Kr within ±0.005, incident height within 0.5 % (truth: generator)
    assert abs(float(r.reflection_coefficient) - kr) < 0.005
    assert float(r.incident_height) == pytest.approx(height, rel=0.005)
    assert float(r.incident_amplitude) == pytest.approx(height / 2, rel=0.005)
    # the phase at x_ref = 0: θ = ωt - k (0 - x_wm)
    k = wavenumber(2 * np.pi / period, H)
    d = np.angle(np.exp(1j * (float(r.incident_phase) - (-k * 32.7))))
    assert abs(d) < 0.01


def test_regular_wave_on_a_non_integer_number_of_periods():
    # the statistics come from a harmonic fit at the exact frequency: no leakage bias
    T = 3.5
    t = 300 * T + np.arange(int(40.37 * T * FS)) / FS
    field = regular_wave_field(t, layout(T), period=T, height=0.2, depth=H, reflection=0.2,
                               second_order=False)
    r = separate(probes(field, 5e-4), H, regular=True, period=T, band=(0.5 / T, 4.5 / T))
    assert abs(float(r.reflection_coefficient) - 0.2) < 0.005
    assert float(r.incident_height) == pytest.approx(0.2, rel=0.005)


def test_regular_period_defaults_to_the_spectral_peak():
    T = 3.0
    field = regular_wave_field(steady_time(T), layout(T), period=T, height=0.2, depth=H,
                               second_order=False)
    r = separate(probes(field), H, regular=True)
    assert r.attrs["fundamental_frequency"] == pytest.approx(1 / T, rel=1e-12)


# --- bound harmonics -------------------------------------------------------------------------

@pytest.mark.parametrize("period, height", [(2.5, 0.2), (3.5, 0.25)])
def test_second_order_wave_bound_harmonics(period, height):
    kr = 0.1
    t = steady_time(period)
    field = regular_wave_field(t, layout(period), period=period, height=height, depth=H,
                               reflection=kr, theory="stokes2")
    a1, a2 = field.attrs["incident_amplitude"], field.attrs["bound_amplitude"]
    da = probes(field, noise=5e-4)
    kw = dict(regular=True, period=period, band=(0.5 / period, 4.5 / period), x_ref=0.0)
    r = separate(da, H, bound_harmonics=True, **kw)
    # acceptance: Kr within ±0.01 with the bound-harmonic option
    assert abs(float(r.reflection_coefficient) - kr) < 0.01
    # truth: the second harmonic is bound: incident a2, reflected Kr² a2
    amp_i, amp_r = r.incident_harmonic_amplitude.values, r.reflected_harmonic_amplitude.values
    assert amp_i[1] == pytest.approx(a2, rel=0.01)
    assert abs(amp_r[1] - kr**2 * a2) < 0.01 * a2
    assert float(r.incident_height) == pytest.approx(height, rel=0.005)
    assert float(r.reflected_height) == pytest.approx(2 * kr * a1, rel=0.02)
    # fitted as free waves, the bound harmonic leaks into the "reflected" wave
    free = separate(da, H, bound_harmonics=False, **kw)
    assert free.reflected_harmonic_amplitude.values[1] > 0.1 * a2
    assert abs(float(free.incident_height) - height) > 0.02 * height


@pytest.mark.parametrize("period, height", [(3.5, 0.25), (4.0, 0.3)])
def test_steep_wave_needs_its_nonlinear_wavenumbers(period, height):
    # a stream-function wave (Ursell 43 and 72) travels 3-5 % faster than linear theory says;
    # separated with the linear k its Kr is off by 0.004 to 0.03 (depending on where the
    # probes sit), with the true k_I, k_R (``wavenumbers``) Kr is within ±0.002 and the 8
    # harmonics within 1 % of the truth
    kr = 0.2
    field = regular_wave_field(steady_time(period), layout(period), period=period,
                               height=height, depth=H, reflection=kr, reflection_phase=0.6)
    da = probes(field, noise=5e-4)
    kw = dict(regular=True, period=period, band=(0.5 / period, 8.5 / period), x_ref=0.0,
              bound_harmonics=True)
    lin = separate(da, H, **kw)
    assert abs(float(lin.reflection_coefficient) - kr) > 0.004
    ks = (field.attrs["wave_number"], field.attrs["reflected_wave_number"])
    r = separate(da, H, wavenumbers=ks, **kw)
    assert abs(float(r.reflection_coefficient) - kr) < 0.002
    np.testing.assert_allclose(r.incident_harmonic_amplitude.values,
                               field.attrs["harmonic_amplitudes"][:8], rtol=0.01, atol=2e-5)
    assert r.attrs["fundamental_wavenumbers"] == list(ks)
    with pytest.raises(ValueError, match="regular"):
        separate(da, H, regular=False, wavenumbers=ks)


# --- irregular waves -------------------------------------------------------------------------

@pytest.mark.parametrize("method, n, window", [("mansard_funke", 3, None),
                                               ("zelt_skjelbreia", 4, None),
                                               ("mansard_funke", 3, "hann")])
def test_jonswap_kr_and_hm0(method, n, window):
    Tp, hm0, kr = 2.5, 0.12, 0.25
    t = np.arange(int(600 * FS)) / FS
    field = irregular_wave_field(t, layout(Tp, n=n), hm0=hm0, peak_period=Tp, depth=H,
                                 reflection=kr, reflection_phase=0.7, rng=3)
    r = separate(probes(field, noise=5e-4, seed=1), H, method=method, window=window)
    # acceptance: Kr within ±0.01; Hm0 within 2 % (untapered); a Hann taper weights the
    # record unevenly, so wave groups make its Hm0 a noisier estimate: 7 % here
    assert abs(float(r.reflection_coefficient) - kr) < 0.01
    assert float(r.incident_height) == pytest.approx(hm0, rel=0.02 if window is None else 0.07)
    assert float(r.reflected_height) == pytest.approx(kr * hm0, rel=0.05)
    assert float(r.masked_energy_fraction) < 0.001


def test_incident_series_at_x_ref_matches_the_truth():
    Tp = 2.0
    t = np.arange(int(300 * FS)) / FS
    x = layout(Tp)
    field = irregular_wave_field(t, np.r_[x, -1.0], hm0=0.1, peak_period=Tp, depth=H,
                                 reflection=0.3, rng=7, f_max=1.2)
    da = probes(field.isel(x=slice(0, 3)))
    r = separate(da, H, x_ref=-1.0)
    # noise-free, periodic record, every bin well-conditioned in (0, 1.2] Hz except the
    # lowest few (masked, holding < 1e-6 of the energy)
    assert float(r.masked_energy_fraction) < 1e-6
    np.testing.assert_allclose(r.eta_incident.values, field.eta_incident.values[3], atol=2e-5)
    np.testing.assert_allclose(r.eta_reflected.values, field.eta_reflected.values[3], atol=2e-5)


# --- singular layouts ------------------------------------------------------------------------

def _masked_fraction_truth(da, x, max_condition=MAX_CONDITION):
    """Energy fraction of the bins the closed-form condition number flags (independent path)."""
    n = da.time.size
    c = np.fft.rfft(da.values - da.values.mean(axis=1, keepdims=True), axis=1)
    f = np.fft.rfftfreq(n, 1 / FS)
    keep = (f > 0) & (f < FS / 2)
    e = np.mean(np.abs(c[:, keep]) ** 2, axis=0)
    bad = condition_number(x, f[keep], H) > max_condition
    return e[bad].sum() / e.sum()


@pytest.mark.parametrize("method, spacing", [("goda_suzuki", (0.5,)),
                                             ("mansard_funke", (0.5, 1.0))])
def test_singular_layout_warns_masks_and_reports_lost_energy(method, spacing):
    Tp = 2.5
    Lp = float(wavelength(Tp, H))
    x = -9.0 + Lp * np.r_[0.0, spacing]
    t = np.arange(int(600 * FS)) / FS
    field = irregular_wave_field(t, x, hm0=0.12, peak_period=Tp, depth=H, reflection=0.25, rng=3)
    da = probes(field, noise=5e-4)
    with pytest.warns(SeparationWarning, match="ill-conditioned"):
        r = separate(da, H, method=method)
    for name in r.data_vars:  # finite everywhere; the condition number is inf where singular
        if name != "condition_number":
            assert np.all(np.isfinite(r[name].values)), name
    assert np.all(r.condition_number.values[r.masked.values == 0] <= MAX_CONDITION)
    frac = float(r.masked_energy_fraction)
    assert frac == pytest.approx(_masked_fraction_truth(da, x), rel=1e-9)
    assert frac > 0.2  # the spectral peak sits on the singularity
    # the reflection coefficient of the retained bins is still right (Kr is uniform here)
    assert abs(float(r.reflection_coefficient) - 0.25) < 0.01
    # masked bins carry no incident or reflected energy
    m = r.masked.values.astype(bool)
    assert np.all(r.spectrum_incident.values[m] == 0)


def test_regular_wave_on_a_singular_layout_is_an_error_not_a_wrong_answer():
    T = 2.5
    L = float(wavelength(T, H))
    x = np.array([-9.0, -9.0 + L / 2, -9.0 + L])
    field = regular_wave_field(steady_time(T), x, period=T, height=0.1, depth=H,
                               second_order=False)
    with pytest.raises(ValueError, match="ill-conditioned"), warnings.catch_warnings():
        warnings.simplefilter("ignore", SeparationWarning)
        separate(probes(field), H, regular=True, period=T, band=(0.2, 0.6))


# --- bad input -------------------------------------------------------------------------------

def test_bad_input_is_named():
    T = 2.5
    field = regular_wave_field(steady_time(T, 8), layout(T), period=T, height=0.1, depth=H)
    da = probes(field)
    with pytest.raises(ValueError, match="exactly 2"):
        separate(da, H, method="goda_suzuki")
    with pytest.raises(ValueError, match="unknown separation method"):
        separate(da, H, method="fft")
    with pytest.raises(ValueError, match="dims"):
        separate(da.rename(probe="gauge"), H)
    with pytest.raises(ValueError, match="coordinate 'x'"):
        separate(da.drop_vars("x"), H)
    with pytest.raises(ValueError, match="distinct"):
        separate(da.assign_coords(x=("probe", [0.0, 0.0, 1.0])), H)
    bad = da.copy()
    bad.values[1, 10] = np.nan
    with pytest.raises(ValueError, match="non-finite.*WP2"):
        separate(bad, H)
    with pytest.raises(ValueError, match="band"):
        separate(da, H, band=(20.0, 30.0))
    with pytest.raises(ValueError, match="uniformly"):
        separate(da.assign_coords(time=da.time.values ** 1.01), H)
    with pytest.raises(ValueError, match="depth"):
        separate(da, -1.0)


# --- properties (hypothesis) -----------------------------------------------------------------

def _regular(kr, phase, amplitude, t0, period=3.0):
    t = t0 + 300 * period + np.arange(int(24 * period * FS)) / FS
    field = regular_wave_field(t, layout(period), period=period, height=2 * amplitude, depth=H,
                               reflection=kr, reflection_phase=phase, second_order=False)
    return probes(field)


KW = dict(regular=True, period=3.0, band=(0.5 / 3.0, 2.5 / 3.0))


@settings(max_examples=25, deadline=None)
@given(st.floats(0.0, 0.9), st.floats(-np.pi, np.pi), st.floats(0.01, 0.2),
       st.floats(1e-3, 1e3))
def test_amplitude_scaling_invariance(kr, phase, amplitude, scale):
    da = _regular(kr, phase, amplitude, 0.0)
    r1 = separate(da, H, **KW)
    r2 = separate(da * scale, H, **KW)
    assert float(r2.reflection_coefficient) == pytest.approx(float(r1.reflection_coefficient),
                                                             rel=1e-9, abs=1e-12)
    assert float(r2.incident_height) == pytest.approx(scale * float(r1.incident_height), rel=1e-9)
    np.testing.assert_allclose(r2.eta_incident.values, scale * r1.eta_incident.values,
                               rtol=1e-9, atol=1e-12 * scale)


@settings(max_examples=25, deadline=None)
@given(st.floats(0.0, 0.9), st.floats(-np.pi, np.pi), st.floats(0.0, 100.0))
def test_time_shift_invariance_of_kr(kr, phase, t0):
    r0 = separate(_regular(kr, phase, 0.05, 0.0), H, **KW)
    r1 = separate(_regular(kr, phase, 0.05, t0), H, **KW)
    assert float(r1.reflection_coefficient) == pytest.approx(float(r0.reflection_coefficient),
                                                             abs=1e-9)
    assert abs(float(r1.reflection_coefficient) - kr) < 1e-6


@settings(max_examples=25, deadline=None)
@given(st.floats(0.0, 0.9), st.floats(-np.pi, np.pi), st.floats(-5.0, 5.0),
       st.sampled_from(["mansard_funke", "zelt_skjelbreia"]))
def test_swapping_the_direction_of_travel_swaps_incident_and_reflected(kr, phase, x_ref, method):
    da = _regular(kr, phase, 0.05, 0.0)
    mirrored = da.assign_coords(x=("probe", -da.x.values))  # x -> -x reverses both waves
    kw = {**KW, "x_ref": x_ref}
    r = separate(da, H, method=method, **kw)
    m = separate(mirrored, H, method=method, **{**kw, "x_ref": -x_ref})
    np.testing.assert_allclose(m.eta_incident.values, r.eta_reflected.values, atol=1e-12)
    np.testing.assert_allclose(m.eta_reflected.values, r.eta_incident.values, atol=1e-12)
    np.testing.assert_allclose(m.spectrum_incident.values, r.spectrum_reflected.values,
                               rtol=1e-9, atol=1e-18)


def test_default_x_ref_is_the_device_in_the_api_and_the_pipeline():
    """Without ``x_ref`` the incident wave is returned at x = 0 (the flap hinge), as the
    pipeline's ``[stages.waves]`` does, not at the first probe."""
    import inspect

    from flumekit.stages.waves import DEFAULTS

    T, a = 2.5, 0.05
    k = wavenumber(2 * np.pi / T, H)
    x = layout(T)  # the first probe at -6 m: the two defaults differ by k * 6 m in phase
    t = np.arange(int(40 * T * FS)) / FS
    da = xr.DataArray(a * np.cos(2 * np.pi / T * t[None, :] - k * x[:, None]),
                      dims=("probe", "time"), coords={"x": ("probe", x), "time": t})
    r = separate(da, H)
    assert inspect.signature(separate).parameters["x_ref"].default == DEFAULTS["x_ref"] == 0.0
    assert r.attrs["x_ref"] == 0.0
    # truth at x = 0: a cos(ωt), to the round-off of a noise-free periodic record
    np.testing.assert_allclose(r.eta_incident.values, a * np.cos(2 * np.pi / T * t), atol=1e-10)


@pytest.mark.parametrize("unknowns", [2, 3])
def test_shared_design_matrices_solve_as_one_per_system(unknowns):
    # systems that share a design matrix (the bins of one harmonic of a regular wave): the
    # index path gives what one matrix per system gives, masked systems included
    from flumekit.waves.separation import lstsq_normal

    rng = np.random.default_rng(0)
    k = np.concatenate([rng.uniform(0.1, 5.0, 40), [0.0, np.pi / 1.1]])  # last two singular
    x = np.array([0.0, 1.1, 2.2, 3.3])[:unknowns + 1]
    phase = np.exp(-1j * k[:, None] * x)
    cols = [phase, np.conj(phase), np.exp(-2j * k[:, None] * x)][:unknowns]
    columns = np.stack(cols, axis=-1)  # (U, P, K)
    index = rng.integers(0, k.size, 500)
    rhs = rng.normal(size=(500, x.size, 2)) + 1j * rng.normal(size=(500, x.size, 2))
    sol, cond, masked = lstsq_normal(columns, rhs, 30.0, index=index)
    ref_sol, ref_cond, ref_masked = lstsq_normal(columns[index], rhs, 30.0)
    assert masked.any() and not masked.all()
    np.testing.assert_array_equal(masked, ref_masked)
    np.testing.assert_allclose(cond, ref_cond, rtol=1e-12)
    np.testing.assert_allclose(sol, ref_sol, rtol=0, atol=1e-12)
    assert np.all(sol[masked] == 0)


@pytest.mark.parametrize("n", [200, 256, 1000, 15001])
def test_harmonic_fit_recovers_exact_harmonics_of_any_length(n):
    # known harmonics (up to near Nyquist), a mean and a non-whole number of periods: the
    # block sums give the exact least-squares fit whether or not n fills whole blocks
    from flumekit.waves.separation import _harmonic_fit

    f1, nh = 0.3123, 30
    t = 12.5 + np.arange(n) / FS
    z = (np.random.default_rng(n).normal(size=(2, nh))
         + 1j * np.random.default_rng(n + 1).normal(size=(2, nh))) * 0.01
    n_h = np.arange(1, nh + 1)
    v = 0.3 + np.real(z[:, :, None] * np.exp(2j * np.pi * n_h[:, None] * f1 * (t - t[0])))
    np.testing.assert_allclose(_harmonic_fit(v.sum(axis=1), t, f1, nh), z, rtol=0, atol=1e-11)
