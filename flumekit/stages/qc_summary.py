"""Action of the qc stage's campaign rule (:mod:`flumekit.stages.qc`).

QC counts, probe-to-flap lags and the warnings of every run.
"""

from __future__ import annotations

from flumekit.io.atomic import Written


def summary(inputs, outputs, params) -> Written:
    """Summarise the quality control of every run and write it.

    Per run: samples per QC flag of every probe and flap channel, the probe-to-flap lag [s]
    and its departure from the lag expected for its wave condition (:mod:`flumekit.qc.clock`;
    a clock offset beyond ``clock_tolerance`` is a warning naming the run, the reference of
    each run is the attribute ``clock_reference``), and every warning of the QC datasets.
    A campaign without the flap instruments has the probe counts only.

    An action of :mod:`flumekit.stages`: reads each run's QC products ``probes/<run>`` and
    ``flap/<run>``, writes ``qc_summary.nc``; ``conditions`` maps run -> ``[period [s], height
    [m]]``.
    """
    import numpy as np
    import xarray as xr

    from flumekit.conventions import WARNINGS
    from flumekit.io.netcdf import read_dataset, write_product
    from flumekit.qc.clock import clock_departures, probe_flap_lag
    from flumekit.qc.flags import FLAG_MEANINGS
    from flumekit.qc.record import flag_counts

    def counts(flags, name):
        """Return the samples per flag of a flag variable, all its channels together."""
        return xr.DataArray(flag_counts(flags.values.reshape(-1)), dims="flag_meaning",
                            coords={"flag_meaning": ("flag_meaning", FLAG_MEANINGS.split(),
                                                     {"long_name": "QARTOD flag meaning"})},
                            attrs={"units": "1", "long_name": f"samples of {name} per QC flag"})

    runs = sorted({k.split("/", 1)[1] for k in inputs})
    rows, lags, warn = [], [], []
    for run in runs:
        p = read_dataset(inputs[f"probes/{run}"])
        name = "probe_voltage" if "probe_voltage" in p else "probe_elevation"
        row = {f"{name}_qc_count": counts(p[f"{name}_qc"], name),
               "record_period": p["record_period"]}
        warn += [w for w in p.attrs.get(WARNINGS, "").splitlines() if w]
        if f"flap/{run}" in inputs:
            f = read_dataset(inputs[f"flap/{run}"])
            period, height = params["conditions"][run]  # the run's wave condition [s, m]
            if period is not None:  # a regular run: its lag against its condition's
                near = p[name].isel(probe=int(np.argmin(np.abs(p["x"].values))))
                lag = probe_flap_lag(near.values, p["time"].values,
                                     f["encoder_counts"].values, f["time"].values, period)
                lags.append((run, lag, period, height))
            row.update({f"{k}_qc_count": counts(f[f"{k}_qc"], k)
                        for k in ("encoder_counts", "chamber_pressure")})
            warn += [w for w in f.attrs.get(WARNINGS, "").splitlines() if w]
        rows.append(xr.Dataset(row).drop_vars(
            ["run", "wave_period", "wave_height", "repeat", "uvp_elevation"],
            errors="ignore").expand_dims(run=[run]))
    out = xr.concat(rows, dim="run", coords="minimal", compat="override")
    for v in out.variables.values():
        # read back from the run products: their encoding names the run coordinates dropped
        # here ("coordinates"), which CF checkers rightly report as missing
        v.encoding = {}
    if lags:
        lagged, lag_values, periods, heights = (list(c) for c in zip(*lags, strict=True))
        dep, basis = clock_departures(np.array(lag_values), np.array(periods),
                                      np.array(heights, dtype=float))
        # NaN for a run without a lag (an irregular run has no condition to compare with)
        index = {r: i for i, r in enumerate(runs)}
        full_lag, full_dep = np.full(len(runs), np.nan), np.full(len(runs), np.nan)
        full_lag[[index[r] for r in lagged]] = lag_values
        full_dep[[index[r] for r in lagged]] = dep
        out["probe_flap_lag"] = ("run", full_lag, {
            "units": "s", "long_name": "cross-correlation offset to add to the flap's time "
            "stamps to align the encoder with the probe nearest the flap (the physical lag, "
            "modulo a period, and any clock offset)"})
        out["clock_departure"] = ("run", full_dep, {
            "units": "s", "long_name": "that offset minus the one expected for the run's wave "
            "condition (the median of three runs or more of the condition, else a fit over "
            "the neighbouring conditions): the flap's clock offset where large; NaN without a "
            "reference",
            "comment": "reported, never applied: declare it as [clock] flap in run.toml"})
        tol = float(params["clock_tolerance"])
        warn += [f"run {r}: the flap aligns with the probes at {lag:+.3f} s, {d:+.3f} s off "
                 f"what T = {t:g} s, H = {h:g} m should give ({b}): a clock offset between "
                 "the probes and the flap? If so declare it in the run's run.toml "
                 f"([clock] flap = {d:.3f})"
                 for r, lag, d, t, h, b in zip(lagged, lag_values, dep, periods, heights,
                                               basis, strict=True) if abs(d) > tol]
        reference = "\n".join(f"{r}: {b}" for r, b in zip(lagged, basis, strict=True))
    else:
        reference = ""
    out.attrs = {WARNINGS: "\n".join(warn)} if warn else {}
    if reference:
        out.attrs["clock_reference"] = reference
    return write_product(out, outputs["dataset"], "Quality-control counts of every run",
                         f"flumekit qc summary of {len(runs)} runs", {"runs": runs, **params})
