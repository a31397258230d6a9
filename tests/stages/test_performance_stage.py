"""The power-matrix stage: its rule, default edges from the targets, and the product."""

import numpy as np
import pytest
import xarray as xr

from flumekit.io.netcdf import read_dataset
from flumekit.performance.matrix import edges_around, target_te
from flumekit.stages import performance as stage

SOURCES = ["experiment", "analytical", "simulator"]


def test_target_te_of_a_jonswap():
    # gamma = 3.3: Te / Tp = 0.90 in IEC TS 62600-101 (two digits: within 1 %); declared: as is
    assert target_te({"tp": 2.0, "gamma": 3.3}) == pytest.approx(2.0 * 0.90, rel=0.01)
    assert target_te({"tp": 2.0, "gamma": None}) == target_te({"tp": 2.0, "gamma": 3.3})
    assert target_te({"tp": 2.0, "te": 1.7}) == 1.7


def test_pierson_moskowitz_ratio_is_exact():
    # gamma = 1: S ~ f^-5 exp(-B f^-4), B = 5/4 fp^4, m_n = B^((n-4)/4) Gamma(1 - n/4) / 4,
    # so Te fp = m_-1 / m0 fp = Gamma(5/4) (4/5)^(1/4)
    from math import gamma as Gamma

    exact = Gamma(1.25) * 0.8**0.25
    assert target_te({"tp": 1.0, "gamma": 1.0}) == pytest.approx(exact, rel=1e-4)


def test_edges_around_targets():
    assert edges_around([0.1, 0.05, 0.1]) == pytest.approx([0.025, 0.075, 0.125])
    assert edges_around([2.0]) == pytest.approx([1.8, 2.2])


def _write(path, ds):
    path.parent.mkdir(parents=True, exist_ok=True)
    ds.to_netcdf(path)


def test_build_bins_the_runs(tmp_path):
    # four runs, two sea states (two repeats each); the experiment from the flap products,
    # the models from the comparisons
    rng = np.random.default_rng(1)
    runs = ["a", "b", "c", "d"]
    hm0 = [0.051, 0.049, 0.101, 0.098]
    te = [1.52, 1.49, 2.21, 2.18]
    inputs, power = {}, {}
    for i, r in enumerate(runs):
        p = rng.uniform(1, 5, 3)
        power[r] = p
        j = 20.0 + i
        _write(tmp_path / f"waves/{r}.nc", xr.Dataset({"hm0": hm0[i], "te": te[i]}))
        _write(tmp_path / f"flap/{r}.nc", xr.Dataset({"mean_power": p[0],
                                                      "capture_width": p[0] / j,
                                                      "capture_width_ratio": p[0] / j / 1.31}))
        _write(tmp_path / f"comparison/{r}.nc", xr.Dataset(
            {"mean_power": ("source", [99.0, *p[1:]]),  # the experiment row is not read here
             "capture_width": ("source", [99.0, *(p[1:] / j)]),
             "capture_width_ratio": ("source", [99.0, *(p[1:] / j / 1.31)])},
            coords={"source": SOURCES}))
        for k in ("waves", "flap", "comparison"):
            inputs[f"{k}:{r}"] = tmp_path / f"{k}/{r}.nc"
    targets = [{"hm0": 0.05, "tp": None, "te": 1.5, "gamma": 3.3}] * 2 + \
        [{"hm0": 0.10, "tp": None, "te": 2.2, "gamma": 3.3}] * 2
    out = tmp_path / "power_matrix.nc"
    stage.build(inputs, {"dataset": out}, {"hm0_edges": None, "te_edges": None,
                                          "targets": targets, "runs": runs})
    ds = read_dataset(out)
    np.testing.assert_allclose(ds.hm0_bin_bounds, [[0.025, 0.075], [0.075, 0.125]])
    np.testing.assert_allclose(ds.te_bin_bounds, [[1.15, 1.85], [1.85, 2.55]])
    np.testing.assert_array_equal(ds.run_count, [[2, 0], [0, 2]])
    for cell, pair in (((0, 0), ("a", "b")), ((1, 1), ("c", "d"))):
        vals = np.array([power[r] for r in pair])
        np.testing.assert_allclose(ds.mean_power.values[cell], vals.mean(0), rtol=1e-12)
        np.testing.assert_allclose(ds.mean_power_std.values[cell], vals.std(0, ddof=0),
                                   rtol=1e-9)
    assert np.all(np.isnan(ds.capture_width_ratio.values[0, 1]))
    np.testing.assert_allclose(ds.run_mean_power.sel(run="c"), power["c"])
    assert list(ds.source.values) == SOURCES and int(ds.runs_outside) == 0


def test_no_rule_without_irregular_runs():
    class Campaign:
        runs = []

    class Ctx:
        campaign = Campaign()

    assert stage.rules(Ctx(), stage.DEFAULTS) == []


def test_runs_outside_the_given_edges_are_said(tmp_path):
    runs = ["a", "b"]
    inputs = {}
    for r, h in zip(runs, (0.05, 0.3)):
        _write(tmp_path / f"waves/{r}.nc", xr.Dataset({"hm0": h, "te": 2.0}))
        _write(tmp_path / f"flap/{r}.nc", xr.Dataset({"mean_power": 1.0, "capture_width": 0.1,
                                                      "capture_width_ratio": 0.1}))
        _write(tmp_path / f"comparison/{r}.nc", xr.Dataset(
            {n: ("source", [1.0, 1.0]) for n in ("mean_power", "capture_width",
                                                  "capture_width_ratio")},
            coords={"source": ["experiment", "analytical"]}))
        for k in ("waves", "flap", "comparison"):
            inputs[f"{k}:{r}"] = tmp_path / f"{k}/{r}.nc"
    out = tmp_path / "power_matrix.nc"
    with pytest.warns(UserWarning, match=r"1 run\(s\) outside the bins.*b \(Hm0 0.3 m"):
        stage.build(inputs, {"dataset": out}, {"hm0_edges": [0.0, 0.1, 0.2],
                                              "te_edges": [1.0, 3.0], "targets": [],
                                              "runs": runs})
    ds = read_dataset(out)
    assert int(ds.runs_outside) == 1 and "b (Hm0 0.3 m" in ds.attrs["runs_outside_the_bins"]
