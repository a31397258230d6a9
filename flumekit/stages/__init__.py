"""Stages: thin rules that read datasets, call domain functions, attach metadata and write.

Each stage module has ``rules(ctx, params) -> list[Rule]`` (cheap: no heavy imports; ``params``
are its ``[stages.<name>]`` parameters over its ``DEFAULTS``, from :func:`build_rules`) and action
functions ``action(inputs, outputs, params)`` that do the work when a rule runs. A stage with
parameters declares them in ``DEFAULTS`` and documents each in ``DOCS`` (with its unit):
:func:`parameters` collects them for ``flumekit params`` and docs/parameters.md.

A stage declares rules only for the instruments the campaign has (``Campaign.instruments``):
probes alone give calibration (probes in volts only), elevation, waves and their figures; the
flap instruments (flap, PTO, encoder and pressure) add flap, models and comparison; the UVP adds
the velocity field. A stage that needs an instrument beyond the probes says so in ``NEEDS``,
and :func:`build_rules` asks for its rules only when the campaign has it.
"""

from __future__ import annotations

from pathlib import Path

from flumekit.pipeline.rules import Rule
from flumekit.stages.context import Context

#: stage modules in the order their rules are declared
STAGES = ("calibration", "qc", "eta", "waves", "flap", "uvp", "models", "performance",
          "ballscrew", "figures", "uncertainty")


def build_rules(ctx: Context) -> list[Rule]:
    """Return the rules of every stage for a campaign.

    Each stage of :data:`STAGES` is asked for its rules with its ``[stages.<name>]``
    parameters over its ``DEFAULTS``, when the campaign has the instrument it ``NEEDS``.

    Parameters
    ----------
    ctx : flumekit.stages.context.Context
        The campaign, the processed folder and the pipeline's parameters.

    Returns
    -------
    list of flumekit.pipeline.Rule
        The rules, stage by stage in the order of :data:`STAGES`.

    Raises
    ------
    flumekit.errors.InputError
        When the campaign has no run.
    flumekit.errors.FlumekitError
        For an unknown parameter of a stage.
    """
    import importlib

    if not ctx.campaign.runs:
        from flumekit.errors import InputError

        # every stage but the ball-screw study summarises runs: none is a user's mistake
        raise InputError(ctx.campaign.root / "runs", "no run: each run is a folder "
                         "runs/<run>/ holding its run.toml and instrument files (raw/README.md)")
    out: list[Rule] = []
    for name in STAGES:
        mod = importlib.import_module(f"flumekit.stages.{name}")
        # every stage's [stages.<name>] parameters over its DEFAULTS, checked here once
        params = ctx.stage_params(name, getattr(mod, "DEFAULTS", {}))
        if getattr(mod, "NEEDS", "probes") in ctx.campaign.instruments:
            out += mod.rules(ctx, params)
    return out


def parameters() -> dict[str, dict[str, tuple[object, str]]]:
    """Return the parameters of every stage that has some.

    Returns
    -------
    dict
        Stage -> parameter -> ``(default, description with unit)``.

    Examples
    --------
    >>> default, doc = parameters()["flap"]["cutoff"]
    >>> default, doc.endswith("[Hz]")
    (4.0, True)
    """
    import importlib

    out = {}
    for name in STAGES:
        mod = importlib.import_module(f"flumekit.stages.{name}")
        defaults = getattr(mod, "DEFAULTS", None)
        if defaults:
            docs = getattr(mod, "DOCS", {})
            out[name] = {k: (v, docs.get(k, "")) for k, v in defaults.items()}
    return out


def check_stage_params(stages: dict, path: Path) -> None:
    """Check that every ``[stages.<name>]`` of a pipeline file names a stage and its parameters.

    All problems are reported at once, each with the closest known name.

    Parameters
    ----------
    stages : dict
        The pipeline's ``[stages]`` table: stage -> parameters.
    path : pathlib.Path
        The pipeline file, named in the error.

    Raises
    ------
    flumekit.errors.InputError
        Listing every unknown stage and parameter.
    """
    from flumekit.schema import Problem, raise_problems, suggest

    known = parameters()
    problems = []
    for stage, given in stages.items():
        if stage not in known:
            problems.append(Problem(path, f"stages.{stage}", "unknown stage (or a stage without "
                                    f"parameters); known: {', '.join(known)}"
                                    + suggest(stage, list(known))))
            continue
        for k in given:
            if k not in known[stage]:
                problems.append(Problem(path, f"stages.{stage}.{k}", "unknown parameter; known: "
                                        f"{', '.join(known[stage])} (`flumekit params {stage}`)"
                                        + suggest(k, list(known[stage]))))
    raise_problems(path, problems)


def _show(v) -> str:
    return "none" if v is None else repr(v).replace("True", "true").replace("False", "false")


def parameters_markdown() -> str:
    """Return the reference of every stage parameter as Markdown (docs/parameters.md).

    Returns
    -------
    str
        One table per stage: parameter, default, meaning.
    """
    lines = ["# Stage parameters", "",
             "Set in a pipeline file under `[stages.<stage>]`; `flumekit params STAGE` prints "
             "one stage. Generated by `flumekit params --markdown`; do not edit by hand.", ""]
    for stage, params in parameters().items():
        lines += [f"## `[stages.{stage}]`", "", "| parameter | default | meaning |",
                  "| --- | --- | --- |"]
        lines += [f"| `{k}` | `{_show(d)}` | {doc} |" for k, (d, doc) in params.items()]
        lines.append("")
    return "\n".join(lines)


__all__ = ["STAGES", "build_rules", "check_stage_params", "parameters", "parameters_markdown"]
