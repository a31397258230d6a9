"""Shared fixtures of the UVP tests: the default campaign (IMFIA flume of Brito et al. 2020)."""

from __future__ import annotations

from importlib import resources

import pytest

from flumekit.campaign import load_campaign


@pytest.fixture(scope="session")
def campaign(tmp_path_factory):
    d = tmp_path_factory.mktemp("campaign")
    (d / "campaign.toml").write_text(
        resources.files("flumekit.data").joinpath("default_campaign.toml").read_text())
    return load_campaign(d)
