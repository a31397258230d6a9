"""The ``flumekit`` command line: parses arguments and calls the pipeline; nothing else."""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

from flumekit.errors import FlumekitError

DEFAULT_PIPELINE = Path("pipelines") / "default.toml"


def _progress(i: int, n: int, run_id: str) -> None:
    print(f"    [{i + 1}/{n}] {run_id}", file=sys.stderr)


def _pipeline(args):
    from flumekit.pipeline.config import load_pipeline

    path = Path(args.pipeline)
    if not path.exists():
        raise FlumekitError(f"{path}: pipeline file not found (run from the project root, or "
                            f"give --pipeline FILE)")
    return load_pipeline(path, processed=getattr(args, "processed", None))


def _graph(pipe, synthesise: bool):
    from flumekit.campaign import load_campaign
    from flumekit.pipeline.engine import Graph
    from flumekit.stages import build_rules, check_stage_params
    from flumekit.stages.context import Context

    if not (pipe.raw / "campaign.toml").exists():
        # The virtual flume is written only into an absent or empty folder: a raw path one
        # folder off or a renamed campaign.toml must never cost a laboratory its files.
        empty = not pipe.raw.exists() or (pipe.raw.is_dir() and not any(pipe.raw.iterdir()))
        if not (synthesise and pipe.synth and empty):
            why = ("" if empty else "; the folder holds other files, so no virtual campaign is "
                   "written there (nothing was changed)")
            raise FlumekitError(f"{pipe.raw / 'campaign.toml'}: campaign file not found{why}. "
                                f"Check 'raw' in {pipe.path}")
        from flumekit.synth.campaign import write_campaign

        size, seed = pipe.synth.get("size", "default"), int(pipe.synth.get("seed", 0))
        print(f"synthesising the '{size}' virtual-flume campaign into {pipe.raw} ...",
              file=sys.stderr)
        t0 = time.perf_counter()
        write_campaign(pipe.raw, size=size, seed=seed, progress=_progress)
        print(f"    done in {time.perf_counter() - t0:.1f} s", file=sys.stderr)
    check_stage_params(pipe.stages, pipe.path)
    campaign = load_campaign(pipe.raw)
    ctx = Context(campaign=campaign, processed=pipe.processed, params=pipe.stages)
    return Graph(build_rules(ctx))


def _targets(pipe, graph, names: list[str]) -> list[str]:
    if not names:
        # every scene the campaign's instruments allow (a waves study has no flap scenes)
        names = [t for targets in pipe.scenes.values() for t in targets
                 if graph.match_any(t)] or ["*"]
    patterns: list[str] = []
    for n in names:
        patterns += pipe.scenes.get(n, [n])
    return graph.match(patterns)


def cmd_make(args) -> int:
    from flumekit.pipeline.engine import make, plan
    from flumekit.pipeline.executors import executor_for
    from flumekit.pipeline.state import State

    pipe = _pipeline(args)
    graph = _graph(pipe, synthesise=not args.dry_run)
    targets = _targets(pipe, graph, args.targets)
    state = State(pipe.state_file)
    if args.dry_run:
        steps = plan(graph, targets, state, force=args.force)
        state.save()
        for t, reason in steps:
            print(f"would build {t}: {reason}")
        if not steps:
            print(f"nothing to do: {len(graph.closure(targets))} target(s) up to date")
        return 0
    with executor_for(args.jobs, args.scheduler, args.executor) as ex:
        report = make(graph, targets, state, ex, force=args.force)
    _results(graph, report)
    return 0


def _results(graph, report) -> None:
    """The make summary's results: each waves run built now, with its first-harmonic Kr."""
    built = [t for t, *_ in report.ran if t.startswith("waves/")]
    if built:
        from flumekit.stages.waves import report as waves_report

        print("results:")
        for t in built:
            print(f"  {t}: {waves_report(graph.rules[t].outputs['dataset'])}")


def cmd_list(args) -> int:
    from flumekit.pipeline.engine import plan
    from flumekit.pipeline.state import State

    pipe = _pipeline(args)
    graph = _graph(pipe, synthesise=False)
    state = State(pipe.state_file)
    stale = dict(plan(graph, list(graph.rules), state))
    print("scenes:")
    for name, targets in pipe.scenes.items():
        if not all(graph.match_any(t) for t in targets):
            print(f"  {name:<20} {'not available':<22} (needs instruments this campaign "
                  "does not declare)")
            continue
        needed = graph.closure(graph.match(targets))
        n_stale = sum(t in stale for t in needed)
        status = "up to date" if n_stale == 0 else f"{n_stale} of {len(needed)} to build"
        print(f"  {name:<20} {status:<22} {' '.join(targets)}")
    print("targets:")
    for t in graph.rules:
        print(f"  {t:<40} {stale.get(t, 'up to date')}")
    return 0


def cmd_synth(args) -> int:
    from flumekit.synth.campaign import write_campaign

    out = Path(args.out)
    t0 = time.perf_counter()
    write_campaign(out, size=args.size, seed=args.seed, progress=_progress)
    print(f"wrote the '{args.size}' virtual-flume campaign to {out} in "
          f"{time.perf_counter() - t0:.1f} s")
    return 0


def cmd_new(args) -> int:
    """A commented campaign skeleton (campaign, one run, pipeline) in an absent or empty folder."""
    from importlib import resources

    out = Path(args.dir)
    if out.exists() and (not out.is_dir() or any(out.iterdir())):
        raise FlumekitError(f"{out}: not an empty folder; `flumekit new` writes only into an "
                            "absent or empty one (nothing was changed)")
    skel = resources.files("flumekit.data").joinpath("skeleton")
    name = out.resolve().name
    files = {"campaign.toml": "campaign.toml", "runs/run01/run.toml": "run.toml",
             "pipeline.toml": "pipeline.toml"}
    for dest, src in files.items():
        text = skel.joinpath(src).read_text().replace("my_campaign", name)
        (out / dest).parent.mkdir(parents=True, exist_ok=True)
        (out / dest).write_text(text)
    print(f"wrote {', '.join(files)} to {out}: edit them, put each run's files in "
          f"runs/<run>/, then `flumekit make --pipeline {out / 'pipeline.toml'}`")
    return 0


def cmd_params(args) -> int:
    from flumekit.stages import parameters, parameters_markdown

    if args.markdown:
        print(parameters_markdown())
        return 0
    known = parameters()
    stages = [args.stage] if args.stage else list(known)
    for s in stages:
        if s not in known:
            from flumekit.schema import suggest

            raise FlumekitError(f"no stage '{s}' with parameters; known: {', '.join(known)}"
                                + suggest(s, list(known)))
        print(f"[stages.{s}]")
        for k, (default, doc) in known[s].items():
            print(f"  {k} = {default!r}\n      {doc}")
    return 0


def cmd_clock(args) -> int:
    """Estimate (never apply) an instrument's clock offset from a signal two instruments share."""
    from flumekit.campaign import load_campaign
    from flumekit.io.instruments import read_flap, read_probes
    from flumekit.signal import estimate_time_offset

    pipe = _pipeline(args)
    c = load_campaign(pipe.raw)
    try:
        run = c.run(args.run)
    except KeyError as e:
        raise FlumekitError(str(e.args[0])) from None

    def channel(spec: str):
        inst, _, name = spec.partition(":")
        if inst == "probes" and name in c.probes.names:
            ds = read_probes(run.file("probes"), c.probes.names, c.probes.sampling_rate,
                             c.dialect("probes"), units=c.probes.units)
            v = next(iter(ds.data_vars.values())).sel(probe=name)
            return v.values, ds["time"].values
        if inst == "flap" and c.encoder and name in ("encoder", "pressure"):
            ds = read_flap(run.file("flap"), c.encoder.sampling_rate, c.dialect("flap"))
            v = ds["encoder_counts" if name == "encoder" else "chamber_pressure"]
            return v.values.astype(float), ds["time"].values
        raise FlumekitError(f"unknown channel {spec!r}: probes:<probe> or flap:encoder|pressure")

    (a, ta), (b, tb) = channel(args.reference), channel(args.other)
    offset = estimate_time_offset(a, ta, b, tb)
    inst = args.other.partition(":")[0]
    print(f"{args.other} matches {args.reference} when its time stamps are shifted by "
          f"{offset:+.4f} s. If both record the same signal, declare it in "
          f"{run.path / 'run.toml'}:\n  [clock]\n  {inst} = {offset:.4f}\n"
          "(nothing was changed; between different quantities the estimate includes their "
          "physical phase lag)")
    return 0


def cmd_bench(args) -> int:
    import importlib

    try:
        mod = importlib.import_module(f"flumekit.bench.{args.area}")
    except ModuleNotFoundError:
        import pkgutil

        import flumekit.bench as b

        areas = [m.name for m in pkgutil.iter_modules(b.__path__)]
        raise FlumekitError(f"no benchmark '{args.area}'; available: {', '.join(areas)}") from None
    print(mod.run(quick=args.quick))
    return 0


def cmd_report(args) -> int:
    from flumekit.report import write_report

    pipe = _pipeline(args)
    t0 = time.perf_counter()
    out = write_report(pipe.processed, out=args.out)
    print(f"wrote {out} in {time.perf_counter() - t0:.2f} s (open it in a browser; no server "
          "needed)")
    return 0


def parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="flumekit", description=__doc__)
    p.add_argument("--debug", action="store_true", help="show tracebacks")
    sub = p.add_subparsers(dest="command", required=True)

    def pipeline_opts(sp):
        sp.add_argument("--pipeline", default=str(DEFAULT_PIPELINE),
                        help="pipeline file (default: pipelines/default.toml)")
        sp.add_argument("--processed", default=None,
                        help="write processed data here instead of the pipeline's folder")

    m = sub.add_parser("make", help="build targets or scenes (default: every scene)")
    m.add_argument("targets", nargs="*", help="scene names, target names or glob patterns")
    m.add_argument("-n", "--dry-run", action="store_true", help="print what would run and why")
    m.add_argument("-j", "--jobs", type=int, default=1, help="rules run in parallel locally")
    m.add_argument("--executor", choices=("processes", "threads"), default="processes")
    m.add_argument("--force", action="store_true", help="rebuild even if up to date")
    m.add_argument("--scheduler", default=None,
                   help="dask.distributed scheduler address (or DASK_SCHEDULER_ADDRESS)")
    pipeline_opts(m)
    m.set_defaults(func=cmd_make)

    ls = sub.add_parser("list", help="targets and scenes with their state")
    pipeline_opts(ls)
    ls.set_defaults(func=cmd_list)

    s = sub.add_parser("synth", help="write a virtual-flume raw campaign and its truth")
    s.add_argument("--size", choices=("small", "default", "paper"), default="small")
    s.add_argument("--seed", type=int, default=2020)
    s.add_argument("--out", default="raw/synthetic",
                   help="an absent or empty folder (existing files are never overwritten)")
    s.set_defaults(func=cmd_synth)

    n = sub.add_parser("new", help="write a commented campaign skeleton into an empty folder")
    n.add_argument("dir")
    n.set_defaults(func=cmd_new)

    pa = sub.add_parser("params", help="stage parameters: defaults and meaning")
    pa.add_argument("stage", nargs="?", help="one stage (default: all)")
    pa.add_argument("--markdown", action="store_true", help="the reference as Markdown")
    pa.set_defaults(func=cmd_params)

    ck = sub.add_parser("clock", help="estimate a clock offset by cross-correlation (reported, "
                        "never applied)")
    ck.add_argument("run")
    ck.add_argument("reference", help="probes:<probe> or flap:encoder|pressure")
    ck.add_argument("other", help="the channel whose clock offset is estimated")
    pipeline_opts(ck)
    ck.set_defaults(func=cmd_clock)

    r = sub.add_parser("report", help="one static HTML page for the processed campaign")
    r.add_argument("--out", default=None,
                   help="file name in the processed folder (default: report.html there)")
    pipeline_opts(r)
    r.set_defaults(func=cmd_report)

    b = sub.add_parser("bench", help="accuracy-versus-run-time benchmarks")
    b.add_argument("area", help="waves, flap, uvp, renzi_dias, simulator, ballscrew, pipeline")
    b.add_argument("--quick", action="store_true")
    b.set_defaults(func=cmd_bench)
    return p


def main(argv: list[str] | None = None) -> int:
    args = parser().parse_args(argv)
    try:
        return args.func(args)
    except FlumekitError as e:
        if args.debug:
            raise
        print(f"flumekit: error: {e}", file=sys.stderr)
        return 1
    except KeyboardInterrupt:
        print("flumekit: interrupted", file=sys.stderr)
        return 130


if __name__ == "__main__":
    sys.exit(main())
