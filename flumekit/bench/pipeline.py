"""Pipeline benchmark: the make engine's costs, the README's main job and loading results.

Synthesis, a full build serial and with 2 processes, the no-op build, and the planning cost of
a paper-size campaign against a bare ``flumekit --version``; the main job (``flumekit make``
on the default campaign from nothing) with the rule time of each stage and the mean figure
time, and its build again with the raw data present; the paper campaign's synthesis and cold
build (-j 2, raw present) with its stages' rule times; opening the default campaign's flap
files with :func:`flumekit.open_processed` against xarray.

Run time is what the make engine adds or saves; accuracy is not traded here, so the table
reports wall-clock seconds and how many targets ran. The paper-size no-op is measured on the
paper campaign's real graph (every run's ``run.toml``, 1 200+ targets) over placeholder raw
and output files with a complete build state: the engine's no-op reads no content, so this is
the cost of planning itself without a two-hour build first. As in any make after the first, the
make finds the record of the last one (:mod:`flumekit.pipeline.cache`): nothing it checked
changed. Timed too: the make that checks every target (a file was touched) with the graph from
its cache, and the make that rebuilds the graph (a campaign file changed).
"""

from __future__ import annotations

import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def _make(project: Path, *args: str, pipeline: str = "pipelines/small.toml") -> tuple[float, str]:
    t0 = time.perf_counter()
    r = subprocess.run([sys.executable, "-m", "flumekit.cli", "make", "--pipeline", pipeline,
                        *args], cwd=project, capture_output=True, text=True)
    if r.returncode:
        raise RuntimeError(r.stderr)
    lines = [s for s in r.stderr.strip().splitlines() if not s.startswith(("outputs", "next"))]
    return time.perf_counter() - t0, (lines or [""])[-1]


def _timed(cmds: list[list[str]], cwd: Path, repeat: int = 9,
           before=lambda: None) -> list[tuple[float, float]]:
    """Time commands: (best, median) wall-clock seconds of each.

    Each command runs ``repeat`` times, in turn with the others, so that a load that comes and
    goes on the machine weighs on each alike; ``before`` runs untimed before each command.
    """
    import os
    import statistics

    # as an installed package runs: byte code cached (PYTHONDONTWRITEBYTECODE would make every
    # start recompile the modules, which costs the make more than the bare --version)
    env = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}
    for cmd in cmds:  # warm-up
        subprocess.run(cmd, cwd=cwd, capture_output=True, check=True, env=env)
    times: list[list[float]] = [[] for _ in cmds]
    for _ in range(repeat):
        for cmd, ts in zip(cmds, times):
            before()
            t0 = time.perf_counter()
            subprocess.run(cmd, cwd=cwd, capture_output=True, check=True, env=env)
            ts.append(time.perf_counter() - t0)
    return [(min(ts), statistics.median(ts)) for ts in times]


def paper_noop(project: Path) -> tuple[dict[str, tuple[float, float]], int]:
    """Time the no-op make of a paper-size campaign against ``flumekit --version``.

    Returns (best, median) seconds of ``flumekit --version`` and of the no-op make: as it runs
    after a make ("noop"), without the record of that make ("checked": every target checked,
    the graph from its cache) and without the graph's cache either ("rebuilt"); and the number
    of targets of the paper campaign's graph.
    """
    from flumekit.pipeline.config import load_pipeline
    from flumekit.pipeline.engine import Graph
    from flumekit.pipeline.state import State
    from flumekit.stages import build_rules
    from flumekit.stages.context import Context
    from flumekit.synth.campaign import campaign_toml, run_toml, virtual_campaign

    pipe = load_pipeline(project / "pipelines" / "paper.toml")
    virtual = virtual_campaign(pipe.raw, "paper", 2020)
    (pipe.raw / "calibration").mkdir(parents=True)
    (pipe.raw / "campaign.toml").write_text(campaign_toml("paper"))
    for r in virtual.runs:
        r.path.mkdir(parents=True)
        sea = None if r.sea_state is None else dict(r.sea_state.__dict__)  # irregular runs
        (r.path / "run.toml").write_text(run_toml(r.kind, r.period, r.height, r.repeat,
                                                  r.uvp_elevation, r.probe_x, sea=sea))
    from flumekit.campaign import load_campaign

    graph = Graph(build_rules(Context(load_campaign(pipe.raw), pipe.processed, pipe.stages,
                                      pipe.scenes)))
    for rule in graph.rules.values():
        for p in [*rule.inputs.values(), *rule.outputs.values()]:
            if not Path(p).exists():
                Path(p).parent.mkdir(parents=True, exist_ok=True)
                Path(p).write_text(str(p))  # a placeholder: the no-op reads no content
    from flumekit.pipeline.engine import signature

    state = State(pipe.state_file)
    for t in graph.closure(list(graph.rules)):
        rule = graph.rules[t]
        sig = signature(rule, state)
        sig["outputs"] = {n: state.identity(Path(p)) for n, p in rule.outputs.items()}
        state.targets[t] = sig
    state.save()
    cli = [sys.executable, "-m", "flumekit.cli"]
    make = [*cli, "make", "--pipeline", "pipelines/paper.toml"]
    noop, version = _timed([make, [*cli, "--version"]], project)
    stamp = pipe.processed / ".flumekit-up-to-date.json"
    cache = pipe.processed / ".flumekit-graph.pickle"
    (checked,) = _timed([make], project, repeat=3, before=lambda: stamp.unlink())
    (rebuilt,) = _timed([make], project, repeat=3,
                        before=lambda: (stamp.unlink(), cache.unlink()))
    return {"version": version, "noop": noop, "checked": checked, "rebuilt": rebuilt}, \
        len(graph.rules)


def _stage_rows(processed: Path) -> list[tuple[str, float, str]]:
    """Sum the rule seconds per stage of the last build in ``processed``.

    The engine records each rule's run time; the stages that cost most come first, then the
    mean time of a figure (PNG at 300 dpi and PDF).
    """
    import json

    targets = json.loads((processed / ".flumekit-state.json").read_text())["targets"]
    per: dict[str, list[float]] = {}
    for name, sig in targets.items():
        stage = "figure" if name.startswith("figure/") else name.split("/")[0]
        per.setdefault(stage, []).append(float(sig.get("seconds", 0.0)))
    rows = [(f"  {stage} rules ({len(t)})", sum(t), f"mean {sum(t) / len(t):.3f} s")
            for stage, t in sorted(per.items(), key=lambda kv: -sum(kv[1]))[:8]]
    figs = per.get("figure", [])
    if figs:
        rows.append(("  mean figure (PNG 300 dpi + PDF)", sum(figs) / len(figs),
                     f"{len(figs)} figures (target < 0.5 s)"))
    return rows


def _main_job(project: Path) -> list[tuple[str, float, str]]:
    """Time the README's main job on a fresh project, and the stages of its build.

    ``flumekit make`` (default -j) on the default campaign, its synthesis included.
    """
    sec, msg = _make(project, pipeline="pipelines/default.toml")
    return [("flumekit make, default campaign from nothing", sec, msg + " (target < 60 s)"),
            *_stage_rows(project / "processed" / "default")]


def _default_build(project: Path) -> list[tuple[str, float, str]]:
    """Time the build of the default campaign with its raw data present.

    The main job's processed folder (this benchmark's own) is removed and ``flumekit make``
    (default -j) builds it again from the raw data the main job synthesised.
    """
    shutil.rmtree(project / "processed" / "default")
    sec, msg = _make(project, pipeline="pipelines/default.toml")
    return [("flumekit make, default campaign, raw present", sec, msg + " (target < 30 s)")]


def _paper_build(project: Path) -> list[tuple[str, float, str]]:
    """Time the paper campaign: its synthesis, then its cold build with -j 2 (raw present)."""
    from flumekit.synth import DEFAULT_SEED
    from flumekit.synth.campaign import write_campaign

    t0 = time.perf_counter()
    write_campaign(project / "raw" / "paper", size="paper", seed=DEFAULT_SEED)
    rows = [("synthesise paper campaign", time.perf_counter() - t0, "")]
    sec, msg = _make(project, "-j", "2", pipeline="pipelines/paper.toml")
    rows.append(("make -j 2, paper campaign, raw present", sec, msg + " (target < 120 s)"))
    return rows + _stage_rows(project / "processed" / "paper")


def loading(files, work: Path, copies: int = 41, repeat: int = 3,
            what: str = "") -> list[tuple[str, float, str]]:
    """Time opening a stage's runs with :func:`flumekit.open_processed` against xarray.

    The baseline is xarray's concatenation of the files (what ``open_processed`` did before
    it read the runs itself), in the same process. ``files`` (a built campaign's flap files,
    as the flap stage writes them) are repeated under distinct file names (the run labels
    inside repeat too) up to ``copies`` files in ``work``; each is also written as the
    flap stage wrote them before it stored its records uncompressed (zlib level 1 with
    shuffle), the files that xarray's concatenation is timed on as the baseline. Each way is
    timed ``repeat`` times in turn (best kept), so that a load that comes and goes on the
    machine weighs on each alike; the results are checked equal. ``what`` is said of the
    files in the table.
    """
    import statistics

    import xarray as xr

    from flumekit.io.netcdf import read_dataset, write_dataset
    from flumekit.io.processed import open_processed

    files = sorted(Path(f) for f in files)
    now, before = work / "now", work / "before"
    now.mkdir(parents=True)
    before.mkdir(parents=True)
    for k in range(copies):
        f = files[k % len(files)]
        name = f"{f.stem}_copy{k // len(files)}.nc"
        shutil.copyfile(f, now / name)
        write_dataset(read_dataset(f), before / name, compress=True)

    def concat(folder):
        runs = [read_dataset(f) for f in sorted(folder.glob("*.nc"))]
        return xr.concat(runs, dim="run", join="outer", combine_attrs="drop_conflicts",
                         coords="different", compat="equals")

    ways = {"xarray, files as written before": lambda: concat(before),
            "open_processed, files as written before": lambda: open_processed(before),
            "xarray, files as written now": lambda: concat(now),
            "open_processed, files as written now": lambda: open_processed(now)}
    times: dict[str, list[float]] = {k: [] for k in ways}
    results = {}
    for _ in range(repeat):
        for name, fn in ways.items():
            results.pop(name, None)  # the last result freed before the next is made
            t0 = time.perf_counter()
            results[name] = fn()
            times[name].append(time.perf_counter() - t0)
        ref = results["xarray, files as written before"]
        for ds in results.values():
            xr.testing.assert_identical(ds.drop_attrs(deep=False), ref.drop_attrs(deep=False))
        results.clear()
    # the recipe the README gave before open_processed read the runs itself (timed once: it
    # is by far the slowest, and lazily read it is not what an analyst's first plot waits for)
    t0 = time.perf_counter()
    xr.open_mfdataset(sorted(before.glob("*.nc")), combine="nested", concat_dim="run",
                      data_vars="all", coords="different", compat="equals", join="outer",
                      decode_times=False).load().close()
    recipe = time.perf_counter() - t0
    size = {k: sum(f.stat().st_size for f in d.glob("*.nc")) / 1e6
            for k, d in (("before", before), ("now", now))}
    base = min(times["xarray, files as written before"])
    rows = [(f"xr.open_mfdataset(...).load(), files as written before ({copies} flap "
             f"files{what})",
             recipe, f"{base / recipe:.2f} x faster than xarray's concatenation; timed once; "
             f"{size['before']:.0f} MB of files")]
    for name, ts in times.items():
        which = "before" if "before" in name else "now"
        rows.append((f"{name} ({copies} flap files{what})", min(ts),
                     f"{base / min(ts):.1f} x faster than xarray on the files as written "
                     f"before; median {statistics.median(ts):.2f} s; "
                     f"{size[which]:.0f} MB of files"))
    return rows


def run(quick: bool = False) -> str:
    """Run the benchmark and return its table as text.

    Parameters
    ----------
    quick : bool
        Only the no-op makes (no synthesis, no build).

    Returns
    -------
    str
        The printed table.
    """
    from flumekit.synth.campaign import write_campaign

    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        project = Path(tmp)
        shutil.copytree(ROOT / "pipelines", project / "pipelines")
        t, n = paper_noop(project)
        version, noop = t["version"], t["noop"]
        rows.append((f"paper-size no-op make ({n} targets)", noop[0],
                     f"{noop[0] / version[0]:.2f} x `flumekit --version` (target <= 3); "
                     f"median {noop[1]:.3f} s, {noop[1] / version[1]:.2f} x"))
        rows.append(("flumekit --version", version[0], f"best of 9; median {version[1]:.3f} s"))
        for name, what in (("checked", "every target checked (graph cached)"),
                           ("rebuilt", "graph rebuilt (campaign changed)")):
            rows.append((f"no-op make, {what}", t[name][0],
                         f"{t[name][0] / version[0]:.2f} x `flumekit --version`; best of 3"))
        if not quick:
            t0 = time.perf_counter()
            write_campaign(project / "raw" / "small", size="small", seed=1)
            rows.append(("synthesise small campaign", time.perf_counter() - t0, ""))
            rows.append(("make -j 1 (serial, all scenes)", *_make(project, "-j", "1")))
            rows += _stage_rows(project / "processed" / "small")
            rows.append(("make again (no-op)", *_make(project)))
            rows.append(("make -F -j 2 (processes)", *_make(project, "-F", "-j", "2")))
            rows.append(("make -n (dry run)", *_make(project, "-n")))
            rows += _main_job(project)
            rows += _default_build(project)
            # the default campaign's own flap files, as its build just wrote them (the 41
            # regular runs' of the issue: its irregular runs' records are longer)
            flap = sorted((project / "processed/default/flap").glob("*.nc"))
            flap = [f for f in flap if not f.name.startswith("JS_")] or flap
            rows += loading(flap, project / "loading", copies=len(flap),
                            what=": the default campaign's")
        if not quick:  # its own project: the paper no-op's placeholders fill this one
            paper = Path(tmp) / "paper"
            shutil.copytree(ROOT / "pipelines", paper / "pipelines")
            rows += _paper_build(paper)
    width = max(len(r[0]) for r in rows)
    lines = [f"{'step':<{width}}  {'wall [s]':>8}  result", "-" * (width + 40)]
    lines += [f"{name:<{width}}  {sec:8.2f}  {msg}" for name, sec, msg in rows]
    return "\n".join(lines)


if __name__ == "__main__":
    print(run())
