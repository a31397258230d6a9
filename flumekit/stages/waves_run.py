"""The analyses of the waves stage's per-run rule (:func:`flumekit.stages.waves.build`).

A regular or an irregular sea, with the rule's parameters; and the line of each product's
statistics in the make summary.
"""

from __future__ import annotations

from flumekit.docstrings import filler

#: docstring text that several functions of this module share
_doc = filler(
    eta_probes=("eta : xarray.DataArray\n"
                "    Surface elevation at every probe [m], with probe positions ``x`` [m]."))


@_doc
def regular(eta, params):
    """Analyse a regular run (:func:`flumekit.waves.analyse_run`).

    Parameters
    ----------
    %(eta_probes)s
    params : dict
        The waves rule's parameters.

    Returns
    -------
    xarray.Dataset
        Incident and reflected waves and their statistics.
    """
    from flumekit.waves import analyse_run

    return analyse_run(eta, params["depth"], params["period"], params["x_ref"],
                       method=params["method"], separation_probes=params["separation_probes"],
                       n_harmonics=params["n_harmonics"],
                       bound_harmonics=params["bound_harmonics"],
                       amplitude_dispersion=params["amplitude_dispersion"],
                       tolerance=params["tolerance"], min_cycles=params["min_cycles"],
                       noise_factor=params["noise_factor"],
                       reflection_tolerance=params["reflection_tolerance"])


@_doc
def irregular(eta, params):
    """Analyse an irregular run (:func:`flumekit.waves.analyse_irregular_run`).

    The target peak period steers the analysis band only, not the result.

    Parameters
    ----------
    %(eta_probes)s
    params : dict
        The waves rule's parameters, with the run's target ``sea_state``.

    Returns
    -------
    xarray.Dataset
        Incident and reflected spectra and the sea state's parameters.
    """
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


def report(paths) -> list[str]:
    """Return one line of the statistics of each run's waves product, for the make summary.

    Kr, incident height [m] and period [s] of a regular run; Kr, Hm0 [m], Tp and Te [s] of an
    irregular one. The files are read together, their scalars only
    (:func:`flumekit.io.run_files.open_runs`).
    """
    from flumekit.io.run_files import open_runs

    lines = []
    with open_runs(paths) as runs:
        for i, (variables, _, _) in enumerate(runs.metas):
            def value(name, i=i):
                return runs.values(i, name).item()

            if "hm0" in variables:
                lines.append(
                    f"bulk Kr = {value('reflection_coefficient'):.3f}, Hm0 = "
                    f"{value('hm0'):.4g} m, Tp = {value('tp'):.4g} s, Te = {value('te'):.4g} s "
                    f"over {value('analysis_end') - value('analysis_start'):.0f} s (irregular)")
                continue
            crit = variables["steady_tolerance"][2].get("criterion", "tolerance") \
                if "steady_tolerance" in variables else "tolerance"
            lines.append(
                f"first-harmonic Kr = {value('reflection_coefficient'):.3f}, H_I = "
                f"{value('incident_height'):.4g} m, T = {value('measured_period'):.4g} s, "
                f"{int(value('steady_cycles'))} steady cycles ({crit} criterion)")
    return lines
