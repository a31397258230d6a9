"""What every stage module declares on the small virtual campaign: its rules' inputs, outputs
and the parameters that could be wrong, checked against the campaign they were built from.

The campaign is planned, not synthesised (:func:`flumekit.synth.campaign.virtual_campaign`:
its campaign and run files, read by the campaign reader): two regular wave runs, two UVP runs
and one irregular JONSWAP run, with probes, flap instruments and UVP.
"""

from __future__ import annotations

import dataclasses
import functools
import importlib
from pathlib import Path

import pytest

from flumekit.errors import FlumekitError
from flumekit.stages import STAGES, build_rules
from flumekit.stages.context import Context

PROCESSED = Path("/processed")


@pytest.fixture(scope="module")
def campaign(tmp_path_factory):
    from flumekit.synth.campaign import virtual_campaign

    return virtual_campaign(tmp_path_factory.mktemp("raw") / "small", "small", 2020)


@functools.cache
def default_scenes() -> dict:
    """The default pipeline's scenes: what it asks to build (the ball-screw study among them)."""
    from flumekit.pipeline.config import load_pipeline

    return load_pipeline(Path(__file__).resolve().parents[2] / "pipelines" / "default.toml").scenes


def ctx(campaign, **params) -> Context:
    return Context(campaign, PROCESSED, params, scenes=default_scenes())


def rules_of(stage: str, context: Context) -> dict:
    """The rules of stage module ``stage``, by target, with its parameters as build_rules
    passes them."""
    mod = importlib.import_module(f"flumekit.stages.{stage}")
    params = context.stage_params(stage, getattr(mod, "DEFAULTS", {}))
    return {r.target: r for r in mod.rules(context, params)}


def out(*parts: str) -> Path:
    return PROCESSED.joinpath(*parts)


def runs(campaign, kind: str | None = None) -> list:
    return [r for r in campaign.runs if kind is None or r.kind == kind]


def without_irregular(campaign):
    return dataclasses.replace(campaign, runs=tuple(r for r in campaign.runs if not r.irregular))


def test_the_small_campaign_has_every_kind_of_run(campaign):
    assert {r.kind for r in campaign.runs} == {"waves", "uvp", "irregular"}
    assert set(campaign.instruments) == {"probes", "flap", "uvp"}


def test_calibration(campaign):
    (rule,) = rules_of("calibration", ctx(campaign, calibration={"order": 2})).values()
    assert rule.inputs["calibration"] == campaign.calibration_file
    assert rule.outputs == {"dataset": out("calibration.nc")}
    assert rule.params["probes"] == list(campaign.probes.names)
    assert rule.params["order"] == 2  # the pipeline's, over the default 1


def test_qc(campaign):
    rules = rules_of("qc", ctx(campaign, qc={"spike_fail": 9.0}))
    assert len(rules) == 2 * len(campaign.runs) + 1
    for r in campaign.runs:
        probes, flap = rules[f"qc/probes/{r.id}"], rules[f"qc/flap/{r.id}"]
        assert probes.inputs == {"probes": r.file("probes"), "run": r.path / "run.toml"}
        assert flap.inputs == {"flap": r.file("flap"), "run": r.path / "run.toml"}
        assert probes.outputs == {"dataset": out("qc", "probes", f"{r.id}.nc")}
        assert probes.params["kind"] == r.kind and probes.params["run"] == r.id
        assert probes.params["probe_x"] == r.probe_x
        assert probes.params["sampling_rate"] == campaign.probes.sampling_rate
        assert flap.params["sampling_rate"] == campaign.encoder.sampling_rate
        assert probes.params["spike_fail"] == flap.params["spike_fail"] == 9.0
        # the declared period is checked only where one is declared
        assert probes.params["period"] == (None if r.irregular else r.period)
    summary = rules["qc_summary"]
    assert set(summary.inputs) == {f"{k}/{r.id}" for r in campaign.runs
                                   for k in ("probes", "flap")}
    irregular = runs(campaign, "irregular")[0]
    assert summary.params["conditions"][irregular.id] == [None, irregular.height]


def test_eta(campaign):
    rules = rules_of("eta", ctx(campaign))
    assert set(rules) == {f"eta/{r.id}" for r in campaign.runs}
    for r in campaign.runs:
        rule = rules[f"eta/{r.id}"]
        # the QC'd record, calibrated (the virtual probes record volts)
        assert rule.inputs == {"probes": out("qc", "probes", f"{r.id}.nc"),
                               "calibration": out("calibration.nc")}
        assert rule.outputs == {"dataset": out("eta", f"{r.id}.nc")}
        assert rule.params["probe_x"] == r.probe_x


def test_waves_rules_carry_each_runs_kind_and_sea_state(campaign):
    rules = rules_of("waves", ctx(campaign))
    assert set(rules) == {f"waves/{r.id}" for r in campaign.runs} | {"waves_summary"}
    for r in campaign.runs:
        p = rules[f"waves/{r.id}"].params
        assert rules[f"waves/{r.id}"].inputs["eta"] == out("eta", f"{r.id}.nc")
        assert p["kind"] == r.kind
        assert p["depth"] == campaign.flume.water_depth
        assert p["separation_probes"] == list(campaign.probes.separation)
        assert p["sea_state_coords"] is True  # the campaign has an irregular run
    (irregular,) = runs(campaign, "irregular")
    p = rules[f"waves/{irregular.id}"].params
    assert p["kind"] == "irregular" and p["period"] is None
    assert p["sea_state"]["hm0"] == irregular.sea_state.hm0 == 0.1
    assert p["sea_state"]["tp"] == irregular.sea_state.tp == 2.0
    regular = runs(campaign, "waves")[0]
    assert rules[f"waves/{regular.id}"].params["sea_state"] is None
    assert rules[f"waves/{regular.id}"].params["period"] == regular.period
    assert set(rules["waves_summary"].inputs.values()) == {out("waves", f"{r.id}.nc")
                                                          for r in campaign.runs}
    # without irregular runs, no run carries the sea-state coordinates
    p = rules_of("waves", ctx(without_irregular(campaign)))[f"waves/{regular.id}"].params
    assert p["sea_state_coords"] is False


def test_flap(campaign):
    rules = rules_of("flap", ctx(campaign))
    assert set(rules) == {f"flap/{r.id}" for r in campaign.runs} | {"flap_summary"}
    for r in campaign.runs:
        rule = rules[f"flap/{r.id}"]
        assert rule.inputs["flap"] == out("qc", "flap", f"{r.id}.nc")
        assert rule.inputs["waves"] == out("waves", f"{r.id}.nc")
        assert rule.params["sampling_rate"] == campaign.encoder.sampling_rate
        assert rule.params["kind"] == r.kind


def test_uvp_rules_exist_only_for_uvp_runs_and_carry_the_qc_parameters(campaign):
    from flumekit.stages.qc_params import UVP_PARAMS

    rules = rules_of("uvp", ctx(campaign, qc={"max_gap": 0.3, "spike_fail": 9.0}))
    uvp = runs(campaign, "uvp")
    assert len(uvp) == 2
    assert set(rules) == {f"uvp/{r.id}" for r in uvp} | {"uvp_field"}
    for r in uvp:
        rule = rules[f"uvp/{r.id}"]
        assert set(rule.inputs) == {b.name for b in campaign.uvp.beams} | {
            "campaign", "waves", "flap"}
        assert rule.inputs["UP1"] == r.path / "UP1.mfprof"
        # the rule writes the beams' QC flags beside its phase average
        assert rule.outputs == {"dataset": out("uvp", f"{r.id}.nc"),
                                "qc": out("qc", "uvp", f"{r.id}.nc")}
        assert rule.params["uvp_elevation"] == r.uvp_elevation
        # the [stages.qc] parameters of the UVP's QC, the pipeline's over the defaults
        assert set(rule.params["qc"]) == set(UVP_PARAMS)
        assert rule.params["qc"]["max_gap"] == 0.3
    field = rules["uvp_field"]
    assert set(field.inputs) == {r.id for r in uvp} | {"campaign"}
    assert (field.params["period"], field.params["height"]) == (uvp[0].period, uvp[0].height)
    no_uvp = dataclasses.replace(campaign, runs=tuple(r for r in campaign.runs
                                                      if r.kind != "uvp"))
    assert rules_of("uvp", ctx(no_uvp)) == {}


def test_models(campaign):
    rules = rules_of("models", ctx(campaign))
    assert set(rules) == ({"models/hydro", "comparison_summary"}
                          | {f"comparison/{r.id}" for r in campaign.runs})
    hydro = rules["models/hydro"]
    assert hydro.inputs == {} and hydro.outputs == {"dataset": out("models", "hydro.nc")}
    assert hydro.params["depth"] == campaign.flume.water_depth
    assert "omega_max" in hydro.params and "bem_panel_size" not in hydro.params
    for r in campaign.runs:
        rule = rules[f"comparison/{r.id}"]
        assert rule.inputs["hydro"] == out("models", "hydro.nc")
        assert rule.inputs["flap"] == out("flap", f"{r.id}.nc")
        assert rule.params["kind"] == r.kind
    bem = rules_of("models", ctx(campaign, models={"coefficients": "bem"}))["models/hydro"]
    assert "bem_panel_size" in bem.params and "omega_max" not in bem.params
    with pytest.raises(FlumekitError, match="coefficients"):
        rules_of("models", ctx(campaign, models={"coefficients": "bme"}))


def test_power_matrix_rule_only_with_irregular_runs(campaign):
    rules = rules_of("performance", ctx(campaign))
    (irregular,) = runs(campaign, "irregular")
    assert set(rules) == {"power_matrix"}
    rule = rules["power_matrix"]
    assert rule.inputs == {f"{k}:{irregular.id}": out(k, f"{irregular.id}.nc")
                           for k in ("flap", "comparison", "waves")}
    assert rule.params["runs"] == [irregular.id]
    assert rule.params["targets"][0]["hm0"] == irregular.sea_state.hm0
    assert rules_of("performance", ctx(without_irregular(campaign))) == {}


def test_ballscrew_steps_chain_and_take_only_their_knobs(campaign):
    rules = rules_of("ballscrew", ctx(campaign, ballscrew={"screw_ball_diameter": 0.005}))
    steps = ["kinematics", "efficiency", "thermal_lumped", "thermal_fem"]
    assert list(rules) == [f"ballscrew/{s}" for s in steps]
    for previous, step in zip(steps, steps[1:], strict=False):
        assert rules[f"ballscrew/{step}"].inputs == {
            "previous": out("ballscrew", f"{previous}.nc")}
    assert rules["ballscrew/efficiency"].params["screw_ball_diameter"] == 0.005
    assert "screw_ball_diameter" not in rules["ballscrew/thermal_lumped"].params


def test_figures_are_registered_and_wired(campaign):
    from flumekit.figures.registry import figure

    rules = rules_of("figures", ctx(campaign, figures={"formats": ["png"]}))
    for rule in rules.values():
        entry = figure(rule.params["figure"])  # every figure a rule names is registered
        assert entry.name == rule.params["figure"]
        name = rule.target.removeprefix("figure/")
        assert rule.outputs == {"png": out("figures", f"{name}.png")}
    # the paper's single-run figures: its T = 3.5 s, H = 0.25 m run
    assert rules["figure/fig05a"].inputs == {"waves": out("waves", "T3.50_H0.250_r0.nc")}
    # Figs. 8-9: every regular run's comparison, no irregular one
    assert set(rules["figure/fig08"].inputs) == {r.id for r in campaign.runs if not r.irregular}
    # the separation figure of an irregular run is the sea-state one
    (irregular,) = runs(campaign, "irregular")
    assert rules[f"figure/separation/{irregular.id}"].params["figure"] == "separation_irregular"
    assert rules["figure/separation/T2.00_H0.150_r0"].params["figure"] == "separation"
    # the QC figure: products and raw files, read as the campaign declares them
    for r in campaign.runs:
        qc = rules[f"figure/qc/{r.id}"]
        assert qc.inputs["probes_raw"] == r.file("probes")
        assert qc.inputs["flap_raw"] == r.file("flap")
        assert ("uvp" in qc.inputs) == (r.kind == "uvp")
        assert qc.params["reading"]["probes"]["probes"] == list(campaign.probes.names)
        assert qc.params["run"] == r.id
    assert rules["figure/bs_fig10"].inputs == {"thermal_fem": out("ballscrew",
                                                                  "thermal_fem.nc")}
    assert "figure/power_matrix" in rules
    plain = rules_of("figures", ctx(without_irregular(campaign)))
    assert "figure/power_matrix" not in plain and "figure/capture_width_ratio" not in plain
    with pytest.raises(FlumekitError, match="formats"):
        rules_of("figures", ctx(campaign, figures={"formats": ["gif"]}))


def test_every_rule_names_an_action_and_reads_what_another_writes(campaign):
    """The whole graph: every action is a function of a stage module, every processed input
    is another rule's output, every stage module declared something."""
    rules = build_rules(ctx(campaign))
    outputs = {Path(p) for r in rules for p in r.outputs.values()}
    for rule in rules:
        module, _, name = rule.action.partition(":")
        assert module.startswith("flumekit.stages.")
        assert callable(getattr(importlib.import_module(module), name)), rule.action
        for p in rule.inputs.values():
            if PROCESSED in Path(p).parents:
                assert Path(p) in outputs, (rule.target, p)
    declared = {r.action.split(":")[0].split(".")[2].split("_")[0] for r in rules}
    assert declared == set(STAGES)
