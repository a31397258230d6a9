"""Monte Carlo and linear propagation through the waves analysis; the declared components."""

from __future__ import annotations

import numpy as np
import pytest
import xarray as xr

from flumekit.campaign import Component, load_campaign, uncertainty_components
from flumekit.synth.waves import regular_wave_field
from flumekit.uncertainty.propagation import (
    Input,
    RunModel,
    linear,
    monte_carlo,
    propagate,
    resolve_inputs,
)

DEPTH, PERIOD, HEIGHT = 0.825, 1.5, 0.08
X = np.array([-3.0, -2.6, -1.8])
WAVES_KW = {"x_ref": 0.0, "amplitude_dispersion": False}


@pytest.fixture(scope="module")
def clean():
    t = np.arange(int(110 * 25)) / 25.0
    f = regular_wave_field(t, X, period=PERIOD, height=HEIGHT, depth=DEPTH, reflection=0.2,
                           ramp_waves=5, second_order=False, x_wavemaker=-20.0)
    return xr.DataArray(f["eta"].values, dims=("probe", "time"),
                        coords={"probe": ["A", "B", "C"], "time": t, "x": ("probe", X)})


def _noisy(clean, rng, sigma):
    return clean.copy(data=clean.values + sigma * rng.standard_normal(clean.shape))


def test_monte_carlo_of_probe_noise_matches_the_spread_of_independent_records(clean):
    # the truth of the noise's effect: the analysis of independent noisy records of one wave
    sigma, n = 1.0e-3, 80
    rng = np.random.default_rng(1)
    spread = np.array([RunModel(_noisy(clean, rng, sigma), DEPTH, PERIOD, WAVES_KW)({})
                       for _ in range(n)]).std(axis=0, ddof=1)
    model = RunModel(_noisy(clean, rng, sigma), DEPTH, PERIOD, WAVES_KW)
    mc = monte_carlo(model, [Input("probe_noise", sigma, "m", "normal", "test")], n, 3)
    u = mc.std(axis=0, ddof=1)
    # two standard deviations from 80 samples each: relative sampling error ~8 % each, so
    # 30 % is beyond 2.5 standard deviations of their ratio
    for j, q in enumerate(model.results[:2]):  # H_I and Kr
        assert u[j] == pytest.approx(spread[j], rel=0.3), q


def test_draws_are_seeded_and_nested(clean):
    model = RunModel(_noisy(clean, np.random.default_rng(2), 5e-4), DEPTH, PERIOD, WAVES_KW)
    inputs = [Input("probe_noise", 5e-4, "m", "normal", "t"),
              Input("water_depth", 2e-3, "m", "rectangular", "t")]
    a = monte_carlo(model, inputs, 6, [7, 1])
    b = monte_carlo(model, inputs, 3, [7, 1])
    np.testing.assert_array_equal(a[:3], b)  # the first draws of a larger sample
    np.testing.assert_array_equal(a, monte_carlo(model, inputs, 6, [7, 1]))
    assert not np.array_equal(a, monte_carlo(model, inputs, 6, [7, 2]))


def test_linear_agrees_with_monte_carlo_for_a_smooth_input(clean):
    # depth and probe positions: smooth in Kr and H_I, so GUM's first order holds
    model = RunModel(clean, DEPTH, PERIOD, WAVES_KW)
    inputs = [Input("water_depth", 5e-3, "m", "normal", "t"),
              Input("probe_position", 2e-3, "m", "normal", "t")]
    ds = propagate(model, inputs, draws=150, seed=4, directions=1)
    for q in ("incident_height", "reflection_coefficient"):
        # 150 draws: 6 % sampling error of the MC standard deviation
        assert float(ds[f"{q}_uncertainty_linear"]) == pytest.approx(
            float(ds[f"{q}_uncertainty_type_b"]), rel=0.2), q
        assert ds[f"{q}_contribution"].sum() == pytest.approx(100.0)
        assert f"{q}_uncertainty_type_b" in ds[q].attrs["ancillary_variables"]
    k = ds.incident_height_expanded_uncertainty.attrs["coverage_factor"]
    assert k == pytest.approx(1.976, abs=2e-3)  # t_0.975 with 149 degrees of freedom
    # the sensitivity is per unit of the input (central difference over +-u, here by hand)
    lo = model({"water_depth": np.array(-5e-3)})
    hi = model({"water_depth": np.array(5e-3)})
    c = (hi - lo) / 1e-2
    assert float(ds.incident_height_sensitivity.sel(uncertainty_component="water_depth")) == \
        pytest.approx(abs(c[0]), rel=1e-12)


def test_linear_position_sensitivity_is_root_sum_square_over_probes(clean):
    model = RunModel(clean, DEPTH, PERIOD, WAVES_KW)
    sens, contrib = linear(model, [Input("probe_position", 1e-3, "m", "normal", "t")], 1, 0)
    one = [model({"probe_position": np.eye(3)[j] * 1e-3}) - model(
        {"probe_position": -np.eye(3)[j] * 1e-3}) for j in range(3)]
    expect = np.sqrt(np.sum((np.array(one) / 2) ** 2, axis=0))
    np.testing.assert_allclose(contrib[0], expect, rtol=1e-12)


def test_defaults_from_the_calibration_residuals():
    rng = np.random.default_rng(5)
    levels = np.repeat([-0.1, -0.05, 0.0, 0.05, 0.1], 200)
    volts = 2.0 + 10.0 * (levels[:, None] + 5e-4 * rng.standard_normal((levels.size, 2)))
    from flumekit.waves import calibration

    cal = calibration.fit(volts, levels=levels).assign(
        calibration_voltage=(("sample", "probe"), volts))
    got = {i.name: i for i in resolve_inputs(uncertainty_components(None), calibration=cal,
                                             counts_per_metre=6000.0)}
    res = cal.calibration_residual.values
    assert got["probe_noise"].u == pytest.approx(np.sqrt(np.mean(res ** 2)), rel=1e-12)
    for p in range(2):  # numpy's covariance of the fitted slope (level on volts)
        coef, cov = np.polyfit(volts[:, p], levels, 1, cov=True)
        assert got["calibration"].u[p] == pytest.approx(np.sqrt(cov[0, 0]) / coef[0],
                                                        rel=1e-6)
    assert got["encoder_resolution"].u == pytest.approx(0.5 / 6000 / np.sqrt(3), rel=1e-12)
    assert got["pressure_accuracy"].u == pytest.approx(0.002 * 1e6) \
        and got["pressure_accuracy"].units == "Pa"
    assert "uvp_velocity_resolution" not in got
    with pytest.warns(UserWarning, match="probe_noise.*left out"):
        left = resolve_inputs(uncertainty_components(None))
    assert "probe_noise" not in {i.name for i in left}


def test_rectangular_component_standard_uncertainty():
    c = Component("probe_resolution", 3e-4, "rectangular", True)
    assert c.standard_uncertainty == pytest.approx(3e-4 / np.sqrt(3), rel=1e-15)
    assert Component("water_depth", 2e-3, "normal", True).standard_uncertainty == 2e-3


def test_campaign_uncertainty_table(tmp_path):
    from importlib import resources

    import flumekit

    src = (resources.files("flumekit") / "data" / "default_campaign.toml").read_text()
    (tmp_path / "campaign.toml").write_text(
        src + "\n[uncertainty.water_depth]\nvalue = 0.002\ndistribution = \"rectangular\"\n"
              "[uncertainty.pressure_accuracy]\nrated_output = 5e5\n")
    c = {x.name: x for x in load_campaign(tmp_path).uncertainty}
    assert (c["water_depth"].value, c["water_depth"].distribution, c["water_depth"].declared) \
        == (0.002, "rectangular", True)
    assert c["pressure_accuracy"].rated_output == 5e5 and c["pressure_accuracy"].value == 0.002
    assert c["probe_position"].value == 1e-3 and not c["probe_position"].declared
    (tmp_path / "campaign.toml").write_text(
        src + "\n[uncertainty.water_depth]\ndistribution = \"triangle\"\n"
              "[uncertainty.probe_nosie]\nvalue = 1e-3\n")
    with pytest.raises(flumekit.InputError) as e:
        load_campaign(tmp_path)
    assert "uncertainty.water_depth.distribution" in str(e.value)
    assert "probe_noise" in str(e.value)  # the typo's suggestion


def test_draws_uncertainty_is_the_spread_about_the_unperturbed_result():
    from flumekit.uncertainty.propagation import draws_uncertainty

    rng = np.random.default_rng(4)
    noise = rng.normal(0.0, 1.0, (4000, 1))
    # a result linear in the errors: its draws centre on it, u is their standard deviation
    linear = draws_uncertainty(5.0 + 0.2 * noise, np.array([5.0]))
    assert linear[0] == pytest.approx(0.2, rel=0.03)
    # a nonlinear one whose draws shift by 0.3 from it: u = sqrt(0.2² + 0.3²) = 0.36
    shifted = draws_uncertainty(5.3 + 0.2 * noise, np.array([5.0]))
    assert shifted[0] == pytest.approx(np.hypot(0.2, 0.3), rel=0.03)
    assert np.isnan(draws_uncertainty(noise[:1], np.array([0.0]))[0])


def test_variants_are_analysed_as_runs(clean):
    # the propagation's batched path gives each variant what analyse_run gives it, bit for
    # bit: its own window, the same separation passes (with amplitude dispersion), the
    # refusal of a record without steady waves as NaN
    from flumekit.waves import analyse_run
    from flumekit.waves.analysis import VARIANT_RESULTS, variant_results

    rng = np.random.default_rng(5)
    noisy = _noisy(clean, rng, 5e-4)
    moved = noisy.assign_coords(x=("probe", X + [1e-3, -2e-3, 0.0]))
    flat = clean.copy(data=np.zeros(clean.shape))
    variants, depths = [noisy, moved, flat, clean], [DEPTH, DEPTH, DEPTH, DEPTH + 0.01]
    r = variant_results(variants, depths, PERIOD, x_ref=0.0)
    assert np.isnan([r[k][2] for k in VARIANT_RESULTS]).all()
    for i in (0, 1, 3):
        ds = analyse_run(variants[i], depths[i], PERIOD, x_ref=0.0)
        for k in VARIANT_RESULTS:
            assert r[k][i] == float(ds[k]), (i, k)
    assert r["incident_height"][1] != r["incident_height"][0]
