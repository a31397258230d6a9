"""power_matrix against an independent loop over the runs (count, mean, std with ddof = 0)."""

import numpy as np
import pytest

from flumekit.performance import power_matrix

HM0_EDGES = [0.04, 0.08, 0.12, 0.16]
TE_EDGES = [1.0, 1.5, 2.0, 2.5, 3.0]
SOURCES = ["experiment", "analytical", "simulator"]


def _runs(n=40, seed=3):
    rng = np.random.default_rng(seed)
    hm0 = rng.uniform(0.03, 0.119, n)  # some below the first edge, none in the last Hm0 row
    te = rng.uniform(1.0, 2.6, n)
    hm0[0], te[0] = 0.08, 1.5  # exactly on an edge: belongs to the bin it opens
    hm0[1] = np.nan
    power = rng.gamma(2.0, 1.0, (n, 3)) * 1e3 + 5e3  # a large mean: cancellation would show
    cwr = rng.uniform(0.1, 0.6, n)
    return hm0, te, power, cwr


def test_matches_an_independent_loop():
    hm0, te, power, cwr = _runs()
    ds = power_matrix(hm0, te, {"mean_power": power, "capture_width_ratio": cwr},
                      HM0_EDGES, TE_EDGES, sources=SOURCES)
    outside = 0
    for i in range(len(HM0_EDGES) - 1):
        for j in range(len(TE_EDGES) - 1):
            sel = [k for k in range(hm0.size)
                   if HM0_EDGES[i] <= hm0[k] < HM0_EDGES[i + 1]
                   and TE_EDGES[j] <= te[k] < TE_EDGES[j + 1]]
            assert int(ds.run_count[i, j]) == len(sel)
            if not sel:
                assert np.all(np.isnan(ds.mean_power[i, j])), "an empty cell is NaN"
                assert np.isnan(float(ds.capture_width_ratio[i, j]))
                continue
            for s, name in enumerate(SOURCES):
                vals = [power[k, s] for k in sel]
                m = sum(vals) / len(vals)
                sd = (sum((v - m) ** 2 for v in vals) / len(vals)) ** 0.5  # ddof = 0
                assert float(ds.mean_power.sel(source=name)[i, j]) == pytest.approx(m, rel=1e-12)
                assert float(ds.mean_power_std.sel(source=name)[i, j]) == pytest.approx(
                    sd, rel=1e-9, abs=1e-9)
            c = [cwr[k] for k in sel]
            assert float(ds.capture_width_ratio[i, j]) == pytest.approx(np.mean(c), rel=1e-12)
            assert float(ds.capture_width_ratio_std[i, j]) == pytest.approx(np.std(c, ddof=0),
                                                                           rel=1e-9, abs=1e-12)
    for k in range(hm0.size):
        if not (HM0_EDGES[0] <= hm0[k] < HM0_EDGES[-1] and TE_EDGES[0] <= te[k] < TE_EDGES[-1]):
            outside += 1
    assert int(ds.runs_outside) == outside > 0
    assert int(ds.run_count.sum()) + outside == hm0.size
    assert int(ds.run_count[1, 1]) >= 1  # the run on the edges 0.08 / 1.5 went there


def test_layout_and_attributes():
    hm0, te, power, cwr = _runs()
    ds = power_matrix(hm0, te, {"mean_power": power}, HM0_EDGES, TE_EDGES, sources=SOURCES)
    np.testing.assert_allclose(ds.hm0_bin, [0.06, 0.10, 0.14])
    np.testing.assert_allclose(ds.te_bin_bounds[:, 0], TE_EDGES[:-1])
    np.testing.assert_allclose(ds.te_bin_bounds[:, 1], TE_EDGES[1:])
    assert ds.hm0_bin.attrs["bounds"] == "hm0_bin_bounds"
    assert ds.mean_power.attrs["units"] == "W" and ds.mean_power_std.attrs["units"] == "W"
    assert list(ds.source.values) == SOURCES
    assert ds.mean_power.dims == ("hm0_bin", "te_bin", "source")
    # the last Hm0 row is empty: count 0, NaN statistics
    assert int(ds.run_count[2].sum()) == 0 and np.all(np.isnan(ds.mean_power[2]))


@pytest.mark.parametrize("edges", [[0.1], [0.2, 0.1], [0.0, np.nan, 0.2]])
def test_bad_edges_are_refused(edges):
    with pytest.raises(ValueError, match="edges"):
        power_matrix([0.1], [2.0], {"mean_power": [1.0]}, edges, TE_EDGES)


def test_values_of_the_wrong_length_are_refused():
    with pytest.raises(ValueError, match="shape"):
        power_matrix([0.1, 0.1], [2.0, 2.0], {"mean_power": [1.0]}, HM0_EDGES, TE_EDGES)
