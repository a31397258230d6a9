"""Action of the waves stage's per-run rule (:mod:`flumekit.stages.waves`): a run's elevations
analysed as a regular or an irregular sea, its declared height or sea state checked against
the measured one, warnings kept."""

from __future__ import annotations

from flumekit.io.atomic import Written
from flumekit.stages.runs import write_run


def build(inputs, outputs, params) -> Written:
    import warnings

    from flumekit.conventions import WARNINGS
    from flumekit.errors import InputError
    from flumekit.io.netcdf import read_dataset
    from flumekit.qc.checks import check_declared, check_height

    eta_ds = read_dataset(inputs["eta"])
    eta = eta_ds["eta"]
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            ds = (_irregular if params["kind"] == "irregular" else _regular)(eta, params)
        except ValueError as e:  # a dead probe, a record too short: the message names the probe
            raise InputError(inputs["probes"], str(e)) from None
    # kept in the dataset, where the make summary, the summaries and the report find them
    recorded = [f"{inputs['probes']}: {w.message}" for w in caught
                if issubclass(w.category, UserWarning)]
    # the declared height (sea state) only labels the run (the analysis uses the measured
    # one), so a moderate disagreement is a warning and a gross one an error; an undeclared
    # one is not checked
    warned = []
    if params["height"] is not None:
        warned.append(check_height(params["height"], float(ds["incident_height"]),
                                   params["height_tolerance"], params["height_warning"],
                                   inputs["run"], "incident height at the flap"))
    sea = params.get("sea_state") or {}
    for key, measured, unit, what in (
            ("hm0", "hm0", "m", "incident Hm0 at the flap"),
            ("tp", "tp", "s", "incident peak period (smoothed spectrum)"),
            ("te", "te", "s", "incident energy period Tm-1,0")):
        if sea.get(key) is not None:
            warned.append(check_declared(key, sea[key], float(ds[measured]), unit,
                                         params["sea_state_tolerance"],
                                         params["sea_state_warning"], inputs["run"], what,
                                         "sea_state_tolerance"))
    warnings_ = [w for w in (eta_ds.attrs.get(WARNINGS, ""), *recorded, *warned) if w]
    if warnings_:
        ds.attrs[WARNINGS] = "\n".join(warnings_)
    return write_run(ds, outputs, params, "Incident and reflected waves",
                     f"flumekit waves stage from {inputs['eta']}", record=eta_ds)


def _regular(eta, params):
    """The analysis of a regular run (:func:`flumekit.waves.analyse_run`)."""
    from flumekit.waves import analyse_run

    return analyse_run(eta, params["depth"], params["period"], params["x_ref"],
                       method=params["method"], separation_probes=params["separation_probes"],
                       n_harmonics=params["n_harmonics"],
                       bound_harmonics=params["bound_harmonics"],
                       amplitude_dispersion=params["amplitude_dispersion"],
                       tolerance=params["tolerance"], min_cycles=params["min_cycles"],
                       noise_factor=params["noise_factor"])


def _irregular(eta, params):
    """The analysis of an irregular run (:func:`flumekit.waves.analyse_irregular_run`)."""
    from flumekit.waves import analyse_irregular_run

    sea = params["sea_state"]
    # JONSWAP with gamma 1-7: Te = 0.86-0.92 Tp (the target steers the band, not the result)
    target = sea["tp"] if sea["tp"] is not None else sea["te"] / 0.9
    return analyse_irregular_run(
        eta, params["depth"], params["x_ref"], method=params["irregular_method"],
        peak_period=target,
        separation_probes=params["separation_probes"], gauge_weights=params["gauge_weights"],
        span=params["span"] or (sea.get("transient"), None), n_bins=params["n_bins"],
        low_frequency_warning=params["low_frequency_warning"], rho=params["density"])
