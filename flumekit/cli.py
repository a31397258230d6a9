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
    from flumekit.stages import build_rules
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
    campaign = load_campaign(pipe.raw)
    ctx = Context(campaign=campaign, processed=pipe.processed, params=pipe.stages)
    return Graph(build_rules(ctx))


def _targets(pipe, graph, names: list[str]) -> list[str]:
    if not names:
        names = [t for targets in pipe.scenes.values() for t in targets] or ["*"]
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
        make(graph, targets, state, ex, force=args.force)
    return 0


def cmd_list(args) -> int:
    from flumekit.pipeline.engine import plan
    from flumekit.pipeline.state import State

    pipe = _pipeline(args)
    graph = _graph(pipe, synthesise=False)
    state = State(pipe.state_file)
    stale = dict(plan(graph, list(graph.rules), state))
    print("scenes:")
    for name, targets in pipe.scenes.items():
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
