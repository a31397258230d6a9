"""What every stage needs to declare its rules: the campaign, where things live, its parameters."""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:  # planning from the rules' cache never reads a campaign
    from flumekit.campaign import Campaign


@dataclass(frozen=True)
class Context:
    """What a stage's ``rules`` receive.

    Attributes
    ----------
    campaign : flumekit.campaign.Campaign
        The campaign (read, or planned by the virtual flume).
    processed : pathlib.Path
        The processed data folder.
    params : dict
        The pipeline's ``[stages]`` table: stage -> parameters.
    scenes : dict
        The pipeline's scenes: name -> target patterns.
    """

    campaign: Campaign
    processed: Path
    params: dict[str, dict[str, Any]] = field(default_factory=dict)
    #: the pipeline's scenes (name -> target patterns): what it asks to build
    scenes: dict[str, list[str]] = field(default_factory=dict)

    def stage_params(self, stage: str, defaults: dict[str, Any]) -> dict[str, Any]:
        """Return a stage's defaults overridden by its ``[stages.<stage>]`` parameters.

        Parameters
        ----------
        stage : str
            The stage's name.
        defaults : dict
            Its ``DEFAULTS``.

        Returns
        -------
        dict
            The parameters.

        Raises
        ------
        flumekit.errors.FlumekitError
            For a parameter the stage does not have.
        """
        given = self.params.get(stage, {})
        unknown = set(given) - set(defaults)
        if unknown:
            from flumekit.errors import FlumekitError

            raise FlumekitError(f"pipeline: unknown parameter(s) {sorted(unknown)} for stage "
                                f"'{stage}'; known: {sorted(defaults)}")
        return {**defaults, **given}

    def out(self, *parts: str) -> Path:
        """Return the path of ``parts`` joined under the processed folder."""
        return self.processed.joinpath(*parts)

    @property
    def campaign_file(self) -> Path:
        """Path of the campaign's ``campaign.toml``."""
        return self.campaign.root / "campaign.toml"
