"""Stage: every figure, drawn from processed datasets (the QC figures also from the raw probe
and flap files, which the QC products do not repeat), one rule per figure.

``fig05a`` ... ``fig12`` are the figures of Brito et al. (2020); ``bs_fig09`` ... ``bs_fig18``
those of Senatore & De Simone (2022); ``separation/<run>`` the incident/reflected separation of
every wave run; ``power_matrix`` and ``capture_width_ratio`` those of the irregular runs
(:mod:`flumekit.figures.performance`). Single-run figures use the run named by
``[stages.figures] run`` (default: the paper's UVP condition T = 3.5 s, H = 0.25 m). Each
figure is written in every format of ``[stages.figures] formats`` (default PNG at 300 dpi and
PDF), after passing the figure test (:mod:`flumekit.figures.check`).
"""

from __future__ import annotations

from flumekit.pipeline.rules import Rule
from flumekit.stages.context import Context

VERSION = "4"
DEFAULTS = {"run": "auto", "formats": ["png", "pdf"],
            "pressure_runs": [[3.5, 0.25], [2.5, 0.2]]}
DOCS = {
    "run": "run of the single-run figures; 'auto': the paper's T = 3.5 s, H = 0.25 m run, else "
           "the first",
    "formats": "figure file formats written for each figure (png, pdf, svg)",
    "pressure_runs": "[period [s], height [m]] of the runs of figure 7",
}


def _figure_run(ctx: Context, wanted: str) -> str | None:
    runs = ctx.campaign.runs
    if not runs:
        return None
    if wanted != "auto":
        ctx.campaign.run(wanted)  # KeyError names the campaign and the run
        return wanted
    waves = [r for r in runs if r.kind == "waves"] or [r for r in runs if not r.irregular]
    if not waves:  # the paper's single-run figures are of a regular run
        return None
    paper = [r for r in waves if (r.period, r.height) == (3.5, 0.25)]
    return (paper or waves)[0].id


def rules(ctx: Context, p: dict) -> list[Rule]:
    from flumekit.figures.style import FORMATS
    from flumekit.stages import qc as qc_stage
    from flumekit.stages.ballscrew import FIGURE_SOURCES
    from flumekit.stages.ballscrew import wanted as ballscrew_wanted

    formats = [p["formats"]] if isinstance(p["formats"], str) else list(p["formats"])
    bad = [f for f in formats if f not in FORMATS]
    if bad or not formats:
        from flumekit.errors import FlumekitError

        raise FlumekitError(f"pipeline: [stages.figures] formats {formats} must be a non-empty "
                            f"list of {sorted(FORMATS)}")
    out: list[Rule] = []

    def fig(name: str, draw: str, inputs: dict, **params) -> None:
        out.append(Rule(f"figure/{name}", "flumekit.stages.figures:draw", inputs=inputs,
                        outputs={f: ctx.out("figures", f"{name}.{f}") for f in formats},
                        params={"draw": draw, **params}, version=VERSION))

    run = _figure_run(ctx, p["run"])
    if run is not None:
        waves = ctx.out("waves", f"{run}.nc")
        fig("fig05a", "waves:figure_5a", {"waves": waves})
        fig("fig06a", "waves:figure_6a", {"waves": waves})
    if run is not None and "flap" in ctx.campaign.instruments:
        flap = ctx.out("flap", f"{run}.nc")
        fig("fig05b", "flap:figure_5b", {"flap": flap})
        fig("fig06bcd", "flap:figure_6bcd", {"flap": flap})
        fig("fig10", "flap:figure_10", {"flap": flap, "waves": waves,
                                        "comparison": ctx.out("comparison", f"{run}.nc")})
        # one wave run per condition (the UVP runs repeat the paper's condition)
        pressure = []
        for cond in p["pressure_runs"]:
            match = sorted((r for r in ctx.campaign.runs if r.kind == "waves"
                            and [r.period, r.height] == list(cond)), key=lambda r: r.repeat)
            pressure += [match[0].id] if match else []
        fig("fig07", "flap:figure_7",
            {r: ctx.out("flap", f"{r}.nc") for r in (pressure or [run])})
        every = {r.id: ctx.out("comparison", f"{r.id}.nc") for r in ctx.campaign.runs
                 if not r.irregular}  # Figs. 8-9: regular waves (amplitudes, C_f)
        fig("fig08", "flap:figure_8", every)
        fig("fig09", "flap:figure_9", every)
    if "flap" in ctx.campaign.instruments and any(r.irregular for r in ctx.campaign.runs):
        matrix = {"matrix": ctx.out("power_matrix.nc")}
        fig("power_matrix", "performance:figure_power_matrix", matrix)
        fig("capture_width_ratio", "performance:figure_capture_width_ratio", matrix)
    for r in ctx.campaign.runs:
        # the QC products and the raw files they were made from (the values as read)
        qc, reading = qc_stage.figure_inputs(ctx, r)
        fig(f"qc/{r.id}", "qc:figure_qc", qc, **reading)
    for r in ctx.campaign.runs:
        if r.kind in ("waves", "irregular"):
            fig(f"separation/{r.id}", "sea_state:separation" if r.irregular
                else "waves:separation", {"waves": ctx.out("waves", f"{r.id}.nc")})
    if any(r.kind == "uvp" for r in ctx.campaign.runs) and ctx.campaign.uvp is not None:
        fig("fig11", "uvp:fig11", {"field": ctx.out("uvp_field.nc")})
        fig("fig12", "uvp:fig12", {"field": ctx.out("uvp_field.nc")})
    for n, step in (FIGURE_SOURCES.items() if ballscrew_wanted(ctx) else ()):
        fig(f"bs_fig{n:02d}", f"ballscrew:FIGURES[{n}]",
            {step: ctx.out("ballscrew", f"{step}.nc")})
    return out


def _function(draw: str):
    import importlib

    module, _, name = draw.partition(":")
    mod = importlib.import_module(f"flumekit.figures.{module}")
    if "[" in name:  # a registry entry such as FIGURES[11]
        table, key = name.rstrip("]").split("[")
        return getattr(mod, table)[int(key)]
    return getattr(mod, name)


def _description(fn) -> str:
    """What a figure shows: the first paragraph of its function's docstring, on one line."""
    import inspect

    doc = inspect.getdoc(fn) or ""
    return " ".join(doc.split("\n\n", 1)[0].split())


def draw(inputs, outputs, params) -> None:
    import numpy as np

    from flumekit.figures.check import assert_passes
    from flumekit.figures.style import laid_out, save, style
    from flumekit.io.netcdf import read_dataset

    draw = params["draw"]
    if draw == "qc:figure_qc":  # raw files among the inputs, read by their instrument readers
        from flumekit.stages.qc import figure_data

        data = figure_data(inputs, params)
    else:
        data = {k: read_dataset(v) for k, v in inputs.items()}
    fn = _function(draw)
    with style():
        if draw == "flap:figure_10":
            # the measured elevation at the probe nearest the flap, over the whole record
            # (the separated incident wave exists only in the waves' own steady window)
            eta = data["waves"]["eta"]
            comp = data["comparison"]
            models = {str(s): comp.sel(source=s) for s in comp["source"].values
                      if str(s) != "experiment"}
            fig = fn(data["flap"], eta=eta.isel(probe=int(np.argmin(np.abs(eta["x"].values)))),
                     models=models)
        elif draw in ("flap:figure_8", "flap:figure_9"):
            comps = [data[k] for k in sorted(data)]
            models = {str(s): [c.sel(source=s) for c in comps]
                      for s in comps[0]["source"].values if str(s) != "experiment"}
            fig = fn([c.sel(source="experiment") for c in comps], models=models)
        elif draw == "qc:figure_qc":
            fig = fn(**data)
        elif draw == "flap:figure_7":
            fig = fn([data[k] for k in sorted(data)])
        else:
            (ds,) = data.values()
            fig = fn(ds)
    with laid_out(fig):  # one layout, and one drawing for the check and the PNG
        save(fig, *outputs.values(), check=lambda f: assert_passes(f, f"figure {draw}"),
             description=_description(fn))
