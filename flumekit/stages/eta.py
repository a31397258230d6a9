"""Stage: surface elevation at every probe of a run, relative to the still-water level.

Probes recorded in volts are calibrated (the ``calibration`` target); probes recorded in length
units skip the calibration. The still-water level is then removed by the declared rule
(``still_water`` of the run, else of the campaign's ``[probes]``; default ``"none"`` for
calibrated voltages, whose calibration levels already refer to still water, and ``"mean"`` for
lengths) and recorded in the dataset.
"""

from __future__ import annotations

from flumekit.pipeline.rules import Rule
from flumekit.stages.context import Context
from flumekit.stages.runs import run_params, write_run

VERSION = "3"


def rules(ctx: Context) -> list[Rule]:
    c = ctx.campaign
    calibrated = c.probes.calibrated
    out = []
    for run in c.runs:
        rule = run.still_water if run.still_water is not None else c.probes.still_water
        if rule is None:
            rule = "mean" if calibrated else "none"
        params = {"probes": list(c.probes.names), "probe_x": run.probe_x,
                  "sampling_rate": c.probes.sampling_rate, "kind": run.kind,
                  "dialect": c.dialect("probes"), "units": c.probes.units,
                  "time_offset": run.clock.get("probes", 0.0), "still_water": rule,
                  **run_params(run)}
        inputs = {"probes": run.file("probes")}
        if not calibrated:
            inputs["calibration"] = ctx.out("calibration.nc")
        out.append(Rule(f"eta/{run.id}", "flumekit.stages.eta:build", inputs=inputs,
                        outputs={"dataset": ctx.out("eta", f"{run.id}.nc")},
                        params=params, version=VERSION, run=run.id))
    return out


def build(inputs, outputs, params) -> None:
    import warnings

    import numpy as np

    from flumekit.errors import InputError
    from flumekit.io.instruments import read_probes
    from flumekit.io.netcdf import read_dataset
    from flumekit.waves import calibration
    from flumekit.waves.still_water import remove_still_water

    raw = read_probes(inputs["probes"], tuple(params["probes"]), params["sampling_rate"],
                      params["dialect"], units=params["units"],
                      time_offset=params["time_offset"])
    if "probe_voltage" in raw:
        cal = read_dataset(inputs["calibration"])
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always", calibration.CalibrationWarning)
            elevation = calibration.apply(raw["probe_voltage"], cal)
        for w in caught:
            print(f"warning: {inputs['probes']}: {w.message}")
        source = f"{inputs['probes']} and {inputs['calibration']}"
    else:
        elevation = raw["probe_elevation"]
        source = f"{inputs['probes']} (calibrated probes)"
    try:
        eta, level = remove_still_water(elevation, params["still_water"])
    except ValueError as e:
        raise InputError(inputs["probes"], str(e), field="still_water") from None
    x = np.array([params["probe_x"][p] for p in params["probes"]])
    ds = eta.to_dataset().assign_coords(x=("probe", x))
    ds["still_water_level"] = level
    ds.attrs.update(still_water_rule=level.attrs["rule"], time_offset=params["time_offset"])
    write_run(ds, outputs, params, "Surface elevation per probe",
              f"flumekit eta stage from {source}")
