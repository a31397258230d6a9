"""The noise test: a channel that is mostly alternating spikes or white noise fails, and is an
error naming the file and channel; clean records, their still-water lead-in, short waves and a
quantised encoder pass. Truths: the analytic lag-one autocorrelation of each signal."""

from pathlib import Path

import numpy as np
import pytest

from flumekit.errors import InputError
from flumekit.io.tables import write_table
from flumekit.qc import flags as F
from flumekit.qc import qartod
from flumekit.qc.record import Thresholds, check_series
from flumekit.stages import qc as qc_stage

FS = 25.0  # [Hz]
PROBES = ["WP1", "WP2", "WP3", "WP4"]


def _waves(period: float = 2.0, seconds: float = 218.0, rest: float = 20.0, noise=0.005,
           seed: int = 1) -> tuple[np.ndarray, np.ndarray]:
    """(probe, time) voltages: a still lead-in, then a ramped wave, with sensor noise."""
    rng = np.random.default_rng(seed)
    t = np.arange(int(seconds * FS)) / FS
    env = np.clip((t - rest) / (8 * period), 0, 1)
    x = np.array([2.5 + 0.4 * env * np.sin(2 * np.pi * t / period + j)
                  + noise * rng.standard_normal(t.size) for j in range(4)])
    return t, x


def test_alternating_spikes_and_white_noise_fail_everywhere():
    t, x = _waves()
    n = t.size
    x[1] = 2.5 + 0.5 * (-1.0) ** np.arange(n)  # +-0.5 V at 12.5 Hz: r1 = -1
    x[2] = 2.5 + 0.3 * np.random.default_rng(4).standard_normal(n)  # white: r1 = 0
    x[3] += 0.5 * (-1.0) ** np.arange(n)  # the waves under the spikes: r1 = (0.08 - 0.25)/0.33
    per = check_series(x, t, FS, Thresholds())
    noise = per["noise"]
    assert (noise[0] == F.GOOD).all()
    assert (noise[1:] == F.FAIL).all()
    # the spike test alone sees none of the alternating spikes: each sample is as far from
    # its neighbours as the next
    assert not (per["spike"][1] >= F.SUSPECT).any()


@pytest.mark.parametrize("period", [0.5, 1.0, 2.0, 3.5])
def test_clean_waves_with_a_still_lead_in_pass(period):
    """cos(2 pi / (T fs)) is 0.81 for 0.5 s waves at 25 Hz: above the default 0.5; the lead-in
    is noise (r1 = 0) but its energy is 0.005² / (0.4² / 2) = 3e-4 of the channel's."""
    t, x = _waves(period)
    assert (qartod.noise_test(x, int(10 * FS)) == F.GOOD).all()


def test_a_noisy_stretch_fails_its_blocks_only():
    t, x = _waves()
    x[0, 2500:2750] = 2.5 + 0.4 * np.random.default_rng(6).standard_normal(250)  # 10 s
    f = qartod.noise_test(x, int(10 * FS))
    assert (f[0, 2500:2750] == F.FAIL).all()
    assert (f[0, :2500] == F.GOOD).all() and (f[0, 2750:] == F.GOOD).all()
    assert (f[1:] == F.GOOD).all()


def test_quantised_encoder_passes():
    t = np.arange(int(200 * 100)) / 100.0
    env = np.clip((t - 20) / 28, 0, 1)
    counts = np.round(600 * env * np.sin(2 * np.pi * t / 3.5))
    assert (qartod.noise_test(counts, 1000) == F.GOOD).all()


def _params(name: str, period: float = 2.0) -> dict:
    return {**qc_stage.DEFAULTS, "run": name, "kind": "waves", "period": period, "height": 0.15,
            "repeat": 0,
            "uvp_elevation": None, "probes": PROBES, "sampling_rate": FS,
            "probe_x": {p: -float(k) for k, p in enumerate(PROBES)}}


@pytest.mark.parametrize("fault", ["spikes", "white"])
def test_a_noise_probe_is_an_error_naming_file_and_channel(tmp_path, fault):
    """Before: 0 flags of 5 450 and an error blaming run.height later on."""
    t, x = _waves()
    if fault == "spikes":
        x[1] = 2.5 + 0.5 * (-1.0) ** np.arange(t.size)
    else:
        x[1] = 2.5 + 0.3 * np.random.default_rng(4).standard_normal(t.size)
    write_table(tmp_path / "probes.csv", [("time", "s")] + [(p, "V") for p in PROBES],
                np.column_stack([t, x.T]), fmt=["%.2f"] + ["%.6f"] * 4)
    (tmp_path / "run.toml").write_text("[run]\nperiod = 2.0\n")
    with pytest.raises(InputError) as e:
        qc_stage.probes({"probes": tmp_path / "probes.csv", "run": tmp_path / "run.toml"},
                        {"dataset": tmp_path / "out.nc"}, _params("r"))
    msg = str(e.value)
    assert msg.startswith(str(tmp_path / "probes.csv"))
    assert "channel 'WP2' is noise" in msg and "100% of the record" in msg
    r1 = -1.0 if fault == "spikes" else 0.0
    got = float(msg.split("lag-one autocorrelation ")[1].split(" ")[0])
    assert abs(got - r1) < 0.05
    assert not Path(tmp_path / "out.nc").exists()


def test_partial_noise_is_flagged_and_counted_for_the_figure(tmp_path):
    t, x = _waves()
    x[2, 3000:3250] = 2.5 + 0.4 * np.random.default_rng(7).standard_normal(250)
    write_table(tmp_path / "probes.csv", [("time", "s")] + [(p, "V") for p in PROBES],
                np.column_stack([t, x.T]), fmt=["%.2f"] + ["%.6f"] * 4)
    (tmp_path / "run.toml").write_text("[run]\nperiod = 2.0\n")
    qc_stage.probes({"probes": tmp_path / "probes.csv", "run": tmp_path / "run.toml"},
                    {"dataset": tmp_path / "out.nc"}, _params("r"))
    from flumekit.io.netcdf import read_dataset

    # read as the pipeline reads its products: times in seconds, not decoded to datetimes
    with read_dataset(tmp_path / "out.nc") as ds:
        by = ds["probe_voltage_qc"].attrs["flagged_by_noise"]
        assert list(by) == [0, 0, 250, 0]
        assert "WP3 120.000-129.960 s" in ds.attrs["flumekit_warnings"]
        from flumekit.figures.qc import flag_summary

        text = flag_summary(ds["probe_voltage_qc"], 2)
        from flumekit.figures.check import assert_passes
        from flumekit.figures.qc import figure_qc

        fig = figure_qc(ds.load())
    assert text == "noise 250 (noise, not signal)"
    titles = [ax.get_title(loc="left") for ax in fig.axes]
    assert "WP3: 0 suspect, 250 fail, 0 missing; flagged by noise 250 (noise, not signal)" \
        in titles
    assert_passes(fig, "qc figure")
