"""Stages: thin rules that read datasets, call domain functions, attach metadata and write.

Every stage module follows one protocol, documented here once; its own docstrings say only
what is particular to it (the inputs it reads, the outputs it writes, its own parameters):

``rules(ctx, params) -> list[Rule]``
    Declare the stage's rules (:class:`flumekit.pipeline.Rule`) for a campaign: each names
    its target, its action ``"flumekit.stages.<module>:<action>"``, its input and output
    files, its parameters and the stage's ``VERSION``. Cheap: no heavy imports. ``ctx`` is
    the :class:`~flumekit.stages.context.Context` (the campaign, the processed folder under
    which ``ctx.out(...)`` names the products, the pipeline's ``[stages]`` table and scenes);
    ``params`` are the stage's ``[stages.<name>]`` parameters over its ``DEFAULTS``, from
    :func:`build_rules`. An empty list when the campaign or pipeline has nothing for it.
``action(inputs, outputs, params) -> Written``
    Do a rule's work when it runs. ``inputs`` and ``outputs`` are dicts of str to
    :class:`pathlib.Path`: the files the rule reads (products of other rules, raw files, some
    only named in messages) and the ones it writes (``dataset`` unless the rule says
    otherwise); ``params`` are the rule's parameters (JSON-able, units as in the stage's
    ``DOCS``). It returns the :class:`~flumekit.io.atomic.Written` (file and content digest)
    its writer returned, for the engine (:mod:`flumekit.pipeline.rules`; a list for several
    files, None: the engine identifies the outputs by their bytes), and raises
    :class:`~flumekit.errors.InputError` naming the file for input it cannot analyse.

A stage with parameters declares them in ``DEFAULTS`` and documents each in ``DOCS`` (with its
unit): :func:`parameters` collects them for ``flumekit params`` and docs/parameters.md
(:mod:`flumekit.stages.catalogue`, with the order of the stages, :data:`STAGES`).

A stage declares rules only for the instruments the campaign has (``Campaign.instruments``):
probes alone give calibration (probes in volts only), elevation, waves and their figures; the
flap instruments (flap, PTO, encoder and pressure) add flap, models and comparison; the UVP adds
the velocity field. A stage that needs an instrument beyond the probes says so in ``NEEDS``,
and :func:`build_rules` asks for its rules only when the campaign has it.

Examples
--------
>>> STAGES[:4]
('calibration', 'qc', 'eta', 'waves')
"""

from __future__ import annotations

from flumekit.pipeline.rules import Rule
from flumekit.stages.catalogue import STAGES, check_stage_params, parameters, parameters_markdown
from flumekit.stages.context import Context


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

    Examples
    --------
    The rules of the small virtual campaign, planned without writing anything, with a lower
    cut-off for the flap: one run's targets, stage by stage, and the flap rules' parameter.

    >>> from pathlib import Path
    >>> from flumekit.stages.context import Context
    >>> from flumekit.synth.campaign import virtual_campaign
    >>> campaign = virtual_campaign("raw/small", "small", 2020)
    >>> rules = build_rules(Context(campaign, Path("processed"), {"flap": {"cutoff": 3.0}}))
    >>> [r.target.rsplit("/", 1)[0] for r in rules if r.run == "T2.00_H0.150_r0"]
    ['qc/probes', 'qc/flap', 'eta', 'waves', 'flap', 'comparison', 'uncertainty']
    >>> {r.params["cutoff"] for r in rules if r.target.startswith("flap/")}
    {3.0}
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


__all__ = ["STAGES", "build_rules", "check_stage_params", "parameters", "parameters_markdown"]
