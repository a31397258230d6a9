"""Stage: every figure, drawn from processed datasets, one rule per figure.

The QC figures also read the raw probe and flap files, which the QC products do not repeat.

``fig05a`` ... ``fig12`` are the figures of Brito et al. (2020); ``bs_fig09`` ... ``bs_fig18``
those of Senatore & De Simone (2022); ``separation/<run>`` the incident/reflected separation of
every wave run; ``power_matrix`` and ``capture_width_ratio`` those of the irregular runs
(:mod:`flumekit.figures.performance`). Single-run figures use the run named by
``[stages.figures] run`` (default: the paper's UVP condition T = 3.5 s, H = 0.25 m). Each
figure is written in every format of ``[stages.figures] formats`` (default PNG at 300 dpi and
PDF), after passing the figure test (:mod:`flumekit.figures.check`). A rule names its figure,
which the figure modules register (:mod:`flumekit.figures.registry`), and its inputs; this
stage knows no figure function.
"""

from __future__ import annotations

from flumekit.pipeline.rules import Rule
from flumekit.stages.common import RAW, raw_reading
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
    """Declare one rule ``figure/<name>`` per figure the campaign can draw (module notes).

    ``p`` holds the ``[stages.figures]`` parameters; an empty or unknown ``formats`` is a
    FlumekitError, a ``run`` the campaign lacks a KeyError.
    """
    from flumekit.figures.style import FORMATS
    from flumekit.stages.ballscrew import FIGURE_SOURCES
    from flumekit.stages.ballscrew import wanted as ballscrew_wanted

    formats = [p["formats"]] if isinstance(p["formats"], str) else list(p["formats"])
    bad = [f for f in formats if f not in FORMATS]
    if bad or not formats:
        from flumekit.errors import FlumekitError

        raise FlumekitError(f"pipeline: [stages.figures] formats {formats} must be a non-empty "
                            f"list of {sorted(FORMATS)}")
    out: list[Rule] = []

    def fig(figure: str, inputs: dict, target: str | None = None, **params) -> None:
        """Add the rule of the registered figure ``figure``, drawn from ``inputs``.

        The figure is looked up in :mod:`flumekit.figures.registry`; the target is
        ``figure/<target>`` (default: the figure's name).
        """
        name = target or figure
        out.append(Rule(f"figure/{name}", "flumekit.stages.figures_run:draw", inputs=inputs,
                        outputs={f: ctx.out("figures", f"{name}.{f}") for f in formats},
                        params={"figure": figure, **params}, version=VERSION))

    run = _figure_run(ctx, p["run"])
    if run is not None:
        waves = ctx.out("waves", f"{run}.nc")
        fig("fig05a", {"waves": waves})
        fig("fig06a", {"waves": waves})
    if run is not None and "flap" in ctx.campaign.instruments:
        flap = ctx.out("flap", f"{run}.nc")
        fig("fig05b", {"flap": flap})
        fig("fig06bcd", {"flap": flap})
        fig("fig10", {"flap": flap, "waves": waves,
                      "comparison": ctx.out("comparison", f"{run}.nc")})
        # one wave run per condition (the UVP runs repeat the paper's condition)
        pressure = []
        for cond in p["pressure_runs"]:
            match = sorted((r for r in ctx.campaign.runs if r.kind == "waves"
                            and [r.period, r.height] == list(cond)), key=lambda r: r.repeat)
            pressure += [match[0].id] if match else []
        fig("fig07", {r: ctx.out("flap", f"{r}.nc") for r in (pressure or [run])})
        every = {r.id: ctx.out("comparison", f"{r.id}.nc") for r in ctx.campaign.runs
                 if not r.irregular}  # Figs. 8-9: regular waves (amplitudes, C_f)
        fig("fig08", every)
        fig("fig09", every)
    if "flap" in ctx.campaign.instruments and any(r.irregular for r in ctx.campaign.runs):
        matrix = {"matrix": ctx.out("power_matrix.nc")}
        fig("power_matrix", matrix)
        fig("capture_width_ratio", matrix)
    for r in ctx.campaign.runs:
        # the QC products and the raw files they were made from (the values as read)
        fig("qc", _qc_inputs(ctx, r), target=f"qc/{r.id}", reading=raw_reading(ctx, r),
            run=r.id)
    for r in ctx.campaign.runs:
        if r.kind in ("waves", "irregular"):
            fig("separation_irregular" if r.irregular else "separation",
                {"waves": ctx.out("waves", f"{r.id}.nc")}, target=f"separation/{r.id}")
    if any(r.kind == "uvp" for r in ctx.campaign.runs) and ctx.campaign.uvp is not None:
        fig("fig11", {"field": ctx.out("uvp_field.nc")})
        fig("fig12", {"field": ctx.out("uvp_field.nc")})
    for n, step in (FIGURE_SOURCES.items() if ballscrew_wanted(ctx) else ()):
        fig(f"bs_fig{n:02d}", {step: ctx.out("ballscrew", f"{step}.nc")})
    return out


def _qc_inputs(ctx: Context, run) -> dict:
    """Return the inputs of the QC figure of ``run``: its QC products and raw files.

    The raw probe and flap files give the values as read, which the products do not repeat.
    """
    inputs = {}
    for kind in raw_reading(ctx, run):
        inputs[kind] = ctx.out("qc", kind, f"{run.id}.nc")
        inputs[f"{kind}{RAW}"] = run.file(kind)
    if ctx.campaign.uvp is not None and run.kind == "uvp":
        inputs["uvp"] = ctx.out("qc", "uvp", f"{run.id}.nc")
    return inputs
