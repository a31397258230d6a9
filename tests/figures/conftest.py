"""Small datasets in the shape of the pipeline's processed data, for the figure tests.

Built in a few seconds: waves from the virtual flume's regular-wave field, the velocity field
from its analytic truth, the ball-screw datasets from the models on coarse grids, and flap /
comparison datasets from analytic sinusoids (the figure test checks layout, labels and sizes,
not the physics).
"""

from __future__ import annotations

import numpy as np
import pytest
import xarray as xr

from flumekit import conventions

DEPTH = 0.825


def _run_coords(ds, period, height, kind="T"):
    run = f"T{period:.2f}_H{height:.3f}_r0"
    return ds.assign_coords(run=run, wave_period=period, wave_height=height, repeat=0)


@pytest.fixture(scope="session")
def waves(regular_waves):
    return _run_coords(regular_waves, 2.0, 0.15)


def _ramp(t, period, start=5.0, n=8):
    tau = np.clip((t - start) / (n * period), 0, 1)
    return 0.5 - 0.5 * np.cos(np.pi * tau)


def flap_run(period: float, height: float, n_waves: int = 80) -> xr.Dataset:
    """A flap dataset with every variable the flap figures read: a ramped oscillation about a
    seaward lean, a chamber pressure clamped on its suction side."""
    w = 2 * np.pi / period
    t = np.arange(int(n_waves * period * 50)) / 50.0
    env = _ramp(t, period)
    theta = env * (-0.05 + 0.3 * np.sin(w * t))
    theta_dot = np.gradient(theta, t)
    pressure = env * np.maximum(4e5 * np.sin(w * t + 0.3), -0.8e5)
    phase = np.arange(100) / 100
    ph = 2 * np.pi * phase
    start = 20 * period
    ds = xr.Dataset(
        {"theta": ("time", theta), "theta_dot": ("time", theta_dot),
         "chamber_pressure": ("time", pressure),
         "torque_pressure": ("time", 1e-3 * pressure),
         "torque_pressure_fitted": ("time", 1e-3 * pressure * 1.01),
         "power": ("time", 100 * theta_dot**2),
         "theta_phase_mean": ("phase", -0.05 + 0.3 * np.sin(ph)),
         "theta_dot_phase_mean": ("phase", 0.3 * w * np.cos(ph)),
         "chamber_pressure_phase_mean": ("phase", np.maximum(4e5 * np.sin(ph + 0.3), -0.8e5)),
         "power_phase_mean": ("phase", 100 * (0.3 * w * np.cos(ph)) ** 2),
         "theta_amplitude": ((), 0.3 + 0.1 * height), "torque_amplitude": ((), 2e3 * height),
         "mean_power": ((), 5.0 * height), "incident_height": ((), height),
         "incident_power": ((), 40.0 * height), "capture_factor": ((), 0.3 + period / 20),
         "pressure_fit_r2": ((), 0.98), "steady_start": ((), start),
         "steady_end": ((), start + 40 * period), "measured_period": ((), period),
         "steady_cycles": ((), 40)},
        coords={"time": t, "phase": phase})
    return _run_coords(conventions.annotate(ds), period, height)


def comparison_run(flap: xr.Dataset) -> xr.Dataset:
    """A comparison dataset (experiment, analytical, simulator along ``source``)."""
    scale = xr.DataArray([1.0, 1.3, 0.95], dims="source",
                         coords={"source": ["experiment", "analytical", "simulator"]})
    names = ("theta_amplitude", "torque_amplitude", "mean_power", "capture_factor",
             "theta_phase_mean", "theta_dot_phase_mean", "power_phase_mean")
    ds = xr.Dataset({n: flap[n] * scale for n in names})
    for n in ("incident_height", "measured_period", "incident_power"):
        ds = ds.assign_coords({n: flap[n]})
    return ds


@pytest.fixture(scope="session")
def flaps():
    return [flap_run(p, h) for p in (2.0, 3.0, 3.5) for h in (0.15, 0.25)]


@pytest.fixture(scope="session")
def field(campaign):
    from flumekit.synth.uvp import true_field

    f = true_field(campaign, period=3.5, height=0.25, reflection=0.2, reflection_phase=0.6)
    f.attrs.update(water_depth=campaign.flume.water_depth, n_runs=7)
    return f.assign_coords(wave_period=3.5, wave_height=0.25)


@pytest.fixture(scope="session")
def ballscrew():
    from flumekit.ballscrew import buoy, screw
    from flumekit.ballscrew.thermal.fem import thermal_fem
    from flumekit.ballscrew.thermal.lumped import thermal_lumped

    kin = buoy.kinematics(buoy.reference_motion(1.0, 3.8, samples_per_period=190))
    eff = screw.efficiency(kin)
    eff.attrs["wave_period"] = 3.8
    lumped = thermal_lumped(eff, cycle_duration=600.0, total_duration=1200.0, time_step=1.0)
    fem = thermal_fem(lumped, time_step=60.0, radial_cell_size=0.02, axial_cell_size=0.1,
                      snapshot_times=(300.0, 600.0, 900.0, 1200.0))
    return {"efficiency": eff, "thermal_lumped": lumped, "thermal_fem": fem}
