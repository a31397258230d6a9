"""Stage: calibrated surface elevation at every probe of a run, from the QC'd probe voltages."""

from __future__ import annotations

from flumekit.pipeline.rules import Rule
from flumekit.stages.context import Context
from flumekit.stages.runs import run_params, write_run

VERSION = "3"


def rules(ctx: Context) -> list[Rule]:
    c = ctx.campaign
    out = []
    for run in c.runs:
        params = {"probes": list(c.probes.names), "probe_x": run.probe_x,
                  "sampling_rate": c.probes.sampling_rate, "kind": run.kind,
                  **run_params(run)}
        out.append(Rule(f"eta/{run.id}", "flumekit.stages.eta:build",
                        inputs={"probes": ctx.out("qc", "probes", f"{run.id}.nc"),
                                "calibration": ctx.out("calibration.nc")},
                        outputs={"dataset": ctx.out("eta", f"{run.id}.nc")},
                        params=params, version=VERSION, run=run.id))
    return out


def build(inputs, outputs, params) -> None:
    import numpy as np

    from flumekit.errors import InputError
    from flumekit.io.netcdf import read_dataset
    from flumekit.stages.qc import WARNINGS
    from flumekit.waves import calibration

    qc = read_dataset(inputs["probes"])
    raw = qc["probe_voltage"].sel(probe=list(params["probes"]))
    cal = read_dataset(inputs["calibration"])
    bad = calibration.non_monotonic(raw, cal)
    if bad:
        raise InputError(qc.attrs.get("source_file", inputs["probes"]),
                         "; ".join(f"probe {p}: calibration polynomial is not monotonic over "
                                   f"the recorded voltages [{lo:.4g}, {hi:.4g}] V"
                                   for p, lo, hi in bad))
    eta = calibration.apply(raw, cal)
    x = np.array([params["probe_x"][p] for p in params["probes"]])
    ds = eta.to_dataset().assign_coords(x=("probe", x))
    warnings = [w for w in (qc.attrs.get(WARNINGS, ""), cal.attrs.get(WARNINGS, "")) if w]
    if warnings:
        ds.attrs[WARNINGS] = "\n".join(warnings)
    write_run(ds, outputs, params, "Calibrated surface elevation per probe",
              f"flumekit eta stage from {inputs['probes']} and {inputs['calibration']}")
