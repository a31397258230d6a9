"""Where the UVP phase average lies: a probe fault does not move it; a UVP or flap
fault does, and where no clean window exists the error names the run, the instrument and the
flagged span. Synthetic records here; tests/qc/test_uvp_window.py builds a virtual run."""

import numpy as np
import pytest

from flumekit.uvp.window import Flagged, averaging_start, bad_spans, steady_span

T = 2.0
FS = 25.0


def _waves(seconds=200.0, ramp=40.0):
    """Three probes: a regular wave ramped up over ``ramp`` s, then steady."""
    t = np.arange(int(seconds * FS)) / FS
    env = np.clip(t / ramp, 0, 1)
    eta = np.stack([0.1 * env * np.sin(2 * np.pi * (t - 0.1 * j) / T) for j in range(3)])
    return eta, t


def _span(eta, t):
    return steady_span(eta, t, np.full(3, 0.1), np.full(3, 0.02), 0.75 * T)


def test_steady_span_bridges_a_masked_probe_fault_but_not_an_unsteady_cycle():
    eta, t = _waves()
    clean = _span(eta, t)
    assert 38.0 <= clean[0] <= 42.0 and clean[1] >= 196.0
    masked = eta.copy()
    masked[0, (t > 100) & (t < 108)] = np.nan  # an 8 s flat line QC masked on one probe
    masked[2, (t > 150) & (t < 151)] = np.nan  # a 1 s dropout on another
    assert _span(masked, t) == pytest.approx(clean, abs=1e-9)
    # a cycle whose crest is really off (the flow is not steady there) does cut the span
    off = eta.copy()
    off[1, (t > 120) & (t < 122)] *= 1.2
    s = _span(off, t)
    assert s[1] - s[0] < clean[1] - clean[0] - 60.0


def test_averaging_start_is_the_first_clean_window_and_moves_only_for_the_instruments_read():
    t = np.arange(0, 300, 0.1)
    ref = np.array([41.3, 43.3, 45.3])
    span = (41.0, 280.0)
    clean = {"UVP beam UP1": Flagged(t, np.zeros(t.size, bool))}
    start = averaging_start(ref, T, 50, 3.0, span, clean, max_gap=0.2)
    assert start == pytest.approx(41.3)
    # a beam dropout of 5 s inside the first window: the window moves past it, by whole periods
    bad = (t >= 100.0) & (t <= 105.0)
    moved = averaging_start(ref, T, 50, 3.0, span,
                            {"UVP beam UP1": Flagged(t, bad)}, max_gap=0.2)
    assert moved - 3.0 > 105.0 and (moved - 41.3) / T == pytest.approx(round((moved - 41.3) / T))
    # a gap short enough to be interpolated does not move it
    short = (t >= 100.0) & (t <= 100.1)
    assert averaging_start(ref, T, 50, 3.0, span, {"UVP beam UP1": Flagged(t, short)},
                           max_gap=0.2) == pytest.approx(41.3)


def test_no_clean_window_names_run_instrument_and_span():
    t = np.arange(0, 300, 0.1)
    bad = (t >= 150.0) & (t <= 170.0)
    with pytest.raises(ValueError) as e:
        averaging_start(np.array([41.3]), T, 100, 3.0, (41.0, 280.0),
                        {"UVP beam UP2": Flagged(t, bad),
                         "flap angle": Flagged(t, np.zeros(t.size, bool))},
                        max_gap=0.2, run="uvp_z0.300_r0")
    msg = str(e.value)
    assert "uvp_z0.300_r0" in msg and "UVP beam UP2" in msg and "150.00-170.00 s" in msg
    assert "flap angle" not in msg
    with pytest.raises(ValueError, match="holds fewer than the 150 periods"):
        averaging_start(np.array([41.3]), T, 150, 3.0, (41.0, 280.0), {}, max_gap=0.2)


def test_bad_spans_only_longer_than_the_interpolation_limit():
    t = np.arange(100) * 0.1
    bad = np.zeros(100, bool)
    bad[10:12] = True  # 0.2 s
    bad[50:60] = True  # 1 s
    assert bad_spans(Flagged(t, bad), max_gap=0.25) == [(pytest.approx(5.0), pytest.approx(5.9))]
