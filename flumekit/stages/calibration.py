"""Stage: probe calibration from the static submersions (only for probes recorded in volts)."""

from __future__ import annotations

from flumekit.io.atomic import Written
from flumekit.pipeline.rules import Rule
from flumekit.stages.context import Context

VERSION = "2"
#: ``min_r2``: a fit below it is an error naming the file and probe; ``warn_r2``: a warning
#: recorded in the dataset (:data:`flumekit.conventions.WARNINGS`)
DEFAULTS = {"order": 1, "min_r2": 0.99, "warn_r2": 0.999}
DOCS = {"order": "order of the calibration polynomial, level [m] against voltage [V]",
        "min_r2": "coefficient of determination below which a probe's fit is an error [-]",
        "warn_r2": "coefficient of determination below which a warning is recorded [-]"}


def rules(ctx: Context, params: dict) -> list[Rule]:
    """Return the rule ``calibration``; none for probes recorded in length units.

    Protocol: :mod:`flumekit.stages`; the rule's parameters add the ``probes`` and the
    calibration file's ``dialect`` to the stage's.
    """
    if ctx.campaign.probes.calibrated:  # probes recorded in length units need no calibration
        return []
    params["probes"] = list(ctx.campaign.probes.names)
    params["dialect"] = ctx.campaign.dialect("calibration")
    return [Rule("calibration", "flumekit.stages.calibration:build",
                 inputs={"calibration": ctx.campaign.calibration_file},
                 outputs={"dataset": ctx.out("calibration.nc")}, params=params, version=VERSION)]


def build(inputs, outputs, params) -> Written:
    """Fit each probe's calibration polynomial to its static submersions and write it.

    An action of :mod:`flumekit.stages`: reads the raw ``calibration`` file, writes
    ``calibration.nc``. A probe whose fit is below ``min_r2`` or not monotonic over its
    voltages is an :class:`~flumekit.errors.InputError`; below ``warn_r2``, a recorded warning.
    """
    import warnings

    from flumekit.conventions import WARNINGS
    from flumekit.io.instruments import read_calibration
    from flumekit.io.netcdf import write_product
    from flumekit.qc.checks import check_calibration
    from flumekit.waves import calibration

    raw = read_calibration(inputs["calibration"], tuple(params["probes"]),
                           params.get("dialect"))
    with warnings.catch_warnings():
        # the R² is checked below against the stage's thresholds, naming the file
        warnings.simplefilter("ignore", calibration.CalibrationWarning)
        ds = calibration.fit(raw, order=params["order"])
    v = raw["calibration_voltage"].transpose("sample", "probe").values
    mono = [calibration.is_monotonic(ds["calibration_coefficients"].sel(probe=p).values,
                                     float(v[:, i].min()), float(v[:, i].max()))
            for i, p in enumerate(params["probes"])]
    warned = check_calibration(ds["calibration_r2"].values, mono, params["probes"],
                               inputs["calibration"], params["min_r2"], params["warn_r2"])
    ds = ds.merge(raw[["calibration_voltage"]])
    if warned:
        ds.attrs[WARNINGS] = "\n".join(warned)
    return write_product(ds, outputs["dataset"],
                         "Wave probe calibration (static submersions, least squares)",
                         f"flumekit calibration stage from {inputs['calibration']}", params)
