"""Pipeline benchmark: synthesis, a full build serial and with 2 processes, the no-op build,
and the planning cost of a paper-size campaign against a bare ``flumekit --version``.

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
    """(best, median) wall-clock seconds of each command, run in turn ``repeat`` times (in
    turn, so that a load that comes and goes on the machine weighs on each alike); ``before``
    runs untimed before each command."""
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
    """(best, median) seconds of ``flumekit --version`` and of the no-op make: as it runs after
    a make ("noop"), without the record of that make ("checked": every target checked, the
    graph from its cache) and without the graph's cache either ("rebuilt"); and the number of
    targets, on a paper-size campaign's graph."""
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
        (r.path / "run.toml").write_text(run_toml(r.kind, r.period, r.height, r.repeat,
                                                  r.uvp_elevation, r.probe_x))
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
    """Rule seconds per stage of the last build (the engine records each rule's run time), the
    stages that cost most first, and the mean time of a figure (PNG at 300 dpi and PDF)."""
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
    """The README's main job on a fresh project: ``flumekit make`` (default -j), synthesis of the
    default campaign included, then the rule times of that build."""
    sec, msg = _make(project, pipeline="pipelines/default.toml")
    return [("flumekit make, default campaign from nothing", sec, msg + " (target < 60 s)"),
            *_stage_rows(project / "processed" / "default")]


def run(quick: bool = False) -> str:
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
    width = max(len(r[0]) for r in rows)
    lines = [f"{'step':<{width}}  {'wall [s]':>8}  result", "-" * (width + 40)]
    lines += [f"{name:<{width}}  {sec:8.2f}  {msg}" for name, sec, msg in rows]
    return "\n".join(lines)


if __name__ == "__main__":
    print(run())
