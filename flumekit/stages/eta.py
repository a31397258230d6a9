"""Stage: calibrated surface elevation at every probe of a run."""

from __future__ import annotations

from flumekit.pipeline.rules import Rule
from flumekit.stages.context import Context
from flumekit.stages.runs import run_params, write_run

VERSION = "2"


def rules(ctx: Context) -> list[Rule]:
    c = ctx.campaign
    out = []
    for run in c.runs:
        params = {"probes": list(c.probes.names), "probe_x": run.probe_x,
                  "sampling_rate": c.probes.sampling_rate, "kind": run.kind,
                  **run_params(run)}
        out.append(Rule(f"eta/{run.id}", "flumekit.stages.eta:build",
                        inputs={"probes": run.path / "probes.csv",
                                "calibration": ctx.out("calibration.nc")},
                        outputs={"dataset": ctx.out("eta", f"{run.id}.nc")},
                        params=params, version=VERSION, run=run.id))
    return out


def build(inputs, outputs, params) -> None:
    import warnings

    import numpy as np

    from flumekit.io.instruments import read_probes
    from flumekit.io.netcdf import read_dataset
    from flumekit.waves import calibration

    raw = read_probes(inputs["probes"], tuple(params["probes"]), params["sampling_rate"])
    cal = read_dataset(inputs["calibration"])
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", calibration.CalibrationWarning)
        eta = calibration.apply(raw["probe_voltage"], cal)
    for w in caught:
        print(f"warning: {inputs['probes']}: {w.message}")
    x = np.array([params["probe_x"][p] for p in params["probes"]])
    write_run(eta.to_dataset().assign_coords(x=("probe", x)), outputs, params,
              "Calibrated surface elevation per probe",
              f"flumekit eta stage from {inputs['probes']} and {inputs['calibration']}")
