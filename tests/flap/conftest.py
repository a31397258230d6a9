"""Fixtures of the flap tests: the default campaign and virtual-flume flap records."""

from __future__ import annotations

import functools

import numpy as np
import pytest

from flumekit.waves.theory import stokes2_coefficient, wavenumber

DEPTH = 0.825
#: the default flap in the default flume: the hydrodynamics stage's geometry parameters
GEOMETRY = {"depth": DEPTH, "flap_width": 1.31, "hinge_height": 0.10, "channel_width": 1.5,
            "stiffness": 605.0, "inertia": 14.74, "thickness": 0.17}


def ramped_wave(time: np.ndarray, period: float, height: float, ramp_periods: float = 8.0,
                delay: float = 5.0) -> np.ndarray:
    """Second-order Stokes wave at x = 0 with a half-cosine ramp starting at ``delay`` [s]."""
    omega = 2 * np.pi / period
    k = float(wavenumber(omega, DEPTH))
    a = height / 2
    tau = np.clip((time - delay) / (ramp_periods * period), 0.0, 1.0)
    env = 0.5 - 0.5 * np.cos(np.pi * tau)
    ph = omega * (time - delay)
    return env * (a * np.cos(ph) + float(stokes2_coefficient(k, DEPTH)) * k * a**2 * np.cos(2 * ph))


@functools.lru_cache(maxsize=1)
def _hydrodynamics(campaign):
    from flumekit.synth.flap import flume_hydrodynamics

    return flume_hydrodynamics(campaign)


@functools.lru_cache(maxsize=8)
def _record(campaign, period: float, height: float, n_waves: int, seed: int, model: str):
    from flumekit.synth.flap import FlapTruth, flap_record

    time = np.arange(int((5.0 + n_waves * period) * 100)) / 100.0
    eta = ramped_wave(time, period, height)
    lead_out = ramped_wave(time[-1] + np.arange(1, 2001) / 100.0, period, height)  # 20 s
    return time, eta, flap_record(time, eta, period=period, campaign=campaign,
                                  rng=np.random.default_rng(seed), height=height,
                                  truth=FlapTruth(model=model),
                                  hydro=_hydrodynamics(campaign) if model != "linear" else None,
                                  eta_lead_out=lead_out)


@pytest.fixture(scope="session")
def hydrodynamics(campaign):
    """The simulator's Renzi-Dias container and radiation model for the flume (built once)."""
    return _hydrodynamics(campaign)


@pytest.fixture(scope="session")
def record(campaign):
    """record(period, height, n_waves=45, seed=7, model="simulator") -> (time, eta, truth
    dataset); cached."""

    def make(period: float, height: float, n_waves: int = 45, seed: int = 7,
             model: str = "simulator"):
        return _record(campaign, period, height, n_waves, seed, model)

    return make


@pytest.fixture(scope="session")
def geometry():
    """The default flap's geometry parameters of the hydrodynamics stage (a copy)."""
    return dict(GEOMETRY)


@pytest.fixture(scope="session")
def hydro(tmp_path_factory):
    """The coefficient container of the default flap, through the stage: the file the
    comparison reads."""
    from flumekit.io.netcdf import read_dataset
    from flumekit.stages import models as stage

    out = tmp_path_factory.mktemp("hydro") / "hydro.nc"
    params = {**GEOMETRY, **{k: stage.DEFAULTS[k] for k in
                             ("coefficients", "omega_min", "omega_max", "n_omega",
                              "irf_duration")}}
    stage.hydro({}, {"dataset": out}, params)
    return read_dataset(out)
