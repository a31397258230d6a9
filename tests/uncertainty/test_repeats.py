"""Repeat statistics per condition and the combination with Type B (GUM 4.2, G.4)."""

from __future__ import annotations

import numpy as np
import pytest
import xarray as xr
from scipy import stats

from flumekit.uncertainty import condition_statistics
from flumekit.uncertainty.combine import combine


def _summary(rng):
    # two regular conditions (3 and 1 repeats), one irregular condition (2 repeats)
    period = [2.0, 2.0, 2.0, 3.5, np.nan, np.nan]
    height = [0.15, 0.15, 0.15, 0.25, np.nan, np.nan]
    hm0 = [np.nan] * 4 + [0.1, 0.1]
    tp = [np.nan] * 4 + [2.5, 2.5]
    h = rng.normal(0.15, 0.001, 6)
    kr = rng.normal(0.2, 0.01, 6)
    kr[1] = np.nan  # a run where the quantity is not defined
    hm = np.where(np.isnan(hm0), np.nan, rng.normal(0.1, 0.002, 6))
    return xr.Dataset({"incident_height": ("run", h), "reflection_coefficient": ("run", kr),
                       "hm0": ("run", hm)},
                      coords={"run": [f"r{i}" for i in range(6)], "wave_period": ("run", period),
                              "wave_height": ("run", height), "wave_hm0": ("run", hm0),
                              "wave_tp": ("run", tp), "wave_te": ("run", [np.nan] * 6)})


def test_statistics_match_an_independent_computation():
    rng = np.random.default_rng(4)
    s = _summary(rng)
    c = condition_statistics(s)
    assert c.sizes["condition"] == 3
    assert c.n_repeats.values.tolist() == [3, 1, 2]  # sorted: T 2, T 3.5, then irregular
    np.testing.assert_array_equal(c.wave_period.values[:2], [2.0, 3.5])
    assert np.isnan(c.wave_period.values[2]) and c.wave_hm0.values[2] == 0.1
    for cond, runs in ((0, [0, 1, 2]), (1, [3]), (2, [4, 5])):
        for q in ("incident_height", "reflection_coefficient", "hm0"):
            v = s[q].values[runs]
            v = v[np.isfinite(v)]
            got = c.isel(condition=cond)
            if v.size == 0:
                assert np.isnan(float(got[q]))
                continue
            assert float(got[q]) == pytest.approx(v.mean(), rel=1e-13)
            if v.size > 1:
                sd = np.sqrt(np.sum((v - v.mean()) ** 2) / (v.size - 1))
                assert float(got[f"{q}_std"]) == pytest.approx(sd, rel=1e-12)
                assert float(got[f"{q}_standard_error"]) == pytest.approx(sd / np.sqrt(v.size),
                                                                          rel=1e-12)
                assert float(got[f"{q}_uncertainty_type_a"]) == pytest.approx(
                    sd / np.sqrt(v.size), rel=1e-12)
            else:
                assert np.isnan(float(got[f"{q}_std"]))
            assert float(got[f"{q}_dof"]) == v.size - 1
    # Kr of condition 0 has 2 valid runs of 3 (NaN left out)
    assert float(c.reflection_coefficient_dof[0]) == 1
    assert "incident_height_uncertainty_type_a" in c.incident_height.attrs["ancillary_variables"]
    assert c.incident_height_std.attrs["units"] == "m"


def test_no_condition_coordinates_is_an_error():
    with pytest.raises(ValueError, match="condition coordinates"):
        condition_statistics(xr.Dataset({"incident_height": ("run", [0.1, 0.2])}))


def test_combination_welch_satterthwaite():
    # two runs of one condition: u_A from their scatter (1 dof), u_B from 40 draws (39 dof)
    s = xr.Dataset({"incident_height": ("run", [0.150, 0.152])},
                   coords={"wave_period": ("run", [2.0, 2.0]),
                           "wave_height": ("run", [0.15, 0.15])})
    c = condition_statistics(s)
    ub = np.array([0.0006, 0.0008])
    runs = xr.Dataset(
        {"incident_height_uncertainty_type_b": ("run", ub, {"degrees_of_freedom": 39}),
         "incident_height_budget": (("run", "uncertainty_component"), np.stack([ub, ub]).T
                                    / np.sqrt(2)),
         "incident_height_sensitivity": (("run", "uncertainty_component"), np.ones((2, 2)))},
        coords={"wave_period": ("run", [2.0, 2.0]), "wave_height": ("run", [0.15, 0.15]),
                "uncertainty_component": ["a", "b"]})
    out, budget = combine(c, runs)
    u_a = 0.002 / np.sqrt(2) / np.sqrt(2)  # s = 0.002/sqrt(2), over sqrt(2)
    u_b = np.sqrt(np.mean(ub ** 2))
    u_c = np.hypot(u_a, u_b)
    nu = u_c ** 4 / (u_a ** 4 / 1 + u_b ** 4 / 39)
    assert float(out.incident_height_uncertainty[0]) == pytest.approx(u_c, rel=1e-12)
    k = stats.t.ppf(0.975, nu)
    assert float(out.incident_height_expanded_uncertainty[0]) == pytest.approx(k * u_c,
                                                                               rel=1e-10)
    assert out.incident_height_expanded_uncertainty.attrs["coverage_factor"][0] == \
        pytest.approx(k, rel=1e-10)
    # the budget: two B components sharing u_B and the repeatability; shares sum to 100 %
    share = budget.incident_height_contribution.values[0]
    assert share.sum() == pytest.approx(100.0, rel=1e-12)
    assert share[-1] == pytest.approx(100 * u_a ** 2 / u_c ** 2, rel=1e-10)
    assert list(budget.uncertainty_component.values) == ["a", "b", "repeatability"]


def _two_runs_type_b():
    """The uncertainty datasets of two runs at T = 2 s, H = 0.15 m (water depth only)."""
    return xr.Dataset(
        {"incident_height_uncertainty_type_b": ("run", [1e-4, 1e-4], {"degrees_of_freedom": 9}),
         "incident_height_budget": (("run", "uncertainty_component"), [[1e-4], [1e-4]]),
         "incident_height_sensitivity": (("run", "uncertainty_component"), [[1.0], [1.0]]),
         "input_units": ("uncertainty_component", ["m"]),
         "input_standard_uncertainty": ("uncertainty_component", [1e-4])},
        coords={"wave_period": ("run", [2.0, 2.0]), "wave_height": ("run", [0.15, 0.15]),
                "uncertainty_component": ["water_depth"]})


def test_report_sections_show_results_budget_and_full_scale():
    from flumekit.uncertainty import report_sections

    s = xr.Dataset({"incident_height": ("run", [0.150, 0.152]),
                    "mean_power": ("run", [14.0, 16.0])},
                   coords={"wave_period": ("run", [2.0, 2.0]),
                           "wave_height": ("run", [0.15, 0.15])})
    c = condition_statistics(s)
    c, b = combine(c, _two_runs_type_b())
    c.attrs.update(froude_scale=10.0, model_density=1000.0, prototype_density=1025.0)
    secs = dict((a, h) for a, _, h in report_sections(c, b))
    u = float(c.incident_height_expanded_uncertainty[0])
    assert f"0.151 ± {u:.2g}" in secs["uncertainty-results"]
    # full scale: H x 10, P x 10^3.5 x 1.025, the power's 2 u_A (no Type B) not scaled in
    assert f"1.51 ± {10 * u:.2g}" in secs["uncertainty-results"]
    assert f"{15.0 * 10 ** 3.5 * 1.025:.4g}" in secs["uncertainty-results"]
    assert "water depth" in secs["uncertainty-budget"]
    assert "repeatability" in secs["uncertainty-budget"]


def test_report_shows_a_value_without_uncertainty_as_a_plain_number():
    # one run of a condition and no Type B propagation for it (an irregular run): the value,
    # no dangling "±"
    from flumekit.uncertainty import report_sections

    s = xr.Dataset({"incident_height": ("run", [0.150, 0.152, 0.3])},
                   coords={"wave_period": ("run", [2.0, 2.0, 3.0]),
                           "wave_height": ("run", [0.15, 0.15, 0.3])})
    c = condition_statistics(s)
    c, b = combine(c, _two_runs_type_b())
    html = dict((a, h) for a, _, h in report_sections(c, b))["uncertainty-results"]
    assert ">0.3<" in html
    assert "0.3 ±" not in html
    assert "0.151 ±" in html
