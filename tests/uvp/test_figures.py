"""Figures 11 and 12 from a field dataset (the virtual flume's true field)."""

from __future__ import annotations

import numpy as np
import pytest

from flumekit.figures.uvp import PHASES, fig11, fig12
from flumekit.synth.uvp import true_field


@pytest.fixture(scope="module")
def field(campaign):
    f = true_field(campaign, period=3.5, height=0.25, reflection=0.2, reflection_phase=0.6)
    f.attrs["water_depth"] = campaign.flume.water_depth
    return f


def test_fig11_panels(field):
    fig = fig11(field)
    axes = [ax for ax in fig.axes if ax.get_visible() and ax.get_title(loc="left")]
    assert [ax.get_title(loc="left") for ax in axes] == [
        f"({t}) t/T = {p:.2f}" for t, p in zip("abcdef", PHASES)]
    assert all(ax.collections for ax in axes)  # contours and arrows drawn in every panel


def test_fig12_profiles_at_section(field):
    fig = fig12(field, truth=field)
    ax = fig.axes[0]
    line = ax.get_lines()[0]  # <u>/U0 at t/T = 0
    h = field.attrs["water_depth"]
    expected = field["u_normalised"].interp(x=-0.11 * h).isel(phase=0).values
    np.testing.assert_allclose(line.get_xdata(), expected)
    np.testing.assert_allclose(line.get_ydata(), field["z"].values / h)


def test_figures_need_water_depth(field):
    bad = field.copy()
    bad.attrs["water_depth"] = float("nan")
    with pytest.raises(ValueError, match="water_depth"):
        fig11(bad)
