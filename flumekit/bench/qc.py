"""Benchmark: quality control against injected faults, and its cost against the analysis.

A virtual campaign (``small``: two wave runs and two UVP runs; every size has the same runs,
at the paper's rates and lengths, so each is a paper-scale run) is written twice: clean, and
with faults injected into its raw files with a known truth of which samples are bad:

* probes: 10 single-sample spikes per probe (±15-40 % of the record's range), a 1 s dropout to
  0 V on WP1 and an 8 s flat line (the value held) on WP3, at random times, in every run (the
  UVP runs' average keeps its window: flumekit.uvp.window);
* flap: 10 spikes on the encoder and 10 on the pressure;
* clocks: the flap record of one of the three T = 3.5 s, H = 0.25 m runs is stamped 0.3 s
  late (a 0.3 s clock offset between the probes and the flap);
* UVP: 200 spikes per beam (±0.1-0.3 m s-1) into fluid samples, in memory (the raw
  ``.mfprof`` files are left clean).

Reported: recall of each fault (flagged suspect or fail), false flags on the clean records and on
the good samples of the faulty ones, the clock offset the QC summary finds, the analysis of the
faulty campaign after QC against the virtual flume's truth with the tolerances of
tests/test_virtual_flume_truth.py (:mod:`flumekit.bench.truth`, which both use), and the run
time of QC against the analysis, per run and instrument (best of five, the UVP's of seven,
each rule executed on its own):

* probes and flap: the qc/probes and qc/flap rules against the stages that consume them
  (eta, waves, flap, comparison);
* UVP: the uvp rule checks the beams it reads before analysing them
  (flumekit.stages.uvp_run.beam_checker), over the samples its average reads: its QC is the
  computation of the flags (flumekit.qc.record.beam_flags), the writing of the flag product and
  the masking and filling of the beams (flumekit.stages.uvp.clean_beam), each timed on its own
  on the rule's inputs; its analysis is the rest of the rule (the rule's time minus that QC).
  The beams are read once, by the rule, for both: that read is the analysis's;
* per run (``all``): every QC of the run against every analysis above;
* once per process: the despiking and echo-level loops are compiled (numba,
  flumekit.qc.kernels); a process pays once for importing numba and loading them from their
  cache, measured in a fresh process that has imported the analysis's modules, and shared by
  the UVP runs it checks: its share of a UVP run is given for the paper campaign.

The probe and flap QC rules read the raw files, which the analysis would otherwise read itself;
the time of that read is shown and the ratio given both with it and without it; so is the time
of writing their products (flumekit.io.netcdf.write_dataset, which every stage's products pay
alike).
"""

from __future__ import annotations

import shutil
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[2]
SHIFTED_RUN = "uvp_z0.500_r0"

#: timings are the best of this many (a shared machine's noise only adds), the UVP's of more:
#: its analysis is the difference of three timings
REPEAT = 5
REPEAT_UVP = 7

CLOCK_OFFSET = 0.3  # [s]


def _spikes(rng, n, count, margin=5):
    idx = rng.choice(np.arange(margin, n - margin, 4), size=count, replace=False)
    return np.sort(idx)


def inject(raw: Path, rng: np.random.Generator) -> dict:
    """Write faults into the raw files of a campaign and return which samples are bad.

    The faults of the module's description (spikes, a dropout and a flat line on the probes,
    spikes on the flap channels, a clock offset of one flap record), at random times, into the
    regular runs only (the irregular runs stay clean: their truth is what the benchmark
    measures).

    Parameters
    ----------
    raw : pathlib.Path
        The raw campaign folder (a temporary copy: its files are rewritten).
    rng : numpy.random.Generator
        Random generator of the fault times and sizes.

    Returns
    -------
    dict
        (run, file, channel) -> boolean mask of the bad samples.
    """
    from flumekit.io.tables import read_text, write_table

    truth = {}
    for run in sorted(p for p in (raw / "runs").iterdir() if p.is_dir()):
        if 'kind = "irregular"' in (run / "run.toml").read_text():
            continue  # the faults and their truth are those of the regular runs
        tx = read_text(run / "probes.csv")
        cols = list(zip(tx.labels, tx.units, strict=True))
        data = np.column_stack(tx.columns)
        n = data.shape[0]
        for j, (c, _) in enumerate(cols[1:], start=1):
            x = data[:, j]
            lo, hi = np.percentile(x, [0.1, 99.9])
            bad = np.zeros(n, dtype=bool)
            idx = _spikes(rng, n, 10)
            x[idx] += rng.choice([-1, 1], idx.size) * rng.uniform(0.15, 0.4, idx.size) * (hi - lo)
            bad[idx] = True
            fs = 1.0 / (data[1, 0] - data[0, 0])
            if c == "WP1":
                i0 = int(rng.integers(int(0.1 * n), int(0.9 * n)))
                x[i0:i0 + int(fs)] = 0.0
                bad[i0:i0 + int(fs)] = True
            if c == "WP3":
                i0 = int(rng.integers(int(0.1 * n), int(0.8 * n)))
                x[i0:i0 + int(8 * fs)] = x[i0]
                bad[i0:i0 + int(8 * fs)] = True  # the held run as a whole
            truth[(run.name, "probes", c)] = bad
        write_table(run / "probes.csv", cols, data)
        tx = read_text(run / "flap.csv")
        flap_cols = list(zip(tx.labels, tx.units, strict=True))  # as written (pressure in bar)
        data = np.column_stack(tx.columns)
        n = data.shape[0]
        for j, name in ((1, "encoder_counts"), (2, "chamber_pressure")):
            x = data[:, j]
            lo, hi = np.percentile(x, [0.1, 99.9])
            idx = _spikes(rng, n, 10)
            step = rng.choice([-1, 1], idx.size) * rng.uniform(0.15, 0.4, idx.size) * (hi - lo)
            x[idx] += np.round(step) if j == 1 else step
            bad = np.zeros(n, dtype=bool)
            bad[idx] = True
            truth[(run.name, "flap", name)] = bad
        if run.name == SHIFTED_RUN:
            k = int(round(CLOCK_OFFSET / (data[1, 0] - data[0, 0])))
            # the flap's clock runs 0.3 s behind: each sample is stamped 0.3 s late (the first
            # 0.3 s repeat the flap at rest)
            data[:, 1:] = np.concatenate([np.repeat(data[:1, 1:], k, axis=0), data[:-k, 1:]])
            for key in ("encoder_counts", "chamber_pressure"):
                truth[(run.name, "flap", key)] = np.r_[np.zeros(k, bool),
                                                       truth[(run.name, "flap", key)][:-k]]
        write_table(run / "flap.csv", flap_cols, data, fmt=["%.4f", "%d", "%.6f"])
    return truth


def _make(project: Path, targets: list[str]) -> float:
    from flumekit.cli import main

    t0 = time.perf_counter()
    code = main(["make", "--pipeline", str(project / "pipelines" / "small.toml"), *targets])
    if code != 0:
        raise RuntimeError(f"make failed in {project}")
    return time.perf_counter() - t0


def _recall(processed: Path, truth: dict) -> tuple[dict, float, int]:
    """Recall per fault kind and the false-flag fraction of the good samples."""
    import xarray as xr

    hit = {}
    good_flagged = good = 0
    for (run, kind, channel), bad in truth.items():
        with xr.open_dataset(processed / "qc" / kind / f"{run}.nc", decode_times=False) as ds:
            name = "probe_voltage" if kind == "probes" else channel
            f = ds[f"{name}_qc"]
            f = (f.sel(probe=channel) if kind == "probes" else f).values
        flagged = f >= 3
        label = f"{kind} " + {"WP1": "dropout", "WP3": "flat line"}.get(channel, "spikes")
        spikes = np.zeros_like(bad)
        if kind == "probes" and channel in ("WP1", "WP3"):
            # the spikes of these probes are counted with the others
            runs_ = np.flatnonzero(np.diff(np.r_[0, bad.astype(int), 0]))
            long_ = np.zeros_like(bad)
            for a, b in zip(runs_[::2], runs_[1::2], strict=True):
                if b - a > 1:
                    long_[a:b] = True
            spikes = bad & ~long_
            h = hit.setdefault(label, [0, 0])
            h[0] += int(flagged[long_].sum())
            h[1] += int(long_.sum())
            bad_spikes = spikes
        else:
            bad_spikes = bad
        h = hit.setdefault(f"{kind} spikes", [0, 0])
        h[0] += int(flagged[bad_spikes].sum())
        h[1] += int(bad_spikes.sum())
        good_flagged += int(flagged[~bad].sum())
        good += int((~bad).sum())
    return {k: v[0] / v[1] for k, v in hit.items()}, good_flagged / good, good


def _uvp_recall(raw: Path, processed: Path, rng) -> tuple[float, float]:
    """Return the recall of spikes injected in memory into every beam of the UVP runs.

    With the false flags of the clean beams, over the span the qc stage checks (the
    quasi-steady part of the run).
    """
    from flumekit.io.mfprof import read_mfprof
    from flumekit.io.netcdf import read_dataset
    from flumekit.qc.record import Thresholds, check_beam

    th = Thresholds()
    hits = total = false = n = 0
    for f in sorted(raw.glob("runs/*/*.mfprof")):
        lo, hi = read_dataset(processed / "qc" / "uvp" / f"{f.parent.name}.nc")[
            "evaluated_span"].values
        b = read_mfprof(f)
        t = b["time"].values
        i0, i1 = int(np.searchsorted(t, lo)), int(np.searchsorted(t, hi, side="right"))
        v = b["beam_velocity"].transpose("channel", "time").values[:, i0:i1]
        a = b["amplitude"].transpose("channel", "time").values[:, i0:i1]
        fs = (t.size - 1) / (t[-1] - t[0])
        kw = dict(floor=float(b.attrs["velocity_resolution"]), amplitude=a)
        clean = check_beam(v, t[i0:i1], fs, th, **kw)["goring_nikora"]
        false += int((clean >= 3).sum())
        n += clean.size
        fluid = clean == 1
        cand = np.flatnonzero(fluid.ravel())
        idx = rng.choice(cand, 200, replace=False)
        w = v.copy().ravel()
        w[idx] += rng.choice([-1, 1], 200) * rng.uniform(0.1, 0.3, 200)
        g = check_beam(w.reshape(v.shape), t[i0:i1], fs, th, **kw)["goring_nikora"].ravel()
        hits += int((g[idx] >= 3).sum())
        total += idx.size
    return hits / total, false / n


def _compute_probes_flap(p: dict, f: dict, run) -> float:
    """Return the best time of the QC computations alone of a run's probe and flap records [s].

    The tests, flags, masking and filling, on records read beforehand.
    """
    from flumekit.bench import best_time
    from flumekit.qc.record import Thresholds, qc_dataset
    from flumekit.stages.qc import read_raw

    th = Thresholds.from_params(p)
    probes = read_raw("probes", run.file("probes"), p)
    name = "probe_voltage" if "probe_voltage" in probes else "probe_elevation"
    flap = read_raw("flap", run.file("flap"), f)
    return best_time(lambda: (qc_dataset(probes, name, th, channel_dim="probe"),
                              [qc_dataset(flap, k, th) for k in ("encoder_counts",
                                                                  "chamber_pressure")]),
                     REPEAT)[0]


def _compute_uvp(beams: dict, span, time_offset: float, repeat: int = REPEAT) -> float:
    """Return the best time of the UVP QC computations of the uvp rule on beams read beforehand [s].

    The flags (:func:`flumekit.qc.record.beam_flags`) and the masking and filling of the beams.
    """
    from flumekit.bench import best_time
    from flumekit.qc.record import Thresholds, beam_flags
    from flumekit.stages.uvp import clean_beam

    th = Thresholds()

    def qc():
        flags = beam_flags(beams, span, th, time_offset=time_offset)
        flags.attrs["max_gap"] = th.max_gap
        # as the rule does, in place (the rule's beams are its own; cleaning cleaned beams
        # again gives them back)
        return [clean_beam(b, flags, name, copy=False) for name, b in beams.items()]

    return best_time(qc, repeat)[0]


#: UVP runs of the paper campaign (flumekit.synth.campaign) and the workers of its build
PAPER_UVP_RUNS = 78
PAPER_WORKERS = 2

#: the stages that consume each instrument's QC product, per run (the uvp rule checks the beams
#: itself: see the module's docstring)
CONSUMERS = {"probes+flap": ("eta", "waves", "flap", "comparison"), "uvp": ("uvp",)}


def _write_time(paths: list[Path], compress: bool, repeat: int = REPEAT) -> float:
    """Return the best time of writing the QC rule's products again [s].

    As the rule does (flumekit.io.netcdf.write_dataset: CF checks, provenance, compression or
    not).
    """
    from flumekit.bench import best_time
    from flumekit.io.netcdf import read_dataset, write_dataset

    data = []
    for p in paths:
        ds = read_dataset(p)
        for v in ds.variables.values():
            v.encoding = {}
        data.append(ds)
    with tempfile.TemporaryDirectory() as tmp:
        return best_time(lambda: [write_dataset(d.copy(), Path(tmp) / f"{i}.nc")
                                  for i, d in enumerate(data)], repeat)[0]


#: the first UVP check of a fresh process that has imported what the uvp rule's analysis
#: imports, then a second one (flumekit.bench.qc._kernel_load)
_FIRST_CHECK = """
import sys, time
import flumekit.stages.uvp, flumekit.uvp  # the analysis's modules (scipy among them)
from flumekit.io.mfprof import read_mfprof
from flumekit.qc.record import Thresholds, beam_flags
beams = {p.stem: read_mfprof(p) for p in map(__import__("pathlib").Path, sys.argv[1:])}
t1 = time.perf_counter()
beam_flags(beams, (-1e9, 1e9), Thresholds())
t2 = time.perf_counter()
beam_flags(beams, (-1e9, 1e9), Thresholds())
t3 = time.perf_counter()
print((t2 - t1) - (t3 - t2))
"""


def _kernel_load(beams: list[Path]) -> float:
    """Return the seconds a fresh process spends once loading the compiled QC kernels.

    A process that analyses UVP runs imports numba and loads the compiled kernels
    (flumekit.qc.kernels) from their cache before its first UVP check: its first check of
    ``beams`` less its second [s].
    """
    import subprocess
    import sys

    out = subprocess.run([sys.executable, "-c", _FIRST_CHECK, *map(str, beams)],
                         capture_output=True, text=True, check=True)
    return float(out.stdout.split()[0])


def _timings(processed: Path, raw: Path) -> list[tuple]:
    """Return the QC and analysis times per run and instrument [s].

    QC rule time, of which reading the raw files, the QC computations alone and writing the
    products, and the time of the rules that consume the QC product (best of REPEAT, the UVP's
    of REPEAT_UVP).
    """
    from flumekit.bench import best_time
    from flumekit.campaign import load_campaign
    from flumekit.io.mfprof import read_mfprof
    from flumekit.io.netcdf import read_dataset
    from flumekit.pipeline.config import load_pipeline
    from flumekit.pipeline.rules import execute
    from flumekit.stages import build_rules
    from flumekit.stages.context import Context
    from flumekit.stages.qc import COMPRESS, read_raw

    pipe = load_pipeline(processed.parents[1] / "pipelines" / "small.toml")
    campaign = load_campaign(raw)
    ctx = Context(campaign=campaign, processed=processed, params=pipe.stages, scenes=pipe.scenes)
    rules = {r.target: r for r in build_rules(ctx)}

    def run_rules(targets, repeat=REPEAT):
        return sum(best_time(lambda r=rules[t]: execute(r), repeat)[0] for t in targets
                   if t in rules)

    out = []
    for run in campaign.runs:
        p = rules[f"qc/probes/{run.id}"].params
        f = rules[f"qc/flap/{run.id}"].params
        t_read = best_time(lambda p=p, f=f, run=run: (
            read_raw("probes", run.file("probes"), p), read_raw("flap", run.file("flap"), f)),
            REPEAT)[0]
        t_qc = run_rules([f"qc/probes/{run.id}", f"qc/flap/{run.id}"])
        t_ana = run_rules([f"{s}/{run.id}" for s in CONSUMERS["probes+flap"]])
        t_write = _write_time([processed / "qc" / k / f"{run.id}.nc" for k in ("probes", "flap")],
                              COMPRESS["probes"])
        out.append((run.id, "probes+flap", t_qc, t_read, _compute_probes_flap(p, f, run),
                    t_write, t_ana))
        if f"uvp/{run.id}" in rules:
            beams = {b.name: read_mfprof(run.path / f"{b.name}.mfprof")
                     for b in campaign.uvp.beams}
            # more repeats: the analysis is the difference of three timings
            t_rule = run_rules([f"{s}/{run.id}" for s in CONSUMERS["uvp"]], REPEAT_UVP)
            span = read_dataset(processed / "qc" / "uvp" / f"{run.id}.nc")[
                "evaluated_span"].values
            t_cmp = _compute_uvp(beams, span, run.clock.get("uvp", 0.0), REPEAT_UVP)
            t_write = _write_time([processed / "qc" / "uvp" / f"{run.id}.nc"], COMPRESS["uvp"],
                                  REPEAT_UVP)
            # no read of its own: the rule reads the beams once, for its analysis
            out.append((run.id, "uvp", t_cmp + t_write, 0.0, t_cmp, t_write,
                        t_rule - t_cmp - t_write))
        rows = [r[2:] for r in out if r[0] == run.id]
        if len(rows) > 1:  # every QC rule of the run against every rule analysing it
            out.append((run.id, "all", *(sum(col) for col in zip(*rows, strict=True))))
    return out


def run(quick: bool = False) -> str:
    """Run the benchmark and return its report as text.

    Parameters
    ----------
    quick : bool
        Leave out the timings (recall, clock and truth only).

    Returns
    -------
    str
        The printed report: recall and false flags, the clock offset found, the analysis after
        QC against the truth, and the cost of QC against the analysis.
    """
    from flumekit.bench.truth import failures as truth_failures
    from flumekit.synth.campaign import write_campaign

    lines = []
    with tempfile.TemporaryDirectory() as tmp:
        results = {}
        for label in ("clean", "faulty"):
            project = Path(tmp) / label
            shutil.copytree(ROOT / "pipelines", project / "pipelines")
            write_campaign(project / "raw" / "small", size="small", seed=11)
            truth = inject(project / "raw" / "small", np.random.default_rng(7)) \
                if label == "faulty" else None
            _make(project, ["calibration", "qc_summary", "waves_summary", "flap_summary",
                            "uvp_field", *(f"comparison/{r.name}" for r in sorted(
                                (project / "raw" / "small" / "runs").iterdir()))])
            results[label] = (project, truth)
        clean_p = results["clean"][0] / "processed" / "small"
        fault_p = results["faulty"][0] / "processed" / "small"
        raw = results["clean"][0] / "raw" / "small"
        # false flags on the clean campaign's probe and flap records
        import xarray as xr

        flagged = total = 0
        for f in sorted((clean_p / "qc").glob("*/*.nc")):
            if f.parent.name == "uvp":
                continue
            with xr.open_dataset(f, decode_times=False) as ds:
                for v in ds.data_vars:
                    if v.endswith("_qc"):
                        flagged += int((ds[v] >= 3).sum())
                        total += int(ds[v].size)
        recall, false_faulty, _ = _recall(fault_p, results["faulty"][1])
        uvp_recall, uvp_false = _uvp_recall(raw, clean_p, np.random.default_rng(3))
        lines.append("fault                        recall")
        for k, v in sorted(recall.items()):
            lines.append(f"{k:28s} {v:7.2%}")
        lines.append(f"{'uvp spikes (GN)':28s} {uvp_recall:7.2%}")
        lines.append(f"false flags, clean probe+flap records: {flagged}/{total} = "
                     f"{flagged / total:.4%}")
        lines.append(f"false flags, good samples of faulty records: {false_faulty:.4%}")
        lines.append(f"false flags (GN), clean UVP beams: {uvp_false:.4%}")
        with xr.open_dataset(fault_p / "qc_summary.nc", decode_times=False) as s:
            dep = dict(zip(s.run.values.tolist(), s.clock_departure.values.tolist(),
                           strict=True))
            warned = s.attrs.get("flumekit_warnings", "")
        lines.append(f"clock departure of {SHIFTED_RUN} (0.3 s injected): "
                     f"{dep[SHIFTED_RUN]:+.4f} s; others: "
                     + ", ".join(f"{k} {v:+.4f}" for k, v in dep.items() if k != SHIFTED_RUN))
        lines.append(f"clock warning names the run: {SHIFTED_RUN in warned}")
        fails = truth_failures(fault_p, results["faulty"][0] / "raw" / "small" / "truth",
                               skip_flap={SHIFTED_RUN})
        lines.append("analysis after QC within the clean-data truth tolerances: "
                     + ("yes" if not fails else "NO: " + "; ".join(fails)))
        if not quick:
            lines.append("")
            lines.append(f"QC against the analysis of its product (best of {REPEAT}; uvp best of "
                         f"{REPEAT_UVP}) [s]; "
                         "probes+flap: the qc rules against eta, waves, flap, comparison; uvp: "
                         "the uvp rule's QC (flags, their product, masking and filling) against "
                         "the rest of the rule")
            lines.append("QC: the QC rules (uvp: compute + write); read: their reading of the "
                         "raw files (uvp: none, the rule reads the beams once); compute: the QC "
                         "computations alone (tests, flags, masking, filling); write: writing "
                         "their products (netCDF, as every stage writes)")
            lines.append("run                instrument     QC   read compute  write analysis"
                         "   QC/ana (QC-read)/ana compute/ana write/ana")
            rows = _timings(clean_p, raw)
            for run_id, kind, t_qc, t_read, t_cmp, t_wr, t_ana in rows:
                lines.append(f"{run_id:18s} {kind:11s} {t_qc:6.3f} {t_read:6.3f} "
                             f"{t_cmp:6.3f} {t_wr:6.3f} {t_ana:8.3f} {t_qc / t_ana:8.1%} "
                             f"{(t_qc - t_read) / t_ana:13.1%} {t_cmp / t_ana:11.1%} "
                             f"{t_wr / t_ana:9.1%}")
            # the compiled kernels' one cost per process, shared by its UVP runs
            uvp_runs = sorted(p for p in (raw / "runs").iterdir() if p.name.startswith("uvp"))
            once = min(_kernel_load(sorted(uvp_runs[0].glob("*.mfprof"))) for _ in range(3))
            ana = np.mean([r[-1] for r in rows if r[1] == "all"])
            share = once * PAPER_WORKERS / PAPER_UVP_RUNS
            lines.append(f"once per process checking UVP beams (numba imported, the kernels "
                         f"loaded from their cache): {once:.3f} s; in the paper campaign "
                         f"({PAPER_UVP_RUNS} UVP runs, make -j {PAPER_WORKERS}): {share:.4f} s "
                         f"a UVP run, {share / ana:.1%} of its analysis")
    return "\n".join(lines)
