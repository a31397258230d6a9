"""Actions of the qc stage's per-run rules (:mod:`flumekit.stages.qc`).

A run's probe and flap records are read, checked against their metadata and
quality-controlled.
"""

from __future__ import annotations

from flumekit.io.atomic import Written
from flumekit.stages.common import COMPRESS, gross_range, read_raw, write_qc


def _thresholds(params: dict):
    """Return the QARTOD thresholds of a run's probe or flap rule.

    An irregular run's dropout level is ``dropout_irregular`` (a random sea is no sinusoid:
    its extremes lie further out).
    """
    from flumekit.qc.record import Thresholds

    if params.get("kind") == "irregular":
        params = {**params, "dropout": params["dropout_irregular"]}
    return Thresholds.from_params(params)


def _stuck(ds, name, path, max_gap):
    """Raise an error naming the file and channel of masked spans longer than allowed.

    A stuck or dropped-out channel longer than the interpolation limit ``max_gap`` [s] is one
    the flap analysis cannot bridge.
    """
    from flumekit.errors import InputError
    from flumekit.qc.record import unfilled_gaps

    gaps = unfilled_gaps(ds, name)
    if gaps:
        raise InputError(path, f"channel '{name}': failed quality control over "
                         + ", ".join(gaps[:5]) + (" ..." if len(gaps) > 5 else "")
                         + " (flat line, dropout, spikes or noise longer than [stages.qc] "
                         f"max_gap = {max_gap:g} s, which is what may be interpolated)")


def probes(inputs, outputs, params) -> Written:
    """Quality-control a run's probe record and check it against the run's metadata.

    An action of :mod:`flumekit.stages`: reads the raw ``probes`` file, writes
    ``qc/probes/<run>.nc``, with the ``[stages.qc]`` thresholds (U.S. IOOS 2020, QARTOD manual
    for in-situ surface wave data). A dead, stuck or noise-only probe, or a kind (regular or
    irregular) or dominant period [s] that contradicts ``run`` (run.toml), is an
    :class:`~flumekit.errors.InputError` naming the file and probe.
    """
    from pathlib import Path

    import numpy as np

    from flumekit.conventions import SOURCE_FILE
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
                    gross_range=gross_range(params["probe_range"]))
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
    return write_qc(ds, outputs, params, "Quality-controlled wave probe voltages",
                  f"flumekit qc stage from {path}", warnings, compress=COMPRESS["probes"])


def flap(inputs, outputs, params) -> Written:
    """Quality-control a run's encoder and chamber-pressure record.

    An action of :mod:`flumekit.stages`: reads the raw ``flap`` file, writes ``qc/flap/<run>.nc``,
    as :func:`probes` does. A dead or stuck channel, a masked span longer than ``max_gap`` [s] or
    a period that contradicts ``run`` (run.toml) is an :class:`~flumekit.errors.InputError`
    naming the file and channel.
    """
    from pathlib import Path

    import numpy as np
    import xarray as xr

    from flumekit.conventions import SOURCE_FILE
    from flumekit.qc import checks
    from flumekit.qc.flags import FAIL
    from flumekit.qc.record import qc_dataset

    path = Path(inputs["flap"])
    raw = read_raw("flap", path, params)  # qc_dataset works the integer counts as floats
    th = _thresholds(params)
    parts = []
    for name, rng, unit in (("encoder_counts", "encoder_range", " counts"),
                            ("chamber_pressure", "pressure_range", " Pa")):
        ds = qc_dataset(raw, name, th, gross_range=gross_range(params[rng]))
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
    return write_qc(ds, outputs, params, "Quality-controlled encoder and chamber pressure",
                  f"flumekit qc stage from {path}", compress=COMPRESS["flap"])
