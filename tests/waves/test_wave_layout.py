"""Conditioning of probe layouts: closed form against explicit matrices, singular spacings."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from flumekit.waves import MAX_CONDITION, check_layout, condition_number, probe_spacing, wavenumber

H = 0.825


@settings(max_examples=40, deadline=None)
@given(st.lists(st.floats(-5, 5), min_size=2, max_size=5, unique=True),
       st.floats(0.1, 1.5))
def test_condition_number_equals_numpy_cond_of_the_explicit_matrix(x, f):
    x = np.array(x)
    if np.min(np.diff(np.sort(x))) < 1e-3:
        return
    k = wavenumber(2 * np.pi * f, H)
    m = np.stack([np.exp(-1j * k * x), np.exp(1j * k * x)], axis=1)
    truth = np.linalg.cond(m)
    got = condition_number(x, f, H)
    if truth < 1e6:
        assert got == pytest.approx(truth, rel=1e-8)
    else:
        assert got > 1e5


def test_two_probe_goda_suzuki_limits_and_singularity():
    f = 0.4
    L = 2 * np.pi / wavenumber(2 * np.pi * f, H)
    # Δx/L = 0.05 and 0.45 -> the default threshold cot(π/20)
    for r in (0.05, 0.45):
        assert condition_number([0.0, r * L], f, H) == pytest.approx(MAX_CONDITION, rel=1e-9)
    assert condition_number([0.0, 0.25 * L], f, H) == pytest.approx(1.0, abs=1e-12)
    assert condition_number([0.0, 0.5 * L], f, H) > 1e7  # singular (k Δx = π)


def test_paper_layout_is_sqrt2_conditioned_at_the_design_period():
    # x12 = L/10, x13 = 0.35 L: S = 1 + e^(0.4πi) + e^(1.4πi) = 1, cond = sqrt((3+1)/(3-1))
    x12, x23 = probe_spacing(3.5, H)
    assert condition_number([0, x12, x12 + x23], 1 / 3.5, H) == pytest.approx(np.sqrt(2), rel=1e-12)


def test_check_layout_flags_half_wavelength_spacings():
    f0 = 0.5
    L = 2 * np.pi / wavenumber(2 * np.pi * f0, H)
    bad = check_layout([0.0, 0.5 * L, L], H, band=(0.3, 0.7))
    i = int(np.argmin(np.abs(bad.frequency.values - f0)))
    assert bad.masked.values[i] == 1
    assert 0 < bad.attrs["ill_conditioned_fraction"] < 0.5
    assert "ill-conditioned" in bad.attrs["advice"]
    assert bad.probe_spacing.attrs["units"] == "m"
    x12, x23 = probe_spacing(1 / f0, H)
    good = check_layout([0.0, x12, x12 + x23], H, band=(0.3, 0.7))
    assert good.attrs["ill_conditioned_fraction"] == 0.0
    with pytest.raises(ValueError, match="distinct"):
        check_layout([0.0, 0.0], H, band=(0.3, 0.7))
    with pytest.raises(ValueError, match="band"):
        check_layout([0.0, 1.0], H, band=(0.7, 0.3))
