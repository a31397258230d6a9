"""Stage: probe calibration from the static submersions (only for probes recorded in volts)."""

from __future__ import annotations

from flumekit.pipeline.rules import Rule
from flumekit.stages.context import Context

VERSION = "1"


DEFAULTS = {"order": 1}
DOCS = {"order": "order of the calibration polynomial, level [m] against voltage [V]"}


def rules(ctx: Context) -> list[Rule]:
    params = ctx.stage_params("calibration", DEFAULTS)
    if ctx.campaign.probes.calibrated:  # probes recorded in length units need no calibration
        return []
    params["probes"] = list(ctx.campaign.probes.names)
    params["dialect"] = ctx.campaign.dialect("calibration")
    return [Rule("calibration", "flumekit.stages.calibration:build",
                 inputs={"calibration": ctx.campaign.calibration_file},
                 outputs={"dataset": ctx.out("calibration.nc")}, params=params, version=VERSION)]


def build(inputs, outputs, params) -> None:
    import warnings

    from flumekit import conventions
    from flumekit.io.instruments import read_calibration
    from flumekit.io.netcdf import write_dataset
    from flumekit.waves import calibration

    raw = read_calibration(inputs["calibration"], tuple(params["probes"]), params["dialect"])
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", calibration.CalibrationWarning)
        ds = calibration.fit(raw, order=params["order"])
    for w in caught:
        print(f"warning: {inputs['calibration']}: {w.message}")
    ds = ds.merge(raw[["calibration_voltage"]])
    ds.attrs.update(conventions.global_attrs(
        "Wave probe calibration (static submersions, least squares)",
        f"flumekit calibration stage from {inputs['calibration']}", params))
    write_dataset(ds, outputs["dataset"])
