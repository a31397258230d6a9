"""Clock check with one run per wave condition: a 0.3 s offset between the probes
and the flap of a run alone in its condition is found from the neighbouring conditions.

Runs of nine conditions (T = 2.75, 3.0, 3.25 s; H = 0.15, 0.2, 0.25 m), one run each, are written as
raw files here: a regular wave at the probe nearest the flap and an encoder that follows it
with a lag that varies smoothly with T and H (as the virtual flume's does: 0.24-0.45 of a
period over Table 1; the fit predicts it there within 10 ms, flumekit/qc/clock.py). The flap
clock of T = 3.0 s, H = 0.2 m runs 0.3 s late. The qc stage's actions read them, the summary
reports the departure, and warns naming that run only.
"""

import re

import numpy as np
import pytest
import xarray as xr

from flumekit.io.tables import write_table
from flumekit.qc.clock import clock_departures
from flumekit.stages import qc as qc_stage

PROBES = ["WP1", "WP2", "WP3"]
CONDITIONS = [(t, h) for t in (2.75, 3.0, 3.25) for h in (0.15, 0.2, 0.25)]
SHIFTED = (3.0, 0.2)
OFFSET = 0.3  # [s]


def lag_law(t, h):
    """Smooth lag of the flap behind the nearest probe [s] (shape of the virtual flume's)."""
    return t * (0.1 + 0.08 * t + 0.25 * h)


def _run(tmp_path, t_wave, h, shift, seed):
    rng = np.random.default_rng(seed)
    d = tmp_path / f"T{t_wave}_H{h}"
    d.mkdir()
    t = np.arange(int(90 * 25)) / 25.0
    ramp = np.clip(t / 15.0, 0, 1)
    probes = [2.5 + 10 * h / 2 * ramp * np.sin(2 * np.pi * (t + 0.2 * j) / t_wave)
              + 0.005 * rng.standard_normal(t.size) for j in range(3)]
    write_table(d / "probes.csv", [("time", "s")] + [(p, "V") for p in PROBES],
                np.column_stack([t] + probes))
    tf = np.arange(int(90 * 100)) / 100.0
    # the encoder follows WP3 (x = -1 m, nearest the flap), lag_law later; its clock is late
    # by `shift`: the sample stamped tf was taken at tf - shift
    ts = tf - shift
    enc = np.round(800 * np.clip(ts / 15.0, 0, 1)
                   * np.sin(2 * np.pi * (ts + 0.4 - lag_law(t_wave, h)) / t_wave))
    pres = 2000 * np.clip(ts / 15.0, 0, 1) * np.cos(2 * np.pi * ts / t_wave) \
        + 5 * rng.standard_normal(tf.size)
    write_table(d / "flap.csv", [("time", "s"), ("encoder", "counts"), ("pressure", "Pa")],
                np.column_stack([tf, enc, pres]), fmt=["%.4f", "%d", "%.3f"])
    (d / "run.toml").write_text(f"[run]\nperiod = {t_wave}\nheight = {h}\n")
    return d


def _params(t_wave, h, name):
    return {**qc_stage.DEFAULTS, "run": name, "period": t_wave, "height": h, "repeat": 0,
            "uvp_elevation": None, "kind": "waves", "probes": PROBES, "sampling_rate": 25.0,
            "probe_x": {"WP1": -3.0, "WP2": -2.0, "WP3": -1.0}}


def test_offset_of_a_single_run_condition_is_found_from_the_neighbouring_conditions(tmp_path):
    inputs = {}
    for k, (t_wave, h) in enumerate(CONDITIONS):
        name = f"T{t_wave:.2f}_H{h:.3f}_r0"
        d = _run(tmp_path, t_wave, h, OFFSET if (t_wave, h) == SHIFTED else 0.0, k)
        out_p, out_f = tmp_path / f"p_{name}.nc", tmp_path / f"f_{name}.nc"
        qc_stage.probes({"probes": d / "probes.csv", "run": d / "run.toml"},
                        {"dataset": out_p}, _params(t_wave, h, name))
        qc_stage.flap({"flap": d / "flap.csv"}, {"dataset": out_f},
                      {**_params(t_wave, h, name), "sampling_rate": 100.0})
        inputs[f"probes/{name}"], inputs[f"flap/{name}"] = out_p, out_f
    summary = tmp_path / "summary.nc"
    # the wave condition of each run, as the qc_summary rule passes it from the campaign
    conditions = {f"T{t:.2f}_H{h:.3f}_r0": [t, h] for t, h in CONDITIONS}
    qc_stage.summary(inputs, {"dataset": summary},
                     {"clock_tolerance": 0.05, "conditions": conditions})
    with xr.open_dataset(summary) as s:
        dep = dict(zip(s.run.values.tolist(), s.clock_departure.values.tolist(), strict=True))
        warned = s.attrs.get("flumekit_warnings", "")
        reference = s.attrs["clock_reference"]
    shifted = f"T{SHIFTED[0]:.2f}_H{SHIFTED[1]:.3f}_r0"
    # the flap's stamps are 0.3 s late: 0.3 s is to be subtracted from them
    assert dep[shifted] == pytest.approx(-OFFSET, abs=0.02)
    assert f"{shifted}: fit over" in reference
    checked = {k: v for k, v in dep.items() if k != shifted and np.isfinite(v)}
    assert checked and all(abs(v) < 0.02 for v in checked.values())
    assert f"run {shifted}" in warned
    declared = float(re.search(r"\[clock\] flap = (-?[0-9.]+)", warned).group(1))
    assert declared == pytest.approx(-OFFSET, abs=0.02)  # the value that undoes the offset
    assert warned.count("clock offset") == 1


def test_fit_reference_rejects_another_runs_offset_and_never_extrapolates_in_period():
    t = np.repeat([2.0, 2.25, 2.5, 2.75, 3.0], 3)
    h = np.tile([0.15, 0.2, 0.25], 5)
    lags = lag_law(t, h)
    lags[4] += OFFSET  # T = 2.25 s, H = 0.2 m
    d, basis = clock_departures(lags, t, h)
    # the fit is linear in T over the neighbouring periods: the law's curvature costs 5 ms
    assert d[4] == pytest.approx(OFFSET, abs=0.01)
    checked = np.delete(d, 4)
    assert np.nanmax(np.abs(checked)) < 0.01  # the offset run left out of the other fits
    assert np.isfinite(checked).sum() >= 6
    # T = 2.0 s has no period below it and too few conditions at and above it to check a fit
    assert np.isnan(d[0]) and basis[0].startswith("no reference")
    lone = clock_departures(np.array([1.0]), np.array([3.0]), np.array([0.2]))
    assert np.isnan(lone[0][0]) and lone[1][0].startswith("no reference")
