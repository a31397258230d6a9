"""Benchmark: UVP processing at paper scale, and run time against error for its knobs.

Part A (scale): the paper-size set of Brito et al. (2020, §2.3) — 78 runs cycling through the
27 UVP elevations 0.20..0.72 m, 3 beams x 360 channels at 11.6 Hz, 100 waves of T = 3.5 s,
H = 0.25 m, Kr = 0.2 — is written by the virtual flume to a temporary folder as .mfprof files
(untimed). Timed: raw files -> per-run read, filter, phase average (processes) -> field, with the
peak memory of the worker processes and of the parent. Target: <= 30 s on 2 cores.

Part B (knobs): per-run run time and field error against the virtual flume's truth for the
low-pass cut-off, the number N of waves averaged, the interpolation between samples and the
decomposition (Eqs. (9)-(10) vs least squares), on a turbulent variant of the flow
(band-limited fluctuations σ_u = 0.03, σ_w = 0.02 m/s, so that N matters).

Errors are RMS over the field (all phases and grid points where both the field and the truth
are defined), divided by U0 = πH/T.
"""

from __future__ import annotations

import multiprocessing as mp
import os
import resource
import shutil
import sys
import tempfile
import time
from concurrent.futures import ProcessPoolExecutor
from importlib import resources as _res
from pathlib import Path

import numpy as np

from flumekit.docstrings import filler

#: docstring text that several functions of this module share
_doc = filler(
    returns_lines=("Returns\n"
                   "-------\n"
                   "list of str\n"
                   "    Report lines."),
    workers=("workers : int\n"
             "    Worker processes."))

PERIOD, HEIGHT, DEPTH, KR, PHI = 3.5, 0.25, 0.825, 0.2, 0.6
N_WAVES = 100
ELEVATIONS = tuple(np.round(np.arange(0.20, 0.7201, 0.02), 3))


def _campaign():
    from flumekit.campaign import load_campaign

    d = Path(tempfile.mkdtemp(prefix="flumekit_bench_uvp_"))
    (d / "campaign.toml").write_text(
        _res.files("flumekit.data").joinpath("default_campaign.toml").read_text())
    c = load_campaign(d)
    shutil.rmtree(d)
    return c


def _record(uvp):
    return np.arange(int(N_WAVES * PERIOD * uvp.sampling_rate)) / uvp.sampling_rate


def _start(t_last: float, n_cycles: int, pad: float) -> float:
    """Return the latest incident up-crossing whose n_cycles window (+ pad) fits the record."""
    from flumekit.synth.uvp import incident_upcrossing

    t_up = incident_upcrossing(period=PERIOD, height=HEIGHT, depth=DEPTH)
    n = np.floor((t_last - pad - n_cycles * PERIOD - t_up) / PERIOD)
    return float(t_up + n * PERIOD)


def _write_run(job):
    from flumekit.synth.uvp import uvp_beams, write_uvp_run

    k, z, folder = job
    c = _campaign()
    beams = uvp_beams(_record(c.uvp), c.uvp, z, period=PERIOD, height=HEIGHT, depth=DEPTH,
                      reflection=KR, reflection_phase=PHI, rng=k)
    write_uvp_run(Path(folder) / f"run{k:02d}", beams)
    return k


def _process_run(job):
    """One pipeline rule: read the run's beam files, filter, phase-average (small result)."""
    from flumekit.io.mfprof import read_mfprof
    from flumekit.uvp import phase_average_beams

    folder, z, start, kw = job
    c = _campaign()
    cpu = time.process_time()
    beams = {b.name: read_mfprof(Path(folder) / f"{b.name}.mfprof") for b in c.uvp.beams}
    ds = phase_average_beams(beams, c.uvp, z, period=PERIOD, start=start,
                             flap_thickness=c.flap.thickness, **kw)
    ds.attrs["bench_cpu_s"] = time.process_time() - cpu
    ds.attrs["bench_maxrss_mb"] = _maxrss_mb(resource.RUSAGE_SELF)
    return ds


def _stats(results, acc):
    """Pass per-run results through, collecting the workers' CPU time and peak memory."""
    for ds in results:
        acc["cpu"] += ds.attrs.pop("bench_cpu_s")
        acc["rss"] = max(acc["rss"], ds.attrs.pop("bench_maxrss_mb"))
        yield ds


def _err(field, truth) -> tuple[float, float, float]:
    u0 = np.pi * HEIGHT / PERIOD
    tr = truth.interp(x=field.x, z=field.z)
    out = []
    for c in "uw":
        e = (field[c] - tr[c]).values / u0
        ok = np.isfinite(e)
        out.append(float(np.sqrt(np.mean(e[ok] ** 2))) if ok.any() else np.nan)
    cov = float(np.mean(np.isfinite(field["u"].values) & np.isfinite(field["w"].values)))
    return out[0], out[1], cov


def _maxrss_mb(who) -> float:
    return resource.getrusage(who).ru_maxrss / 1024.0  # Linux: kilobytes


@_doc
def part_a(n_runs: int, workers: int) -> list[str]:
    """Process a paper-scale UVP set from raw files to the field, timed; return the report lines.

    The runs are written by the virtual flume to a temporary folder (untimed), then read,
    filtered and phase-averaged by worker processes and combined into the field, with the peak
    memory of the workers and of the parent, and the field's error against the truth.

    Parameters
    ----------
    n_runs : int
        Runs (cycling through the 27 elevations).
    %(workers)s

    %(returns_lines)s

    %(references_brito2020)s, §2.3.
    """
    from flumekit.synth.uvp import true_field
    from flumekit.uvp import velocity_field

    c = _campaign()
    elev = [ELEVATIONS[k % len(ELEVATIONS)] for k in range(n_runs)]
    ctx = mp.get_context("spawn")  # workers do not inherit the parent's memory
    root = Path(tempfile.mkdtemp(prefix="flumekit_bench_uvp_raw_"))
    try:
        t0 = time.perf_counter()
        with ProcessPoolExecutor(workers, mp_context=ctx) as ex:
            list(ex.map(_write_run, [(k, z, str(root)) for k, z in enumerate(elev)]))
        t_write = time.perf_counter() - t0
        size = sum(p.stat().st_size for p in root.rglob("*.mfprof")) / 1e9
        t_last = _record(c.uvp)[-1]
        kw = dict(min_amplitude=100.0)
        start = _start(t_last, 50, pad=6.0)
        jobs = [(str(root / f"run{k:02d}"), z, start, kw) for k, z in enumerate(elev)]
        rss0 = _maxrss_mb(resource.RUSAGE_SELF)
        acc = {"cpu": 0.0, "rss": 0.0}
        t0 = time.perf_counter()
        cpu0 = time.process_time()
        with ProcessPoolExecutor(workers, mp_context=ctx) as ex:
            # streaming: combine_repeats consumes one small per-run result at a time
            field = velocity_field(_stats(ex.map(_process_run, jobs), acc), c.uvp,
                                   height=HEIGHT, period=PERIOD, water_depth=DEPTH)
        t_total = time.perf_counter() - t0
        cpu_parent = time.process_time() - cpu0
        rss_self = _maxrss_mb(resource.RUSAGE_SELF)
        load = os.getloadavg()[0]
    finally:
        shutil.rmtree(root, ignore_errors=True)
    truth = true_field(c, period=PERIOD, height=HEIGHT, reflection=KR, reflection_phase=PHI)
    eu, ew, cov = _err(field, truth)
    return [
        f"Part A: paper-scale UVP set, {n_runs} runs x {len(c.uvp.beams)} beams x "
        f"{c.uvp.n_channels} channels, {N_WAVES} waves at {c.uvp.sampling_rate} Hz "
        f"({size:.2f} GB of .mfprof, written in {t_write:.0f} s, untimed)",
        f"  raw files -> field, {workers} worker processes: wall {t_total:6.1f} s "
        f"(target <= 30 s; machine load average {load:.1f} on {os.cpu_count()} cores)",
        f"  CPU: workers {acc['cpu']:.1f} s in read + filter + phase average "
        f"({acc['cpu'] / n_runs:.3f} s per run), parent {cpu_parent:.1f} s (field "
        f"assembly, process start-up not counted)",
        f"  peak RSS: largest worker {acc['rss']:.0f} MB, parent {rss_self:.0f} MB "
        f"(parent before: {rss0:.0f} MB)",
        f"  field vs truth (least squares, N = 50, 2 Hz): RMS error <u> {100 * eu:.2f} % U0, "
        f"<w> {100 * ew:.2f} % U0 (target <= 2 %), coverage (u and w) {100 * cov:.0f} % "
        "of (phase, z, x)",
    ]


def _knob_run(job):
    """Synthesize one turbulent run in memory, process it with every knob setting."""
    from flumekit.synth.uvp import uvp_beams
    from flumekit.uvp import phase_average_beams

    k, z, settings, t_last = job
    c = _campaign()
    beams = uvp_beams(_record(c.uvp), c.uvp, z, period=PERIOD, height=HEIGHT, depth=DEPTH,
                      reflection=KR, reflection_phase=PHI, turbulence=(0.03, 0.02, 0.0), rng=k)
    out = []
    for key, kw in settings:
        start = _start(t_last, kw["n_cycles"], pad=6.0)
        t0 = time.process_time()
        ds = phase_average_beams(beams, c.uvp, z, period=PERIOD, start=start,
                                 flap_thickness=c.flap.thickness, min_amplitude=100.0, **kw)
        out.append((key, time.process_time() - t0, ds))
    return out


@_doc
def part_b(quick: bool, workers: int) -> list[str]:
    """Return the run time and field error against the UVP processing's knobs, as report lines.

    The low-pass cut-off, the number N of waves averaged, the interpolation between samples and
    the decomposition (Eqs. (9)-(10) vs least squares), on a turbulent variant of the flow.

    Parameters
    ----------
    quick : bool
        Fewer knob settings.
    %(workers)s

    %(returns_lines)s
    """
    from flumekit.synth.uvp import true_field
    from flumekit.uvp import velocity_field

    c = _campaign()
    cutoffs = (None, 2.0) if quick else (None, 1.0, 2.0, 3.0)
    ns = (10, 50) if quick else (10, 25, 50)
    settings = [((f, n, "cubic"), dict(cutoff=f, n_cycles=n, interpolation="cubic"))
                for f in cutoffs for n in ns]
    settings.append(((2.0, 50, "linear"), dict(cutoff=2.0, n_cycles=50, interpolation="linear")))
    t_last = _record(c.uvp)[-1]
    ctx = mp.get_context("spawn")
    with ProcessPoolExecutor(workers, mp_context=ctx) as ex:
        per_run = list(ex.map(_knob_run, [(k, z, settings, t_last)
                                          for k, z in enumerate(ELEVATIONS)]))
    truth = true_field(c, period=PERIOD, height=HEIGHT, reflection=KR, reflection_phase=PHI)
    lines = ["Part B: knobs (turbulent flow, 27 runs, one per elevation); time = CPU time of "
             "the per-run filter + phase average of 3 beams (median over runs)",
             f"  {'cut-off':>8} {'N':>4} {'interp':>7} {'method':>14} {'cpu/run':>9} "
             f"{'err <u>':>8} {'err <w>':>8} {'coverage':>8}"]
    for j, (key, _) in enumerate(settings):
        runs = [r[j][2] for r in per_run]
        t = float(np.median([r[j][1] for r in per_run]))
        for method in ("least_squares", "paired"):
            if method == "paired" and key != (2.0, 50, "cubic"):
                continue
            f = velocity_field(runs, c.uvp, height=HEIGHT, period=PERIOD, method=method)
            eu, ew, cov = _err(f, truth)
            cut = "none" if key[0] is None else f"{key[0]:g} Hz"
            lines.append(f"  {cut:>8} {key[1]:>4} {key[2]:>7} {method:>14} {t:8.3f}s "
                         f"{100 * eu:7.2f}% {100 * ew:7.2f}% {100 * cov:7.0f}%")
    return lines


def run(quick: bool = False) -> str:
    """Run the benchmark and return the table as text.

    Parameters
    ----------
    quick : bool
        27 runs in part A instead of 78, and fewer knob settings.

    Returns
    -------
    str
        The printed report.
    """
    workers = 2
    lines = part_a(27 if quick else 78, workers)
    lines.append("")
    lines += part_b(quick, workers)
    return "\n".join(lines)


if __name__ == "__main__":
    print(run(quick="--quick" in sys.argv))
