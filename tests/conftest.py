"""Fixtures that tests of several folders share: the default campaign and one regular run."""

from __future__ import annotations

import os
import shutil
from importlib import resources
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

#: the project's root (the shipped pipelines are in its pipelines/)
ROOT = Path(__file__).resolve().parents[1]
#: still-water depth of the default campaign's flume [m]
DEPTH = 0.825


@pytest.fixture(scope="session")
def campaign(tmp_path_factory):
    """The default campaign (``flumekit/data/default_campaign.toml``), loaded from a copy."""
    from flumekit.campaign import load_campaign

    root = tmp_path_factory.mktemp("campaign")
    src = resources.files("flumekit.data").joinpath("default_campaign.toml")
    with resources.as_file(src) as path:
        shutil.copy(path, root / "campaign.toml")
    return load_campaign(root)


@pytest.fixture(scope="session")
def regular_waves():
    """The waves analysis of a 2 s, 0.15 m regular wave of the virtual flume: four probes, the
    first three spaced for the separation, 80 periods at 25 Hz."""
    from flumekit.synth.waves import regular_wave_field
    from flumekit.waves import analyse_run, probe_spacing

    period = 2.0
    x12, x23 = probe_spacing(period, DEPTH)
    x = np.array([-7.0, -7.0 + x12, -7.0 + x12 + x23, -1.0])
    t = np.arange(int(80 * period * 25)) / 25.0
    f = regular_wave_field(t, x, period=period, height=0.15, depth=DEPTH)
    da = xr.DataArray(f.eta.values, dims=("probe", "time"),
                      coords={"probe": ["WP1", "WP2", "WP3", "WP4"], "x": ("probe", x),
                              "time": t})
    return analyse_run(da, DEPTH, period, x_ref=0.0, separation_probes=["WP1", "WP2", "WP3"])


@pytest.fixture
def action_module(tmp_path, monkeypatch):
    """Write a module of rule actions, importable here and in the processes a make starts.

    Returns ``write(name, source)``: the module ``name`` with ``source`` in ``tmp_path/mods``,
    on ``sys.path`` and ``PYTHONPATH`` for the test's duration.
    """
    folder = tmp_path / "mods"
    folder.mkdir()
    monkeypatch.syspath_prepend(str(folder))
    monkeypatch.setenv("PYTHONPATH", str(folder) + os.pathsep + os.environ.get("PYTHONPATH", ""))

    def write(name: str, source: str) -> None:
        (folder / f"{name}.py").write_text(source)

    return write


@pytest.fixture
def fresh_project(tmp_path):
    """A project folder as a fresh clone has it before its first make: the shipped default and
    small pipelines, no raw or processed data."""
    (tmp_path / "pipelines").mkdir()
    for name in ("default.toml", "small.toml"):
        shutil.copy(ROOT / "pipelines" / name, tmp_path / "pipelines" / name)
    return tmp_path
