"""Rules that synthesise a virtual-flume campaign lazily: only what a requested target reads.

``synth/campaign`` writes the campaign-wide files (``campaign.toml``, the probe calibration) and
``synth/<run>`` one run; each is declared to produce exactly the raw files the stage rules read,
so `make ballscrew` synthesises nothing and `make fig10` the base and one run. These are
``source`` rules: they run only where all their files are absent, are never forced, and the
engine never removes what they wrote (raw data is sacred). The synthesis records each run it writes
in the campaign's marker (:mod:`flumekit.synth.marker`), so that a run missing later is known
to have been removed by hand and is never synthesised again (:mod:`flumekit.pipeline.raw`).
"""

from __future__ import annotations

from pathlib import Path

from flumekit.docstrings import doc
from flumekit.pipeline.rules import Rule


@doc
def rules(stage_rules: list[Rule], root: Path, size: str, seed: int,
          run_ids: list[str]) -> list[Rule]:
    """Return the rules that synthesise the raw files the stage rules read.

    Parameters
    ----------
    stage_rules : list of flumekit.pipeline.Rule
        The stages' rules; their inputs under ``root`` are what the synthesis must write.
    root : pathlib.Path
        The raw campaign folder.
    %(size)s
    %(seed)s
    run_ids : list of str
        The planned runs.

    Returns
    -------
    list of flumekit.pipeline.Rule
        ``synth/campaign`` and one ``synth/<run>`` per run, all ``source`` rules.
    """
    runs_dir = (root / "runs").resolve()
    base: dict[str, Path] = {}
    per_run: dict[str, dict[str, Path]] = {r: {} for r in run_ids}
    for rule in stage_rules:
        for p in rule.inputs.values():
            p = Path(p)
            if not p.resolve().is_relative_to(root.resolve()):
                continue
            if p.resolve().is_relative_to(runs_dir):
                run = p.resolve().relative_to(runs_dir).parts[0]
                per_run.setdefault(run, {})[p.name] = p
            else:
                base[str(p.resolve().relative_to(root.resolve()))] = p
    base.setdefault("campaign.toml", root / "campaign.toml")
    out = [Rule("synth/campaign", "flumekit.stages.virtual:base", inputs={}, outputs=base,
                params={"root": str(root), "size": size, "seed": seed}, source=True)]
    for run, files in per_run.items():
        files.setdefault("run.toml", root / "runs" / run / "run.toml")
        out.append(Rule(f"synth/{run}", "flumekit.stages.virtual:run",
                        inputs={"campaign": root / "campaign.toml"}, outputs=files,
                        params={"root": str(root), "run": run}, run=run, source=True))
    return out


def base(inputs, outputs, params) -> None:
    """Write the campaign-wide raw files of a virtual campaign (``campaign.toml``, calibration).

    An action of :mod:`flumekit.stages` (a source rule: it reads nothing), into ``root`` with the
    campaign's ``size`` and ``seed``.
    """
    from flumekit.synth.campaign import write_virtual_base

    write_virtual_base(params["root"], params["size"], int(params["seed"]))


def run(inputs, outputs, params) -> None:
    """Write the raw files of run ``run`` of the virtual campaign in ``root``.

    An action of :mod:`flumekit.stages` (a source rule), after ``campaign`` (campaign.toml).
    """
    from flumekit.synth.campaign import write_virtual_run

    write_virtual_run(params["root"], params["run"])

