"""The whole pipeline against the virtual flume's known truth (small campaign, built once).

Tolerances are the acceptance points of issues 2-5: probe gains/offsets 0.1 %; Kr ±0.005 and
H_I 0.5 %; theta 0.05° RMS, theta_dot 2 % and T_h 3 % RMS of their amplitudes, K_p and I_p 2 %,
C_f 2 %; UVP <u>, <w> within 2 % of U0 RMS over the field.
"""

import shutil
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from flumekit.cli import main

ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    from flumekit.synth.campaign import write_campaign

    project = tmp_path_factory.mktemp("project")
    shutil.copytree(ROOT / "pipelines", project / "pipelines")
    write_campaign(project / "raw" / "small", size="small", seed=11)
    code = main(["make", "--pipeline", str(project / "pipelines" / "small.toml"),
                 "calibration", "waves_summary", "flap_summary", "uvp_field",
                 "comparison_summary"])
    assert code == 0
    return project / "processed" / "small", project / "raw" / "small" / "truth"


def runs(truth: Path) -> list[str]:
    return sorted(p.name for p in truth.iterdir() if p.is_dir())


def test_calibration_recovers_probe_gains_and_offsets(built):
    processed, truth = built
    with xr.open_dataset(processed / "calibration.nc", decode_times=False) as cal, \
            xr.open_dataset(truth / "calibration.nc", decode_times=False) as true:
        np.testing.assert_allclose(cal.gain, true.gain, rtol=1e-3)
        np.testing.assert_allclose(cal.offset, true.offset, rtol=1e-3)


def test_separation_recovers_reflection_and_incident_height(built):
    processed, truth = built
    for run in runs(truth):
        with xr.open_dataset(processed / "waves" / f"{run}.nc", decode_times=False) as w, \
                xr.open_dataset(truth / run / "waves.nc", decode_times=False) as t:
            assert abs(float(w.reflection_coefficient) - t.attrs["reflection_coefficient"]) < 5e-3
            assert float(w.incident_height) == pytest.approx(t.attrs["wave_height"], rel=5e-3)


def _rms(a, b, mask):
    return float(np.sqrt(np.mean((a[mask] - b[mask]) ** 2)))


def test_flap_motion_torque_and_power_against_truth(built):
    processed, truth = built
    for run in runs(truth):
        with xr.open_dataset(processed / "flap" / f"{run}.nc", decode_times=False) as f, \
                xr.open_dataset(truth / run / "flap.nc", decode_times=False) as t:
            time = f.time.values
            win = (time >= float(f.steady_start)) & (time <= float(f.steady_end))
            assert np.degrees(_rms(f.theta.values, t.theta.values, win)) < 0.05
            for name, tol in (("theta_dot", 0.02), ("torque_hydrodynamic", 0.03)):
                amp = 0.5 * np.ptp(t[name].values[win])
                assert _rms(f[name].values, t[name].values, win) < tol * amp, (run, name)
            # the flume's chamber pressure holds a check-valve term Eq. (13) cannot represent:
            # the stage's target is the best Eq. (13) fit to the noise-free truth
            assert float(f.pressure_loss_coefficient) == pytest.approx(
                t.attrs["eq13_pressure_loss_coefficient"], rel=0.02)
            assert float(f.fluid_inertia) == pytest.approx(t.attrs["eq13_fluid_inertia"],
                                                           rel=0.02)
            # C_f: true mean power over the same window, W_I from the true height (Eq. A2)
            from flumekit.flap.power import incident_power

            w_i = incident_power(t.attrs["wave_height_target"], float(f.measured_period), 0.825,
                                 1.31)
            c_true = float(np.mean(t.power.values[win])) / float(w_i)
            assert float(f.capture_factor) == pytest.approx(c_true, rel=0.02), run


def test_uvp_field_against_truth(built):
    processed, truth = built
    with xr.open_dataset(processed / "uvp_field.nc", decode_times=False) as f, \
            xr.open_dataset(truth / "uvp_field.nc", decode_times=False) as t:
        true = t.interp(z=f.z, x=f.x)
        u0 = float(t.velocity_scale)
        for name in ("u", "w"):
            err = (f[name] - true[name]).values
            ok = np.isfinite(err)
            assert ok.mean() > 0.3, "most of the field is masked"
            assert np.sqrt(np.mean(err[ok] ** 2)) < 0.02 * u0, name


def test_experiment_simulator_and_linear_model_differ(built):
    """Issue 16: the virtual flume has losses the simulator and the linear model lack (vortex
    drag, overtopping, bearing friction, check valve), so the comparison shows three distinct
    curves, the experiment's motion below both models'. The simulator's numerics against a
    flume of its own physics (issue 7) are tested in tests/flap/test_flap_synth.py."""
    processed, truth = built
    for run in runs(truth):
        with xr.open_dataset(processed / "comparison" / f"{run}.nc", decode_times=False) as c:
            amp = c.theta_amplitude
            exp = float(amp.sel(source="experiment"))
            assert float(amp.sel(source="simulator")) > 1.2 * exp, run
            assert float(amp.sel(source="analytical")) > 1.2 * exp, run
            assert float(c.theta_relative_rms_difference) > 0.1, run


def test_main_condition_reproduces_the_papers_numbers(built):
    """Issue 16 calibration, on this build's T = 3.5 s, H = 0.25 m run (its own repeat draw):
    the numbers Brito et al. (2020) state that the virtual flume reproduces, within the
    precision the paper gives them (flumekit.bench.flume.STATED; the full table, with the
    numbers it does not reach, is `flumekit bench flume`)."""
    from flumekit.bench.flume import MAIN_RUN, STATED, _runs, measure

    processed, _ = built
    values, _ = measure({MAIN_RUN: _runs(processed)[MAIN_RUN]})
    for key in ("theta_max", "cf", "kr", "r2_main"):
        lo, hi = STATED[key][2]
        assert lo <= values[key] <= hi, (key, values[key])
