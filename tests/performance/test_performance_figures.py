"""The power-matrix and capture-width-ratio figures pass the figure test."""

import numpy as np
import pytest
import xarray as xr

from flumekit.figures.check import problems
from flumekit.figures.performance import figure_capture_width_ratio, figure_power_matrix
from flumekit.performance import power_matrix

SOURCES = ["experiment", "analytical", "simulator"]


def matrix() -> xr.Dataset:
    """Eight runs over a 2 x 3 matrix (the cell Hm0 0.1 m, Te 2.2 s empty), three sources."""
    rng = np.random.default_rng(2)
    hm0 = np.array([0.05, 0.052, 0.049, 0.05, 0.1, 0.098, 0.101, 0.1])
    te = np.array([1.5, 1.52, 1.8, 2.2, 1.5, 1.8, 1.82, 1.55])
    cwr = 0.3 + 0.1 * np.sin(te)[:, None] + rng.normal(0, 0.01, (8, 3)) + [0.0, 0.08, -0.04]
    power = cwr * 40 * hm0[:, None] ** 2
    ds = power_matrix(hm0, te, {"mean_power": power, "capture_width_ratio": cwr},
                      [0.025, 0.075, 0.125], [1.35, 1.65, 2.0, 2.4], sources=SOURCES)
    per_run = xr.Dataset({"run_hm0": ("run", hm0), "run_te": ("run", te),
                          "run_capture_width_ratio": (("run", "source"), cwr)},
                         coords={"run": [f"r{i}" for i in range(8)], "source": SOURCES})
    return ds.merge(per_run)


@pytest.mark.parametrize("draw", [figure_power_matrix, figure_capture_width_ratio])
def test_figures_pass_the_figure_test(draw, tmp_path):
    from flumekit.figures.style import save, style

    with style():
        fig = draw(matrix())
    assert problems(fig) == []
    save(fig, tmp_path / f"{draw.__name__}.png")


@pytest.mark.parametrize("draw", [figure_power_matrix, figure_capture_width_ratio])
def test_a_figure_drawn_by_hand_is_the_pipelines(draw, tmp_path):
    """Outside ``style()`` (a notebook) a registered figure is built in the package style all
    the same: the same PNG bytes as drawn within it, as the figures stage draws."""
    from flumekit.figures.registry import FIGURES
    from flumekit.figures.style import save, style

    assert any(f.function is draw for f in FIGURES.values())  # what the pipeline calls
    (by_hand,) = save(draw(matrix()), tmp_path / "by_hand.png")
    with style():
        fig = draw(matrix())
    (pipeline,) = save(fig, tmp_path / "pipeline.png")
    assert by_hand.read_bytes() == pipeline.read_bytes()


def test_power_matrix_figure_writes_counts_in_cells():
    fig = figure_power_matrix(matrix())
    texts = [t.get_text() for t in fig.axes[0].texts]
    assert sum("n = " in t for t in texts) == 5  # five occupied cells, the sixth empty
    assert any("n = 2" in t for t in texts)


def test_figure_refuses_other_datasets():
    with pytest.raises(ValueError, match="power_matrix"):
        figure_power_matrix(xr.Dataset({"x": 1.0}))
