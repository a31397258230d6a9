"""The whole pipeline against the virtual flume's known truth (small campaign, built once).

Tolerances are the acceptance points of issues 2-5: probe gains/offsets 0.1 %; Kr ±0.005 and
H_I 0.5 %; theta 0.05° RMS, theta_dot 2 % and T_h 3 % RMS of their amplitudes, K_p and I_p 2 %,
C_f 2 %; UVP <u>, <w> within 2 % of U0 RMS over the field; and those of the irregular-seas
issue for the irregular run (flumekit.bench.truth.TOLERANCE).
"""

import shutil
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from flumekit.bench import truth as checks
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


def runs(truth):
    """The regular runs (the errors and tolerances shared with the benchmarks)."""
    return [r for r in checks.runs(truth) if not checks.irregular(truth, r)]


def test_calibration_recovers_probe_gains_and_offsets(built):
    for name, error in checks.calibration_errors(*built).items():
        assert checks.within(name, error), (name, error)


def test_separation_recovers_reflection_and_incident_height(built):
    processed, truth = built
    for run in runs(truth):
        for name, error in checks.waves_errors(processed, truth, run).items():
            assert checks.within(name, error), (run, name, error)


def _rms(a, b, mask):
    return float(np.sqrt(np.mean((a[mask] - b[mask]) ** 2)))


def test_flap_motion_torque_and_power_against_truth(built):
    processed, truth = built
    for run in runs(truth):
        # theta RMS and C_f (against the true mean power over the same window, W_I from the
        # true height, Eq. A2)
        for name, error in checks.flap_errors(processed, truth, run).items():
            assert checks.within(name, error), (run, name, error)
        with xr.open_dataset(processed / "flap" / f"{run}.nc", decode_times=False) as f, \
                xr.open_dataset(truth / run / "flap.nc", decode_times=False) as t:
            win = checks.steady_window(f)
            for name, tol in (("theta_dot", 0.02), ("torque_hydrodynamic", 0.03)):
                amp = 0.5 * np.ptp(t[name].values[win])
                assert _rms(f[name].values, t[name].values, win) < tol * amp, (run, name)
            # the flume's chamber pressure holds a check-valve term Eq. (13) cannot represent:
            # the stage's target is the best Eq. (13) fit to the noise-free truth
            assert float(f.pressure_loss_coefficient) == pytest.approx(
                t.attrs["eq13_pressure_loss_coefficient"], rel=0.02)
            assert float(f.fluid_inertia) == pytest.approx(t.attrs["eq13_fluid_inertia"],
                                                           rel=0.02)


def test_irregular_run_against_truth(built):
    """Incident Hm0 and Te at the flap within 2 %, Tp 5 %, bulk Kr ±0.02, Kr(f) ±0.05 over the
    band of 90 % of the incident energy, mean absorbed power and capture width ratio 5 %, against
    the truth of the span the pipeline analysed."""
    processed, truth = built
    irregular = [r for r in checks.runs(truth) if checks.irregular(truth, r)]
    assert irregular
    for run in irregular:
        for name, error in checks.irregular_errors(processed, truth, run).items():
            assert checks.within(name, error), (run, name, error)


def test_uvp_field_against_truth(built):
    for name, e in checks.uvp_field_errors(*built).items():
        assert e["uvp_coverage"] > checks.TOLERANCE["uvp_coverage"], "most of the field is masked"
        assert checks.within("uvp_rms", e["uvp_rms"]), (name, e)


def test_experiment_simulator_and_linear_model_differ(built):
    """The virtual flume has losses the simulator and the linear model lack (vortex
    drag, overtopping, bearing friction, check valve), so the comparison shows three distinct
    curves, the experiment's motion below both models'. The simulator's numerics against a
    flume of its own physics are tested in tests/flap/test_flap_synth.py."""
    processed, truth = built
    for run in runs(truth):
        with xr.open_dataset(processed / "comparison" / f"{run}.nc", decode_times=False) as c:
            amp = c.theta_amplitude
            exp = float(amp.sel(source="experiment"))
            assert float(amp.sel(source="simulator")) > 1.2 * exp, run
            assert float(amp.sel(source="analytical")) > 1.2 * exp, run
            assert float(c.theta_relative_rms_difference) > 0.1, run


def test_main_condition_reproduces_the_papers_numbers(built):
    """The losses calibrated on this build's T = 3.5 s, H = 0.25 m run (its own repeat draw):
    the numbers Brito et al. (2020) state that the virtual flume reproduces, within the
    precision the paper gives them (flumekit.bench.flume.STATED; the full table, with the
    numbers it does not reach, is `flumekit bench flume`)."""
    from flumekit.bench.flume import MAIN_RUN, STATED, built_runs, measure

    processed, _ = built
    values, _ = measure({MAIN_RUN: built_runs(processed)[MAIN_RUN]})
    for key in ("theta_max", "theta_min", "cf", "kr", "r2_main", "steady_eta", "steady_theta"):
        lo, hi = STATED[key][2]
        assert lo <= values[key] <= hi, (key, values[key])
