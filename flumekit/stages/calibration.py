"""Stage: probe calibration from the static submersions."""

from __future__ import annotations

from flumekit.pipeline.rules import Rule
from flumekit.stages.context import Context

VERSION = "1"


def rules(ctx: Context) -> list[Rule]:
    params = ctx.stage_params("calibration", {"order": 1})
    params["probes"] = list(ctx.campaign.probes.names)
    return [Rule("calibration", "flumekit.stages.calibration:build",
                 inputs={"calibration": ctx.campaign.calibration_file},
                 outputs={"dataset": ctx.out("calibration.nc")}, params=params, version=VERSION)]


def build(inputs, outputs, params) -> None:
    import warnings

    from flumekit.io.instruments import read_calibration
    from flumekit.io.netcdf import write_product
    from flumekit.waves import calibration

    raw = read_calibration(inputs["calibration"], tuple(params["probes"]))
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", calibration.CalibrationWarning)
        ds = calibration.fit(raw, order=params["order"])
    for w in caught:
        print(f"warning: {inputs['calibration']}: {w.message}")
    ds = ds.merge(raw[["calibration_voltage"]])
    write_product(ds, outputs["dataset"],
                  "Wave probe calibration (static submersions, least squares)",
                  f"flumekit calibration stage from {inputs['calibration']}", params)
