"""Stages: thin rules that read datasets, call domain functions, attach metadata and write.

Each stage module has ``rules(ctx) -> list[Rule]`` (cheap: no heavy imports) and action
functions ``action(inputs, outputs, params)`` that do the work when a rule runs.
"""

from __future__ import annotations

from flumekit.pipeline.rules import Rule
from flumekit.stages.context import Context

#: stage modules in the order their rules are declared
STAGES = ("calibration", "qc", "eta", "waves", "flap", "uvp", "models", "ballscrew", "figures")


def build_rules(ctx: Context) -> list[Rule]:
    import importlib

    out: list[Rule] = []
    for name in STAGES:
        out += importlib.import_module(f"flumekit.stages.{name}").rules(ctx)
    return out
