"""Stage: surface elevation at every probe of a run, relative to the still-water level.

Reads the quality-controlled probe records (``qc/probes/<run>``). Probes recorded in volts are
calibrated (the ``calibration`` target); probes recorded in length units skip the calibration.
The still-water level is then removed by the declared rule (``still_water`` of the run, else of
the campaign's ``[probes]``; default ``"none"`` for calibrated voltages, whose calibration
levels already refer to still water, and ``"mean"`` for lengths) and recorded in the dataset.
"""

from __future__ import annotations

from flumekit.io.atomic import Written
from flumekit.pipeline.rules import Rule
from flumekit.stages.context import Context
from flumekit.stages.runs import run_params, write_run

VERSION = "3"


def rules(ctx: Context, params: dict) -> list[Rule]:
    """Return one rule per run, ``eta/<run>``: the surface elevation at every probe.

    Protocol: :mod:`flumekit.stages`; the stage has no parameters of its own, each rule carries
    the probes, their positions, the still-water rule and the run's parameters.
    """
    c = ctx.campaign
    calibrated = c.probes.calibrated
    out = []
    for run in c.runs:
        rule = run.still_water if run.still_water is not None else c.probes.still_water
        if rule is None:
            rule = "mean" if calibrated else "none"
        params = {"probes": list(c.probes.names), "probe_x": run.probe_x,
                  "sampling_rate": c.probes.sampling_rate,
                  "time_offset": run.clock.get("probes", 0.0), "still_water": rule,
                  **run_params(run, c)}
        inputs = {"probes": ctx.out("qc", "probes", f"{run.id}.nc")}
        if not calibrated:
            inputs["calibration"] = ctx.out("calibration.nc")
        out.append(Rule(f"eta/{run.id}", "flumekit.stages.eta:build", inputs=inputs,
                        outputs={"dataset": ctx.out("eta", f"{run.id}.nc")},
                        params=params, version=VERSION, run=run.id))
    return out


def build(inputs, outputs, params) -> Written:
    """Compute the surface elevation at every probe of a run and write it.

    An action of :mod:`flumekit.stages`: reads the QC'd ``probes`` record (and the
    ``calibration`` dataset for probes in volts), writes ``eta/<run>.nc`` with the positions
    ``probe_x`` [m] as ``x``. A calibration not monotonic over the recorded voltages, or a
    still-water rule that does not apply, is an :class:`~flumekit.errors.InputError`.
    """
    import numpy as np

    from flumekit.conventions import SOURCE_FILE, WARNINGS
    from flumekit.errors import InputError
    from flumekit.io.netcdf import read_dataset
    from flumekit.waves import calibration
    from flumekit.waves.still_water import remove_still_water

    qc = read_dataset(inputs["probes"])
    source_file = qc.attrs.get(SOURCE_FILE, inputs["probes"])
    warnings = [qc.attrs.get(WARNINGS, "")]
    if "probe_voltage" in qc:
        raw = qc["probe_voltage"].sel(probe=list(params["probes"]))
        cal = read_dataset(inputs["calibration"])
        bad = calibration.non_monotonic(raw, cal)
        if bad:
            raise InputError(source_file,
                             "; ".join(f"probe {p}: calibration polynomial is not monotonic "
                                       f"over the recorded voltages [{lo:.4g}, {hi:.4g}] V"
                                       for p, lo, hi in bad))
        elevation = calibration.apply(raw, cal)
        warnings.append(cal.attrs.get(WARNINGS, ""))
        source = f"{inputs['probes']} and {inputs['calibration']}"
    else:
        elevation = qc["probe_elevation"].sel(probe=list(params["probes"]))
        source = f"{inputs['probes']} (calibrated probes)"
    try:
        eta, level = remove_still_water(elevation, params["still_water"])
    except ValueError as e:
        raise InputError(source_file, str(e), field="still_water") from None
    x = np.array([params["probe_x"][p] for p in params["probes"]])
    ds = eta.to_dataset().assign_coords(x=("probe", x))
    ds["still_water_level"] = level
    ds.attrs.update(still_water_rule=level.attrs["rule"], time_offset=params["time_offset"])
    warnings = [w for w in warnings if w]
    if warnings:
        ds.attrs[WARNINGS] = "\n".join(warnings)
    return write_run(ds, outputs, params, "Surface elevation per probe",
                     f"flumekit eta stage from {source}")
