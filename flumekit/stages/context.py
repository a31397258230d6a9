"""What every stage needs to declare its rules: the campaign, where things live, its parameters."""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:  # planning from the rules' cache never reads a campaign
    from flumekit.campaign import Campaign


@dataclass(frozen=True)
class Context:
    campaign: Campaign
    processed: Path
    params: dict[str, dict[str, Any]] = field(default_factory=dict)
    #: the pipeline's scenes (name -> target patterns): what it asks to build
    scenes: dict[str, list[str]] = field(default_factory=dict)

    def stage_params(self, stage: str, defaults: dict[str, Any]) -> dict[str, Any]:
        """Defaults overridden by ``[stages.<stage>]`` of the pipeline file (unknown keys fail)."""
        given = self.params.get(stage, {})
        unknown = set(given) - set(defaults)
        if unknown:
            from flumekit.errors import FlumekitError

            raise FlumekitError(f"pipeline: unknown parameter(s) {sorted(unknown)} for stage "
                                f"'{stage}'; known: {sorted(defaults)}")
        return {**defaults, **given}

    def out(self, *parts: str) -> Path:
        return self.processed.joinpath(*parts)

    @property
    def campaign_file(self) -> Path:
        return self.campaign.root / "campaign.toml"
