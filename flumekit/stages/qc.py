"""Stage: quality control of every run's instrument records, before any analysis.

Per run and instrument one rule reads the raw record, checks it against its metadata (dead or
stuck channels, the declared period), runs the QARTOD battery of :mod:`flumekit.qc` and writes
``qc/<instrument>/<run>.nc``: the QC'd values (failed samples masked, short gaps interpolated),
the per-sample QARTOD flags and the counts. The eta and flap stages read these instead of the
raw files. The values as read are not repeated (the QC figure reads the raw files), and the
probe and flap products are not deflated. The rules' actions are in
:mod:`flumekit.stages.qc_records` (probes, flap) and :mod:`flumekit.stages.qc_summary`; the
parameters in :mod:`flumekit.stages.qc_params`.

The UVP beams are checked (Goring-Nikora despiking, echo level) by the rule that analyses them,
before its analysis, where its average reads (:mod:`flumekit.stages.uvp_run`): their analysis
reads the beams whole, and a rule of its own would read them and the waves a second time.
"""

from __future__ import annotations

from flumekit.pipeline.rules import Rule
from flumekit.stages.common import COMPRESS, raw_reading, read_raw  # noqa: F401  (bench, tests)
from flumekit.stages.context import Context
from flumekit.stages.qc_params import DEFAULTS, DOCS  # noqa: F401  (the stage's parameters)
from flumekit.stages.qc_records import flap, probes  # noqa: F401  (the rules' actions)
from flumekit.stages.qc_summary import summary  # noqa: F401
from flumekit.stages.runs import run_params

VERSION = "5"


def rules(ctx: Context, params: dict) -> list[Rule]:
    """Return the quality-control rules of every run and the campaign's QC summary.

    Protocol: :mod:`flumekit.stages`. Per run ``qc/probes/<run>`` (and ``qc/flap/<run>`` with the
    flap instruments), each with the stage's QARTOD thresholds (U.S. IOOS 2020, QARTOD manual for
    in-situ surface wave data), the run's parameters and its raw reading; then ``qc_summary``.
    """
    c = ctx.campaign
    out = []
    for run in c.runs:
        rp = {**params, **run_params(run, c)}
        reading = raw_reading(ctx, run)
        out.append(Rule(f"qc/probes/{run.id}", "flumekit.stages.qc_records:probes",
                        inputs={"probes": run.file("probes"), "run": run.path / "run.toml"},
                        outputs={"dataset": ctx.out("qc", "probes", f"{run.id}.nc")},
                        params={**rp, **reading["probes"], "probe_x": run.probe_x},
                        version=VERSION, run=run.id))
        if "flap" in c.instruments:
            out.append(Rule(f"qc/flap/{run.id}", "flumekit.stages.qc_records:flap",
                            inputs={"flap": run.file("flap"), "run": run.path / "run.toml"},
                            outputs={"dataset": ctx.out("qc", "flap", f"{run.id}.nc")},
                            params={**rp, **reading["flap"]}, version=VERSION, run=run.id))
    inputs = {f"{kind}/{r.id}": ctx.out("qc", kind, f"{r.id}.nc")
              for r in c.runs for kind in ("probes", "flap")
              if kind == "probes" or "flap" in c.instruments}
    out.append(Rule("qc_summary", "flumekit.stages.qc_summary:summary", inputs=inputs,
                    outputs={"dataset": ctx.out("qc_summary.nc")},
                    params={"clock_tolerance": params["clock_tolerance"],
                            "conditions": {r.id: [r.period, r.height] for r in c.runs}},
                    version=VERSION))
    return out


def __getattr__(name: str):
    """Return ``WARNINGS`` of :mod:`flumekit.conventions`, for callers that read it from here.

    Loaded on use: planning imports no xarray.
    """
    if name == "WARNINGS":
        from flumekit.conventions import WARNINGS

        return WARNINGS
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
