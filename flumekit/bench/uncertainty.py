"""Uncertainty of the results against the virtual flume's truth, and its cost.

``flumekit bench uncertainty`` synthesises independent virtual repeats of one condition
(T = 2 s, H = 0.15 m of Table 1): each with its own probe gains and static calibration, the
wavemaker's repeat scatter and the flap's loss drift (:class:`flumekit.synth.flume.
RepeatScatter`), probe noise, encoder quantisation and pressure sensor noise, exactly as the
virtual flume writes a run. Each repeat is analysed as the pipeline does (calibration, waves,
flap) and its uncertainty propagated as the ``uncertainty`` stage does (the campaign's default
components, the stage's default draws). It reports:

- coverage: the share of repeats whose expanded 95 % interval of H_I, Kr, θ amplitude and C_f
  contains the repeat's truth (acceptance: 90-99 %), with the RMS error over the RMS standard
  uncertainty (1: the uncertainty is the size of the error);
- Monte Carlo against linear propagation on the standard uncertainties (acceptance: within
  10 % on H_I and Kr) and the Monte Carlo estimate when the draws double (within 5 %);
- the cost per run against the number of draws and the cost on the default campaign.
"""

from __future__ import annotations

import time

import numpy as np

from flumekit.docstrings import filler

#: docstring text that several functions of this module share
_doc = filler(
    random_seed=("seed : int\n"
                 "    Seed."))

PERIOD, HEIGHT = 2.0, 0.15  # the condition of the repeats [s], [m]
QUANTITIES = ("incident_height", "reflection_coefficient", "theta_amplitude", "capture_factor")


def _setup():
    import tempfile
    from pathlib import Path

    from flumekit.campaign import load_campaign
    from flumekit.synth.campaign import campaign_toml
    from flumekit.synth.flap import flume_hydrodynamics

    with tempfile.TemporaryDirectory() as tmp:
        (Path(tmp) / "campaign.toml").write_text(campaign_toml("bench"))
        campaign = load_campaign(tmp)
    return campaign, flume_hydrodynamics(campaign)


def virtual_repeat(index: int, seed: int, campaign, hydro, n_steady: int = 55):
    """Synthesise one virtual repeat of the condition: what the pipeline would read, and the truth.

    Parameters
    ----------
    index : int
        Index of the repeat (with ``seed``, its random stream).
    seed : int
        Seed of the repeats.
    campaign : flumekit.campaign.Campaign
        The bench campaign.
    hydro : object
        The flap's hydrodynamics in the flume (:func:`flumekit.synth.flap.flume_hydrodynamics`).
    n_steady : int
        Waves of the quasi-steady part of the record.

    Returns
    -------
    eta : xarray.DataArray
        Calibrated elevation (probe, time) [m], as the eta stage makes it.
    calibration : xarray.Dataset
        The repeat's calibration dataset.
    record : dict
        The flap record: ``time`` [s], ``encoder_counts`` [-], ``chamber_pressure`` [Pa].
    truth : dict
        ``height`` (generated) [m], ``period`` (generated) [s], ``reflection`` (effective Kr at
        the hinge) [-] and ``flap`` (the flap truth dataset).
    """
    import dataclasses

    import pandas as pd
    import xarray as xr

    from flumekit.synth.campaign import (
        CALIBRATION_LEVELS,
        Truth,
        probe_positions,
        regular_waves_at_flap,
    )
    from flumekit.synth.flap import FlapTruth, flap_record
    from flumekit.synth.flume import repeat_conditions
    from flumekit.synth.waves import regular_wave_field
    from flumekit.waves import calibration
    from flumekit.waves.theory import group_velocity

    truth = Truth()
    rng = np.random.default_rng([seed, index])
    names = list(campaign.probes.names)
    rate = campaign.probes.sampling_rate
    depth = campaign.flume.water_depth
    # the virtual flume's sensor law V = a + b eta and static calibration (synth.campaign)
    b = 10.0 * (1 + 0.05 * rng.standard_normal(len(names)))
    a = 2.5 + 0.3 * rng.standard_normal(len(names))
    levels = np.repeat(CALIBRATION_LEVELS, int(truth.static_seconds * rate))
    volts = a + b * (levels[:, None] + truth.probe_noise
                     * rng.standard_normal((levels.size, len(names))))
    volts = np.round(volts, 6)  # the CSV's 6 decimals
    cal = calibration.fit(pd.DataFrame(volts, columns=names), levels=levels)
    # as the calibration stage writes it, with the static voltages
    cal = cal.assign(calibration_voltage=(("sample", "probe"), volts))
    flap_truth = FlapTruth()
    period, height, losses = repeat_conditions(rng, PERIOD, HEIGHT, truth.scatter,
                                               flap_truth.losses)
    flap_truth = dataclasses.replace(flap_truth, losses=losses)
    xp = probe_positions(PERIOD, depth, truth)
    travel = abs(truth.x_wavemaker) / float(group_velocity(PERIOD, depth))
    duration = float(np.ceil(travel + (35 + n_steady + 10) * PERIOD))
    kw = dict(period=period, height=height, depth=depth, reflection=truth.reflection,
              reflection_phase=truth.reflection_phase, x_reflector=0.0,
              ramp_waves=truth.ramp_waves, second_order=True, x_wavemaker=truth.x_wavemaker,
              beach=truth.beach)
    t25 = np.arange(int(duration * rate)) / rate
    field = regular_wave_field(t25, np.array([xp[p] for p in names] + [0.0]), **kw)
    eta_true = field["eta"].values[:-1]
    noisy = eta_true + truth.probe_noise * rng.standard_normal(eta_true.shape)
    v = np.round(a[:, None] + b[:, None] * noisy, 6)  # the CSV's 6 decimals
    voltage = xr.DataArray(v, dims=("probe", "time"), coords={"probe": names, "time": t25})
    eta = calibration.apply(voltage, cal).assign_coords(x=("probe", [xp[p] for p in names]))
    enc = campaign.encoder
    t100, at = regular_waves_at_flap(duration, enc.sampling_rate, kw)
    n100 = t100.size
    flap = flap_record(t100, at["eta_incident"][:n100], period=period, campaign=campaign,
                       rng=rng, height=height, hydro=hydro, truth=flap_truth,
                       eta_lead_out=at["eta_incident"][n100:],
                       eta_front=at["eta_incident"] + at["eta_reflected"] + at["eta_beach"])
    record = {"time": t100, "encoder_counts": flap["encoder_counts"].values.astype(float),
              # the CSV's pressure in bar with 6 decimals
              "chamber_pressure": np.round(flap["chamber_pressure"].values / 1e5, 6) * 1e5}
    return eta, cal, record, {"height": float(field.attrs["wave_height"]), "period": period,
                              "reflection": float(field.attrs["reflection_coefficient"]),
                              "flap": flap}


def truth_values(truth: dict, result, campaign) -> dict[str, float]:
    """Return the true H_I, Kr, θ amplitude and C_f of a repeat, by the analysis' definitions.

    θ amplitude by :func:`flumekit.signal.cycle_amplitude` of the true θ over the analysed
    window, C_f as the true mean power over that window over W_I of the true height.

    Parameters
    ----------
    truth : dict
        The truth of :func:`virtual_repeat`.
    result : dict
        The analysed window: ``flap_period`` [s], ``flap_start`` [s], ``flap_cycles``.
    campaign : flumekit.campaign.Campaign
        The bench campaign (water depth, flap width).

    Returns
    -------
    dict of str to float
        ``incident_height`` [m], ``reflection_coefficient`` [-], ``theta_amplitude`` [rad],
        ``capture_factor`` [-].
    """
    from flumekit.flap.power import incident_power
    from flumekit.signal import cycle_amplitude

    flap = truth["flap"]
    t = flap.time.values
    period, start = float(result["flap_period"]), float(result["flap_start"])
    n = int(result["flap_cycles"])
    win = (t >= start) & (t < start + n * period)
    w_i = float(incident_power(truth["height"], truth["period"], campaign.flume.water_depth,
                               campaign.flap.width))
    return {"incident_height": truth["height"], "reflection_coefficient": truth["reflection"],
            "theta_amplitude": cycle_amplitude(flap.theta.values, t, period, start, n),
            "capture_factor": float(np.mean(flap.power.values[win])) / w_i}


#: the [uncertainty] table of the virtual flume's own errors: exact probe positions, depth,
#: inertia and clocks, the CSV's 1e-6 V steps at ~10 V m-1 (the probe noise, calibration,
#: encoder and pressure components keep their defaults, which are the virtual flume's)
VIRTUAL_ERRORS = {"probe_position": {"value": 0.0}, "water_depth": {"value": 0.0},
                  "flap_inertia": {"value": 0.0}, "clock_offset": {"value": 0.0},
                  "probe_resolution": {"value": 5e-8}}


def _model(eta, cal, record, campaign, components=None):
    from flumekit.stages.flap import DEFAULTS as FLAP
    from flumekit.stages.waves import DEFAULTS as WAVES
    from flumekit.uncertainty.propagation import RunModel, resolve_inputs

    inputs = resolve_inputs(campaign.uncertainty if components is None else components,
                            calibration=cal,
                            counts_per_metre=campaign.encoder.counts_per_metre)
    waves_kw = {k: WAVES[k] for k in ("method", "x_ref", "n_harmonics", "bound_harmonics",
                                      "amplitude_dispersion", "tolerance", "min_cycles",
                                      "noise_factor", "reflection_tolerance")}
    waves_kw["separation_probes"] = list(campaign.probes.separation)
    flap_kw = {"flap": campaign.flap, "pto": campaign.pto, "encoder": campaign.encoder,
               **{k: FLAP[k] for k in ("cutoff", "tolerance", "n_phase",
                                       "max_flagged_fraction")}}
    return RunModel(eta, campaign.flume.water_depth, PERIOD, waves_kw, record, flap_kw), inputs


def _flap_window(model) -> dict:
    """Return the flap analysis' window of the unperturbed run."""
    import warnings

    from flumekit.flap import analyse_run

    r = model.flap_record
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        w = model.waves({})
        ds = analyse_run(r["time"], r["encoder_counts"], r["chamber_pressure"],
                         depth=model.depth, period=w["measured_period"],
                         incident_height=w["incident_height"], **model.flap_kw)
    return {"flap_period": float(ds.measured_period), "flap_start": float(ds.steady_start),
            "flap_cycles": int(ds.steady_cycles)}


def coverage(n_repeats: int, draws: int, seed: int = 7, progress=None) -> dict:
    """Return the coverage of the expanded intervals over ``n_repeats`` virtual repeats.

    With the campaign's default components ("defaults") and with the virtual flume's own errors
    (:data:`VIRTUAL_ERRORS`, "virtual").

    Parameters
    ----------
    n_repeats : int
        Virtual repeats.
    draws : int
        Monte Carlo draws per repeat.
    seed : int
        Seed of the repeats and draws.
    progress : callable, optional
        Called with the index of each finished repeat.

    Returns
    -------
    dict
        set -> quantity -> (share covered, RMS error / RMS u, RMS error, RMS u), set -> "bias"
        -> quantity -> mean error, and "seconds" per repeat.

    References
    ----------
    JCGM 101:2008, §8 (validation of the GUM uncertainty framework by coverage).
    """
    from flumekit.campaign import uncertainty_components
    from flumekit.uncertainty.propagation import propagate

    campaign, hydro = _setup()
    sets = {"defaults": None, "virtual": uncertainty_components(VIRTUAL_ERRORS)}
    names = QUANTITIES
    err = {k: {q: [] for q in names} for k in sets}
    u = {k: {q: [] for q in names} for k in sets}
    covered = {k: {q: [] for q in names} for k in sets}
    t0 = time.perf_counter()
    for i in range(n_repeats):
        eta, cal, record, truth = virtual_repeat(i, seed, campaign, hydro)
        for key, comps in sets.items():
            model, inputs = _model(eta, cal, record, campaign, comps)
            ds = propagate(model, inputs, draws=draws, seed=[seed, i], linear_check=False)
            true = truth_values(truth, _flap_window(model), campaign)
            for q in names:
                e = float(ds[q]) - true[q]
                err[key][q].append(e)
                u[key][q].append(float(ds[f"{q}_uncertainty_type_b"]))
                covered[key][q].append(abs(e) <= float(ds[f"{q}_expanded_uncertainty"]))
        if progress:
            progress(i)
    out = {}
    for key in sets:
        rms_e = {q: float(np.sqrt(np.mean(np.square(err[key][q])))) for q in names}
        rms_u = {q: float(np.sqrt(np.mean(np.square(u[key][q])))) for q in names}
        out[key] = {q: (float(np.mean(covered[key][q])), rms_e[q] / rms_u[q], rms_e[q],
                        rms_u[q]) for q in names}
        out[key]["bias"] = {q: float(np.mean(err[key][q])) for q in names}
    out["seconds"] = (time.perf_counter() - t0) / max(n_repeats, 1)
    return out


@_doc
def agreement(draws: int, directions: int = 16, seed: int = 11) -> dict:
    """Compare Monte Carlo with ``draws`` and 2 ``draws`` against the linear propagation.

    On one repeat.

    Parameters
    ----------
    draws : int
        Monte Carlo draws n.
    directions : int
        Random directions of the per-sample inputs in the linear propagation.
    %(random_seed)s

    Returns
    -------
    dict
        Quantity -> (u_MC(n), u_MC(2n), u_linear) [unit of the quantity].
    """
    from flumekit.uncertainty.propagation import draws_uncertainty, linear, monte_carlo

    campaign, hydro = _setup()
    eta, cal, record, _ = virtual_repeat(0, seed, campaign, hydro)
    model, inputs = _model(eta, cal, record, campaign)
    base = model({})
    mc = monte_carlo(model, inputs, 2 * draws, seed)
    mc = mc[np.isfinite(mc).all(axis=1)]
    u_n = draws_uncertainty(mc[:draws], base)
    u_2n = draws_uncertainty(mc, base)
    _, contrib = linear(model, inputs, directions, seed)
    u_lin = np.sqrt(np.sum(contrib ** 2, axis=0))
    return {q: (float(u_n[j]), float(u_2n[j]), float(u_lin[j]))
            for j, q in enumerate(model.results)}


@_doc
def cost(draws_list=(10, 20, 40, 160), seed: int = 5) -> dict:
    """Return the run time of the propagation of one run against the number of draws.

    And of the linear budget at the stage's default directions.

    Parameters
    ----------
    draws_list : sequence of int
        Numbers of draws.
    %(random_seed)s

    Returns
    -------
    dict
        Draws -> seconds, and "linear" -> seconds [s].
    """
    from flumekit.stages.uncertainty import DEFAULTS
    from flumekit.uncertainty.propagation import linear, monte_carlo

    campaign, hydro = _setup()
    eta, cal, record, _ = virtual_repeat(0, seed, campaign, hydro)
    model, inputs = _model(eta, cal, record, campaign)
    out = {}
    for n in draws_list:
        t0 = time.perf_counter()
        monte_carlo(model, inputs, n, seed)
        out[n] = time.perf_counter() - t0
    t0 = time.perf_counter()
    linear(model, inputs, int(DEFAULTS["directions"]), seed)
    out["linear"] = time.perf_counter() - t0
    return out


def run(quick: bool = False) -> str:
    """Run the benchmark and return its report as text.

    Parameters
    ----------
    quick : bool
        Fewer repeats (20 instead of 100) and draws in the comparisons.

    Returns
    -------
    str
        The printed report: cost, Monte Carlo against linear, coverage.
    """
    from flumekit.stages.uncertainty import DEFAULTS
    from flumekit.synth.campaign import plan_runs

    draws = int(DEFAULTS["draws"])
    n_rep = 20 if quick else 100
    lines = [f"Uncertainty on the virtual flume: T = {PERIOD} s, H = {HEIGHT} m", ""]
    t = cost((10, 20, 40) if quick else (10, 20, 40, 160))
    n_runs = sum(1 for r in plan_runs("default"))
    per_run = t[draws] if draws in t else t[40] * draws / 40
    first = len({(r.period, r.height) for r in plan_runs("default")})
    lines += ["cost of one run (the waves and flap analyses per draw; one BLAS thread):"]
    lines += [f"  {k:>4} draws: {v:6.2f} s" for k, v in t.items() if k != "linear"]
    lines += [f"  linear budget ({DEFAULTS['directions']} directions): {t['linear']:.2f} s",
              f"  default campaign ({n_runs} regular runs, {draws} draws; budget on the "
              f"first run of each of {first} conditions): "
              f"{n_runs * per_run + first * t['linear']:.0f} s on one core", ""]
    n = 100 if quick else 400
    agr = agreement(n)
    lines += [f"standard uncertainties: MC {n} draws, MC {2 * n} draws, linear "
              "(16 directions for the per-sample inputs)"]
    for q, (a, b, c) in agr.items():
        lines.append(f"  {q:24s} {a:10.4g} {b:10.4g} {c:10.4g}   MC(2n)/MC(n) - 1 = "
                     f"{b / a - 1:+6.1%}   linear/MC - 1 = {c / b - 1:+6.1%}")
    lines.append("")
    cov = coverage(n_rep, draws)
    lines += [f"coverage of the expanded 95 % intervals over {n_rep} virtual repeats "
              f"({draws} draws each, {cov['seconds']:.1f} s per repeat for both sets)"]
    for key, what in (("virtual", "components of the virtual flume's own errors"),
                      ("defaults", "the campaign's default components (1 mm positions and "
                                   "depth, 2 % inertia: errors the virtual flume has not)")):
        lines.append(f" {what}:")
        for q in QUANTITIES:
            share, ratio, rms_e, rms_u = cov[key][q]
            lines.append(f"  {q:24s} {share:6.1%}  RMS error {rms_e:.3g}, RMS u {rms_u:.3g} "
                         f"(ratio {ratio:.2f}), mean error {cov[key]['bias'][q]:+.3g}")
    return "\n".join(lines)
