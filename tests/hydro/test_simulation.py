"""Generic one-dof simulator: WEC-Sim's OSWEC against the frequency-domain solution, energy
balance, waves, PTOs, stability guards and bounded memory; tolerances stated per test."""

import tracemalloc
import warnings
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from flumekit.hydro import coefficients as H
from flumekit.hydro import simulation as S
from flumekit.hydro.capytaine import read_capytaine
from flumekit.hydro.rigid_body import about_hinge, inertia_about_hinge

OSWEC = Path(__file__).resolve().parents[1] / "data" / "wecsim" / "oswec_hydrodynamics.nc"
COG, HINGE = (0.0, 0.0, -3.9), (0.0, 0.0, -8.9)
KERNEL = {"amplitude": [400.0, 300.0], "decay_rate": [1.0, 3.0], "frequency": [2.5, 6.0]}


@pytest.fixture(scope="module")
def oswec():
    """WEC-Sim's OSWEC example: the flap's coefficients about its hinge and its inertia."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", H.FailedFrequencyWarning)
        rb = read_capytaine(OSWEC, body="oswec_flap", reference_point=COG)
        # negative damping above 9.6 rad/s (BEM noise, 2 % of the peak) clipped explicitly
        hy = about_hinge(rb, HINGE, mass=127000.0, displaced_volume=297.38, passivity="clip")
    inertia = inertia_about_hinge(127000.0, 1.85e6, COG, HINGE)  # wecSimInputFile.m
    return hy, inertia


@pytest.fixture(scope="module")
def kernel_hydro():
    w = np.linspace(0.05, 25.0, 500)
    return H.from_kernel(w, **KERNEL, added_inertia_infinite=25.0,
                         excitation_torque=2000 * np.exp(-((w / 6) ** 2)) * np.exp(-0.3j * w),
                         hydrostatic_stiffness=605.0)


@pytest.fixture(scope="module")
def kernel_rad(kernel_hydro):
    """One state-space fit shared by the tests (as a campaign shares it by its runs)."""
    return S.radiation_model(kernel_hydro, "state_space", 0.05, irf_duration=20.0)


def harmonic(ds, w, start):
    sel = ds["time"].values >= start
    t, y = ds["time"].values[sel], ds["theta"].values[sel]
    c = np.linalg.lstsq(np.column_stack([np.cos(w * t), np.sin(w * t), np.ones_like(t)]), y,
                        rcond=None)[0]
    return c[0] + 1j * c[1]


@pytest.mark.parametrize("kind", ["state_space", "convolution"])
def test_oswec_matches_the_frequency_domain_solution(oswec, kind):
    """H = 2.5 m, PTO 12 kN m s/rad: steady amplitude within 0.5 %, phase within 1 deg."""
    hy, inertia = oswec
    nu, dt = 12000.0, 0.1
    rad = S.radiation_model(hy, kind, dt, irf_duration=60.0)  # one fit for both periods
    w_grid = hy["angular_frequency"].values
    for period in (8.0, 12.0):
        w = 2 * np.pi / period
        ds = S.simulate(hy, inertia, S.LinearPTO(nu), S.RegularWave(2.5, period, ramp=5 * period),
                        dt=dt, duration=30 * period, radiation=rad)
        a, b = (np.interp(w, w_grid, hy[n].values) for n in ("added_inertia",
                                                             "radiation_damping"))
        f = np.interp(w, w_grid, hy["excitation_torque"].values.real) + 1j * np.interp(
            w, w_grid, hy["excitation_torque"].values.imag)
        truth = f * 1.25 / (-w**2 * (inertia + a) + float(hy["hydrostatic_stiffness"])
                            - 1j * w * (b + nu))
        z = harmonic(ds, w, 25 * period)
        assert abs(abs(z) / abs(truth) - 1) < 5e-3, (kind, period, abs(z) / abs(truth) - 1)
        assert abs(np.degrees(np.angle(z / truth))) < 1.0, (kind, period)
        # energy balance closes to the integration error
        resid = float(np.max(np.abs(ds["energy_balance_residual"].values)))
        assert resid < 5e-3 * float(ds["work_excitation"].max())


def test_linear_pto_at_half_second_step_raises_a_clear_error(kernel_hydro, kernel_rad):
    with pytest.raises(S.DivergenceError, match=r"diverged at step \d+ \(t = .* s\).*dt = 0\.5 s"
                                                r".*reduce dt, e\.g\. to 0\.125 s"):
        S.simulate(kernel_hydro, 14.74, S.LinearPTO(150.0), S.RegularWave(0.1, 3.5, ramp=7.0),
                   dt=0.5, duration=200.0, radiation=kernel_rad)
    ds = S.simulate(kernel_hydro, 14.74, S.LinearPTO(150.0), S.RegularWave(0.1, 3.5, ramp=7.0),
                    dt=0.1, duration=200.0, radiation=kernel_rad)
    assert float(np.abs(ds["theta"]).max()) < 0.2


def test_bad_parameters_are_named(kernel_hydro):
    for kwargs, name in (({"inertia": np.nan}, "inertia"), ({"dt": np.nan}, "dt")):
        args = {"inertia": 14.74, "dt": 0.05, **kwargs}
        with pytest.raises(S.BadParameterError, match=f"bad parameter: {name} = nan"):
            S.simulate(kernel_hydro, args["inertia"], None, S.RegularWave(0.1, 3.5),
                       dt=args["dt"], duration=10.0)
    with pytest.raises(S.BadParameterError, match="pto damping = nan"):
        S.LinearPTO(np.nan)
    with pytest.raises(S.BadParameterError, match="wave height = nan"):
        S.RegularWave(np.nan, 3.5)
    with pytest.raises(S.BadParameterError, match="drag_coefficient"):
        S.BodyDynamics(14.74, 25.0, 605.0, drag_coefficient=np.nan)


def test_passivity_is_always_checked(kernel_hydro):
    bad = kernel_hydro.copy()
    bad["radiation_damping"] = bad["radiation_damping"] - 50.0
    assert "added_inertia_infinite" in bad
    with pytest.raises(H.HydroError, match="radiation damping is negative"):
        S.simulate(bad, 14.74, None, S.RegularWave(0.1, 3.5), dt=0.05, duration=10.0)


def test_callable_pto_and_irregular_wave(kernel_hydro, kernel_rad):
    w = np.linspace(0.5, 6.0, 60)
    s = 0.001 * np.exp(-(((w - 2.0) / 0.5) ** 2))
    wave = S.IrregularWave(w, s, seed=3, ramp=10.0)
    runs = [S.simulate(kernel_hydro, 14.74, pto, wave, dt=0.05, duration=60.0, radiation=kernel_rad)
            for pto in (S.LinearPTO(150.0), S.CallablePTO(lambda t, th, om: 150.0 * om))]
    np.testing.assert_allclose(runs[0]["theta"], runs[1]["theta"], rtol=0, atol=1e-14)
    again = S.simulate(kernel_hydro, 14.74, S.LinearPTO(150.0), wave, dt=0.05, duration=60.0,
                       radiation=kernel_rad)
    np.testing.assert_array_equal(again["theta"], runs[0]["theta"])
    other = S.simulate(kernel_hydro, 14.74, S.LinearPTO(150.0),
                       S.IrregularWave(w, s, seed=4, ramp=10.0), dt=0.05, duration=60.0,
                       radiation=kernel_rad)
    assert not np.allclose(other["theta"], runs[0]["theta"])
    # the elevation's variance over the steady part against the spectrum's, Hs = 4 sqrt(m0)
    eta = runs[0]["eta_incident"].values[runs[0]["time"].values > 10]
    hs = runs[0].attrs["significant_wave_height"]
    assert 4 * eta.std() == pytest.approx(hs, rel=0.25)
    p = runs[0]
    assert float(np.max(np.abs(p["energy_balance_residual"]))) < 1e-4 * float(
        p["work_excitation"].max())


def test_excitation_filter_end_effect_is_bounded(kernel_hydro, kernel_rad):
    """A record cut out of a longer sea: inside [valid_start, valid_end] the filtered torque
    equals the exact one within 1e-4 of its amplitude, and so does the motion it drives."""
    from flumekit.hydro.excitation import excitation_torque, transfer_function

    length, dt = 200.0, 0.05
    ws = 2 * np.pi * np.array([53, 61, 70, 88]) / length  # whole periods: zero-mean record
    amp = np.array([0.03, 0.05, 0.02, 0.01]) * np.exp(1j * np.array([0.3, 2.0, 4.1, 5.5]))
    t = np.arange(0.0, length, dt)
    eta = xr.DataArray(np.real(np.exp(-1j * np.outer(t, ws)) @ amp), dims="time",
                       coords={"time": t})
    exact = np.real(np.exp(-1j * np.outer(t, ws)) @ (transfer_function(kernel_hydro, ws) * amp))
    for taper in (0.0, 2.0):
        tq = excitation_torque(eta, kernel_hydro, taper=taper)
        lo, hi = tq.attrs["valid_start"], tq.attrs["valid_end"]
        assert lo <= 10.0 and hi >= length - 10.0  # a few seconds of this filter's spread
        inside = (t >= lo) & (t <= hi)
        err = np.abs(tq.values - exact)
        assert err[inside].max() < 1e-4 * np.abs(exact).max()
        assert err[t > hi].max() > 1e-3 * np.abs(exact).max()  # the bound is not vacuous
    # the simulator driven by the record against the exact torque, to valid_end
    run = S.simulate(kernel_hydro, 14.74, S.LinearPTO(150.0), S.MeasuredWave(eta, taper=2.0),
                     dt=dt, radiation=kernel_rad)
    ref = S.simulate(kernel_hydro, 14.74, S.LinearPTO(150.0),
                     xr.DataArray(exact, dims="time", coords={"time": t}), dt=dt,
                     radiation=kernel_rad)
    hi = run.attrs["valid_end"]
    lo = run.attrs["valid_start"]
    keep = (run["time"].values <= hi) & (run["time"].values >= lo)
    diff = np.abs(run["theta"].values - ref["theta"].values)[keep]
    # the torque difference before valid_start (the start taper) decays through the dynamics
    late = run["time"].values[keep] > lo + 40.0
    assert diff[late].max() < 1e-4 * float(np.abs(ref["theta"]).max())


def test_decimated_long_run_memory_is_bounded(kernel_hydro, kernel_rad):
    """Output every 1 s of a 3e4-step run (two chunks): the peak allocation stays that of one
    chunk (< 30 MB; a 1e5 s run is measured by flumekit.bench.simulator)."""
    rad = kernel_rad
    tracemalloc.start()
    ds = S.simulate(kernel_hydro, 14.74, S.LinearPTO(150.0), S.RegularWave(0.1, 3.5, ramp=7.0),
                    dt=0.1, duration=3000.0, radiation=rad, output_step=1.0)
    peak = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    assert ds.sizes["time"] == 3001
    assert peak < 30e6, peak
    full = S.simulate(kernel_hydro, 14.74, S.LinearPTO(150.0), S.RegularWave(0.1, 3.5, ramp=7.0),
                      dt=0.1, duration=300.0, radiation=rad)
    np.testing.assert_array_equal(full["theta"].values[::10], ds["theta"].values[:301])
    np.testing.assert_allclose(full["work_pto"].values[::10], ds["work_pto"].values[:301],
                               rtol=1e-12)
