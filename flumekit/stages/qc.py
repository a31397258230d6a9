"""Stage: quality control of every run's instrument records, before any analysis.

Per run and instrument one rule reads the raw record, checks it against its metadata (dead or
stuck channels, the declared period), runs the QARTOD battery of :mod:`flumekit.qc` and writes
``qc/<instrument>/<run>.nc``: the QC'd values (failed samples masked, short gaps interpolated),
the per-sample QARTOD flags and the counts. The eta and flap stages read these instead of the
raw files. The values as read are not repeated (the QC figure reads the raw files), and the
probe and flap products are not deflated (:data:`COMPRESS`).

The UVP beams are checked (Goring-Nikora despiking, echo level) by the rule that analyses them,
before its analysis: :func:`beam_checker`, called by the uvp rule, which writes the per-sample
flags to ``qc/uvp/<run>.nc``. Their analysis reads the beams whole, 18 MB a run: a rule of its own
would read them and the waves a second time, 25-30 ms a run before any checking, a tenth of
the uvp rule (``flumekit bench qc``). The UVP is checked where its average reads: over the
earliest window of N waves that the waves and the flap angle allow, and over the whole
quasi-steady part of the run only when the beams are not clean there
(:func:`flumekit.stages.uvp.build`).
"""

from __future__ import annotations

from flumekit.conventions import MAX_GAP, SOURCE_FILE, WARNINGS
from flumekit.io.atomic import Written
from flumekit.pipeline.rules import Rule
from flumekit.stages.common import raw_reading, read_raw
from flumekit.stages.context import Context
from flumekit.stages.runs import run_params

VERSION = "5"
#: [stages.qc] parameters: the thresholds of flumekit.qc.record.Thresholds, the metadata checks
#: and optional gross ranges [channel units: V, counts, Pa, m s-1] (unset: not evaluated)
DEFAULTS = {"spike_suspect": 6.0, "spike_fail": 8.0, "rate_of_change": 10.0,
            "flat_line_suspect": 3.0, "flat_line_fail": 5.0, "flat_line_tolerance": 0.0,
            "dropout": 6.0, "hold": 0.2, "block": 10.0, "gap_tolerance": 0.5, "max_gap": 0.2,
            "period_tolerance": 0.1, "max_flat_fraction": 0.5, "despike_iterations": 1,
            "probe_range": None, "encoder_range": None, "pressure_range": None,
            "velocity_range": None, "clock_tolerance": 0.1, "noise_autocorrelation": 0.5,
            "noise_share": 0.1, "dropout_irregular": 12.0}
DOCS = {
    "spike_suspect": "spike test: suspect beyond this many robust local standard deviations of "
                     "x_n - (x_(n-1) + x_(n+1))/2 [-]",
    "spike_fail": "spike test: fail beyond this many [-]",
    "rate_of_change": "rate-of-change test: robust local standard deviations of the first "
                      "difference [-]",
    "flat_line_suspect": "flat-line test: suspect after this long without change [s]",
    "flat_line_fail": "flat-line test: fail after this long [s]",
    "flat_line_tolerance": "flat-line test: changes below this count as none [channel units]",
    "dropout": "dropout test: robust standard deviations of the record about its median [-]",
    "hold": "dropout test: a dropout holds its value at least this long [s]",
    "block": "length of the blocks of the local robust scale [s]",
    "gap_tolerance": "a time step longer than (1 + this) / rate is a gap [-]",
    "max_gap": "longest run of failed samples interpolated [s]",
    "period_tolerance": "declared period vs the probes' dominant period: relative difference "
                        "beyond which the run is refused [-]",
    "max_flat_fraction": "fraction of a record flat-lined (or failing the noise test) beyond "
                         "which the channel is dead, stuck (or noise): an error naming file "
                         "and channel [-]",
    "despike_iterations": "Goring-Nikora despiking iterations at most (UVP) [-]",
    "probe_range": "[min, max] gross range of the probe records [V or m]; none: not tested",
    "encoder_range": "[min, max] gross range of the encoder counts; none: not tested",
    "pressure_range": "[min, max] gross range of the chamber pressure [Pa]; none: not tested",
    "velocity_range": "[min, max] gross range of the UVP velocities [m s-1]; none: not tested",
    "noise_autocorrelation": "noise test: a block (of `block` seconds) whose lag-one "
                             "autocorrelation is below this [-] ...",
    "noise_share": "... and whose high-frequency energy (half the mean square first "
                   "difference) exceeds this share of the channel's variance fails: noise or "
                   "alternating spikes, not a signal sampled far above its band [-]",
    "dropout_irregular": "dropout test of an irregular run's probe and flap records: robust "
                         "standard deviations about the median [-]; an irregular sea's "
                         "largest waves, and the pressure peaks of a single-acting PTO in "
                         "them, lie 7 or more of them out",
    "clock_tolerance": "probe-to-flap lag departing from the lag expected for the run's wave "
                       "condition (its other runs, else the neighbouring conditions) by more "
                       "than this is reported as a possible clock offset [s]",
}
#: whether each product's float arrays are deflated (flumekit.io.netcdf.write_dataset): not the
#: probe and flap records, written once and read once by the next stage, whose float records of
#: measured noise deflate by a third only and slowly (6-10 ms a product, a third of the rule)
COMPRESS = {"probes": False, "flap": False, "uvp": True}
#: the [stages.qc] parameters of the UVP's quality control, which the uvp rules carry (they
#: check the beams they read: :func:`beam_checker`)
UVP_PARAMS = ("despike_iterations", "dropout", "gap_tolerance", "max_gap", "velocity_range")


def rules(ctx: Context, params: dict) -> list[Rule]:
    c = ctx.campaign
    out = []
    for run in c.runs:
        rp = {**params, **run_params(run, c)}
        reading = raw_reading(ctx, run)
        out.append(Rule(f"qc/probes/{run.id}", "flumekit.stages.qc:probes",
                        inputs={"probes": run.file("probes"), "run": run.path / "run.toml"},
                        outputs={"dataset": ctx.out("qc", "probes", f"{run.id}.nc")},
                        params={**rp, **reading["probes"], "probe_x": run.probe_x},
                        version=VERSION, run=run.id))
        if "flap" in c.instruments:
            out.append(Rule(f"qc/flap/{run.id}", "flumekit.stages.qc:flap",
                            inputs={"flap": run.file("flap"), "run": run.path / "run.toml"},
                            outputs={"dataset": ctx.out("qc", "flap", f"{run.id}.nc")},
                            params={**rp, **reading["flap"]}, version=VERSION, run=run.id))
    inputs = {f"{kind}/{r.id}": ctx.out("qc", kind, f"{r.id}.nc")
              for r in c.runs for kind in ("probes", "flap")
              if kind == "probes" or "flap" in c.instruments}
    out.append(Rule("qc_summary", "flumekit.stages.qc:summary", inputs=inputs,
                    outputs={"dataset": ctx.out("qc_summary.nc")},
                    params={"clock_tolerance": params["clock_tolerance"],
                            "conditions": {r.id: [r.period, r.height] for r in c.runs}},
                    version=VERSION))
    return out


def _thresholds(params: dict):
    """The QARTOD thresholds of a run's probe or flap rule: an irregular run's dropout level
    is ``dropout_irregular`` (a random sea is no sinusoid: its extremes lie further out)."""
    from flumekit.qc.record import Thresholds

    if params.get("kind") == "irregular":
        params = {**params, "dropout": params["dropout_irregular"]}
    return Thresholds.from_params(params)


def _span(value):
    return None if value is None else (float(value[0]), float(value[1]))


def _write(ds, outputs, params, title, source, warnings=(), compress=True) -> Written:
    from flumekit.stages.runs import write_run

    if warnings:
        ds.attrs[WARNINGS] = "\n".join(warnings)
    ds.attrs[MAX_GAP] = float(params["max_gap"])
    # no run coordinates: qc_summary stacks its own counts, and the rule's title and
    # parameters name the run (3 ms a product: a tenth of a probe or flap QC rule)
    return write_run(ds, outputs, params, title, source, compress=compress, coords=False)


def _stuck(ds, name, path, max_gap):
    """Error naming the file and channel of masked spans longer than the interpolation limit
    (a stuck or dropped-out channel the flap analysis cannot bridge)."""
    from flumekit.errors import InputError
    from flumekit.qc.record import unfilled_gaps

    gaps = unfilled_gaps(ds, name)
    if gaps:
        raise InputError(path, f"channel '{name}': failed quality control over "
                         + ", ".join(gaps[:5]) + (" ..." if len(gaps) > 5 else "")
                         + " (flat line, dropout, spikes or noise longer than [stages.qc] "
                         f"max_gap = {max_gap:g} s, which is what may be interpolated)")


def probes(inputs, outputs, params) -> Written:
    from pathlib import Path

    import numpy as np

    from flumekit.qc import checks
    from flumekit.qc.flags import FAIL
    from flumekit.qc.record import qc_dataset
    from flumekit.waves.records import REGULAR_FRACTION, harmonic_energy_fraction

    path = Path(inputs["probes"])
    # dialect, units, clock: as the campaign declares them (default: the raw campaign's CSV)
    raw = read_raw("probes", path, params)
    # volts to calibrate, or elevations of calibrated probes [m]
    name = "probe_voltage" if "probe_voltage" in raw else "probe_elevation"
    th = _thresholds(params)
    ds = qc_dataset(raw, name, th, channel_dim="probe",
                    gross_range=_span(params["probe_range"]))
    flat = ds[f"{name}_qc"].attrs["flagged_by_flat_line"] / raw.sizes["time"]
    noise = ds[f"{name}_qc"].attrs["flagged_by_noise"] / raw.sizes["time"]
    checks.check_alive(raw[name].transpose("probe", "time").values,
                       raw["probe"].values, path, flat, params["max_flat_fraction"],
                       " V" if name == "probe_voltage" else " m", noise)
    v = ds[name].transpose("probe", "time").values
    ok = ds[f"{name}_qc"].transpose("probe", "time").values != FAIL
    good = np.where(ok, v, np.nan)
    period = checks.dominant_period(good, params["sampling_rate"])
    # the record's kind as flumekit.waves.separate detects it, against the declared one
    f1, share = harmonic_energy_fraction(np.where(ok, v - np.nanmean(good, axis=-1,
                                                                     keepdims=True), 0.0),
                                         1.0 / params["sampling_rate"])
    checks.check_kind(params["kind"], f1, share, REGULAR_FRACTION, Path(inputs["run"]), path)
    if params["period"] is not None:  # an irregular run's sea state is checked by its waves
        checks.check_period(params["period"], period, params["period_tolerance"],
                            Path(inputs["run"]), path)
    ds = ds.assign_coords(x=("probe", [float(params["probe_x"][p]) for p in params["probes"]]))
    ds["record_period"] = ((), period, {"units": "s", "long_name": "dominant period of the "
                                        "probe records (spectral peak)"})
    warnings = [f"{path}: {name}: masked and not interpolated: {g}"
                for g in ds.attrs[f"{name}_unfilled_gaps"].split("; ") if g]
    ds.attrs[SOURCE_FILE] = str(path)
    return _write(ds, outputs, params, "Quality-controlled wave probe voltages",
                  f"flumekit qc stage from {path}", warnings, compress=COMPRESS["probes"])


def flap(inputs, outputs, params) -> Written:
    from pathlib import Path

    import numpy as np
    import xarray as xr

    from flumekit.qc import checks
    from flumekit.qc.flags import FAIL
    from flumekit.qc.record import qc_dataset

    path = Path(inputs["flap"])
    raw = read_raw("flap", path, params)  # qc_dataset works the integer counts as floats
    th = _thresholds(params)
    parts = []
    for name, rng, unit in (("encoder_counts", "encoder_range", " counts"),
                            ("chamber_pressure", "pressure_range", " Pa")):
        ds = qc_dataset(raw, name, th, gross_range=_span(params[rng]))
        flat = float(ds[f"{name}_qc"].attrs["flagged_by_flat_line"]) / raw.sizes["time"]
        noise = float(ds[f"{name}_qc"].attrs["flagged_by_noise"]) / raw.sizes["time"]
        checks.check_alive(raw[name].values, [name], path, [flat],
                           params["max_flat_fraction"], unit, [noise])
        _stuck(ds, name, path, params["max_gap"])
        parts.append(ds)
    if params.get("period") is not None:  # an irregular run declares no period
        # the samples that passed, as for the probes' period
        checks.check_record_period(params["period"], {
            n.replace("_", " "): checks.dominant_period(
                np.where(p[f"{n}_qc"].values != FAIL, p[n].values, np.nan),
                params["sampling_rate"])
            for p, n in zip(parts, ("encoder_counts", "chamber_pressure"), strict=True)},
            params["period_tolerance"], path,
            inputs.get("run") or f"run.toml of run {params['run']}")
    # on the same time axis, with attributes of their own names: no merge (its alignment
    # costs more than one channel's tests)
    ds = xr.Dataset({k: v.variable for p in parts for k, v in p.data_vars.items()},
                    coords=parts[0].coords, attrs={k: v for p in parts for k, v in p.attrs.items()})
    ds.attrs[SOURCE_FILE] = str(path)
    return _write(ds, outputs, params, "Quality-controlled encoder and chamber pressure",
                  f"flumekit qc stage from {path}", compress=COMPRESS["flap"])


def beam_checker(beams: dict, params: dict):
    """The quality control of a run's UVP beams over a span [s] (probes' clock): the flags of
    :func:`flumekit.qc.record.beam_flags` with the [stages.qc] parameters ``params["qc"]``
    (:data:`UVP_PARAMS`) of the uvp rule; pure (nothing written)."""
    from flumekit.qc.record import Thresholds, beam_flags

    qc = params["qc"]
    th = Thresholds.from_params(qc)

    def check(span):
        return beam_flags(beams, span, th, time_offset=float(params.get("time_offset", 0.0)),
                          gross_range=_span(qc["velocity_range"]))

    return check


def write_beam_flags(flags, path, params: dict, sources) -> Written:
    """Write the UVP beams' QC flags (:func:`beam_checker`) to ``path`` (``qc/uvp/<run>.nc``)."""
    return _write(flags, {"dataset": path}, {**params, "max_gap": params["qc"]["max_gap"]},
                  "Quality-control flags of the UVP beam velocities",
                  "flumekit qc stage from " + ", ".join(map(str, sources)),
                  compress=COMPRESS["uvp"])


def summary(inputs, outputs, params) -> Written:
    """Per run: samples per QC flag of every probe and flap channel, the probe-to-flap lag and
    its departure from the lag expected for its wave condition (:mod:`flumekit.qc.clock`; a
    clock offset beyond ``clock_tolerance`` is a warning naming the run, the reference of each
    run is the attribute ``clock_reference``), and every warning of the QC datasets.
    A campaign without the flap instruments has the probe counts only."""
    import numpy as np
    import xarray as xr

    from flumekit.io.netcdf import read_dataset, write_product
    from flumekit.qc.clock import clock_departures, probe_flap_lag
    from flumekit.qc.flags import FLAG_MEANINGS
    from flumekit.qc.record import flag_counts

    def counts(flags, name):
        """Samples per flag of a flag variable, all its channels together."""
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
