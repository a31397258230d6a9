"""The ``flumekit`` command line: parses arguments and calls the pipeline; nothing else.

Flags follow make and snakemake: ``-n`` dry run, ``-j N`` jobs, ``-k`` keep going, ``-f``/
``--force`` rebuilds the named targets only, ``-F``/``--forceall`` everything they need;
``--debug``, ``-q`` and ``-v`` work before or after the subcommand.

Each subcommand has one handler, ``cmd_<name>(args) -> int``: it takes the parsed command
line (:func:`parser`, whose help is the reference for every option) and returns the exit
status, 0 on success.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

from flumekit.errors import FlumekitError

DEFAULT_PIPELINE = Path("pipelines") / "default.toml"
#: what `flumekit --help` says (plain text: argparse prints it as it stands)
DESCRIPTION = ("Wave-flume experiments on wave energy converters: build the processed data, "
               "figures and report of a campaign from its raw files (make), inspect the "
               "pipeline (list, graph, params), write a virtual campaign (synth) or a "
               "campaign skeleton (new). Flags follow make: -n dry run, -j N jobs, -k keep "
               "going, -f rebuild the named targets, -F also everything they need; --debug, "
               "-q and -v work before or after the subcommand.")
#: how much `make` says: 0 quiet (errors and the closing summary), 1 normal, 2 verbose
_VERBOSITY = {"quiet": 0, "normal": 1, "verbose": 2}


def _say(args, level: int, text: str) -> None:
    if _verbosity(args) >= level:
        print(text, file=sys.stderr)


def _verbosity(args) -> int:
    return 1 - getattr(args, "quiet", 0) + getattr(args, "verbose", 0)


def _progress(i: int, n: int, run_id: str) -> None:  # for `flumekit synth`
    print(f"    [{i + 1}/{n}] {run_id}", file=sys.stderr)


def _pipeline(args):
    from flumekit.pipeline.config import load_pipeline

    path = Path(args.pipeline)
    if not path.exists():
        raise FlumekitError(f"{path}: pipeline file not found (run from the project root, or "
                            f"give --pipeline FILE)")
    return load_pipeline(path, processed=getattr(args, "processed", None))


def _graph(pipe, key_lazy: tuple | None = None):
    from flumekit.stages.plan import pipeline_graph

    return pipeline_graph(pipe, key_lazy)


def _targets(pipe, graph, names: list[str]) -> list[str]:
    if not names:
        # every scene the campaign's instruments allow (a waves study has no flap scenes)
        names = [t for targets in pipe.scenes.values() for t in targets
                 if graph.match_any(t)] or ["*"]
    patterns: list[str] = []
    for n in names:
        patterns += pipe.scenes.get(n, [n])
    return graph.match(patterns)


def _events(args):
    """Progress of a build: a bar with rate and time left on a terminal, plain lines in logs."""
    from flumekit.pipeline.engine import Events

    level = _verbosity(args)
    if level <= 0:
        return Events(lambda s: None)
    if sys.stderr.isatty():
        return _BarEvents(verbose=level >= 2)
    return Events(finished=level >= 2)


class _BarEvents:
    """tqdm progress bar: targets done of those needed, rate, elapsed and time left."""

    def __init__(self, verbose: bool):
        self.verbose, self.bar = verbose, None

    def start(self, n_total: int) -> None:
        from tqdm import tqdm

        self.bar = tqdm(total=n_total, unit="target", file=sys.stderr, dynamic_ncols=True,
                        bar_format="{l_bar}{bar}| {n}/{total} [{elapsed}<{remaining}, "
                                   "{rate_fmt}] {postfix}")

    def started(self, i, n, target, reason) -> None:
        self.bar.set_postfix_str(target, refresh=True)
        if self.verbose:
            self.bar.write(f"[{i}/{n}] {target}: {reason}", file=sys.stderr)

    def finished(self, target, seconds) -> None:
        if self.verbose:
            self.bar.write(f"    {target} done in {seconds:.2f} s", file=sys.stderr)
        self.bar.update(1)

    def skipped(self, target) -> None:
        self.bar.update(1)

    def failed(self, failure) -> None:
        self.bar.write(f"    {failure.target} FAILED: {failure.problem}", file=sys.stderr)
        self.bar.update(1)

    def close(self) -> None:
        if self.bar is not None:
            self.bar.close()


def _interrupts():
    """Count Ctrl-C and return whether one was pressed.

    The first Ctrl-C raises KeyboardInterrupt as usual, and the engine also stops before its
    next target if some library swallowed that exception.
    """
    import signal

    seen: list[int] = []

    def on_int(signum, frame):
        seen.append(signum)
        raise KeyboardInterrupt

    if signal.getsignal(signal.SIGINT) is signal.default_int_handler:
        signal.signal(signal.SIGINT, on_int)
    return lambda: bool(seen)


def _forced(args, pipe, graph) -> tuple[bool, list[str]]:
    if args.forceall:
        return True, []
    if args.force:
        return False, _targets(pipe, graph, args.targets)
    return False, []


def cmd_make(args) -> int:
    """Run ``flumekit make``: build the requested targets (default: every scene).

    Holds the build lock of the processed folder; a make with nothing to do answers from
    the up-to-date record without reading the graph.

    Raises
    ------
    flumekit.errors.FlumekitError
        The first failure (without ``-k``), naming its rule and run.
    """
    import time

    from flumekit.io.atomic import remove_orphans
    from flumekit.pipeline import cache
    from flumekit.pipeline.lock import build_lock

    pipe = _pipeline(args)
    if args.dry_run:
        return _dry_run(args, pipe)
    with build_lock(pipe.processed, say=lambda s: _say(args, 0, s)):
        t0 = time.perf_counter()
        orphans = remove_orphans(pipe.processed)
        if orphans:
            _say(args, 2, f"removed {len(orphans)} temporary file(s) of an interrupted build")
        key, lazy = cache.pipeline_key(pipe)
        # what was asked: a make asked the same, with nothing changed since, has nothing to do
        stamp = pipe.processed / ".flumekit-up-to-date.json"
        request = (None if key is None or args.force or args.forceall
                   else cache.request_key(key, args.targets, pipe.scenes))
        done = cache.up_to_date(stamp, request, pipe.state_file)
        if done is not None:
            from flumekit.pipeline.engine import Report

            report = Report([], done, seconds=time.perf_counter() - t0)
            _summary(args, pipe, None, report)
            return 0
        cache.forget_up_to_date(stamp)
        from flumekit.pipeline.engine import make
        from flumekit.pipeline.executors import executor_for
        from flumekit.pipeline.state import State

        graph = _graph(pipe, (key, lazy))
        targets = _targets(pipe, graph, args.targets)
        forceall, forced = _forced(args, pipe, graph)
        state = State(pipe.state_file)
        with executor_for(args.jobs, args.scheduler, args.executor, args.dask_timeout,
                          exit_on_interrupt=True) as ex:
            report = make(graph, targets, state, ex, force=forceall, force_targets=forced,
                          interrupted=_interrupts(),
                          root=pipe.path.parent.resolve(),
                          keep_going=args.keep_going, events=_events(args))
        if not report.failed and not report.blocked:
            cache.record_up_to_date(stamp, request, pipe.state_file, graph, targets)
        # read while the lock is held: a `flumekit clean` waiting on it may remove them
        _results(graph, report)
        warned = _warnings(graph, report)
    _summary(args, pipe, graph, report)
    _say_warnings(warned)
    return 1 if report.failed else 0


def _dry_run(args, pipe) -> int:
    from flumekit.pipeline.engine import plan
    from flumekit.pipeline.state import State

    graph = _graph(pipe)
    targets = _targets(pipe, graph, args.targets)
    forceall, forced = _forced(args, pipe, graph)
    steps = plan(graph, targets, State(pipe.state_file), force=forceall, force_targets=forced)
    for t, reason in steps:
        print(f"would build {t}: {reason}")
    if not steps:
        print(f"nothing to do: {len(graph.closure(targets))} target(s) up to date")
    return 0


def _summary(args, pipe, graph, report) -> None:
    """Print the closing lines of a build: counts, failures, where the outputs are, what next."""
    import os

    try:
        where = os.path.relpath(pipe.processed)
    except ValueError:
        where = str(pipe.processed)
    counts = [f"built {len(report.ran)}", f"up to date {len(report.skipped)}"]
    if report.failed:
        counts.append(f"failed {len(report.failed)}")
    if report.blocked:
        counts.append(f"not built (input failed) {len(report.blocked)}")
    if not report.ran and not report.failed:
        print(f"nothing to do: all {len(report.skipped)} target(s) up to date "
              f"({report.seconds:.2f} s)", file=sys.stderr)
    else:
        print(f"{', '.join(counts)} in {report.seconds:.1f} s", file=sys.stderr)
    if report.failed:
        print("failures (target, run, file: problem):", file=sys.stderr)
        for f in report.failed:
            print(f"  {f.target}  run {f.run or '-'}  {f.file or '-'}: {f.problem}",
                  file=sys.stderr)
        if report.removed:
            print(f"removed the outputs of {len(report.removed)} target(s) built from the "
                  "failed ones (no stale result stays readable)", file=sys.stderr)
    figures = [str(p) for t, _, _ in report.ran if t.startswith("figure/")
               for p in graph.rules[t].outputs.values()]
    print(f"outputs in {where}/", file=sys.stderr)
    if figures:
        shown = ", ".join(os.path.relpath(f) for f in figures[:4])
        more = f" and {len(figures) - 4} more" if len(figures) > 4 else ""
        print(f"figures written: {shown}{more}", file=sys.stderr)
    pipe_opt = "" if Path(args.pipeline) == DEFAULT_PIPELINE else f" --pipeline {args.pipeline}"
    if report.failed:
        nxt = (f"fix the files named above, then `flumekit make{pipe_opt}` (add -k to build "
               "everything else meanwhile)")
    else:
        nxt = f"`flumekit list{pipe_opt}` for every target and scene"
    print(f"next: {nxt}", file=sys.stderr)


def _warnings(graph, report) -> list[str]:
    """Return the warnings of the datasets built now, each once and naming its run.

    They are the datasets' ``flumekit_warnings`` attribute.
    """
    from flumekit.conventions import WARNINGS, run_warnings
    from flumekit.io.run_files import text_attributes

    built = [(graph.rules[t].run, p) for t, *_ in report.ran
             for p in graph.rules[t].outputs.values() if str(p).endswith(".nc")
             and Path(p).is_file()]
    try:
        texts = text_attributes([p for _, p in built], WARNINGS)
    except OSError:  # a product that cannot be read: the others' warnings all the same
        texts = []
        for _, p in built:
            try:
                texts += text_attributes([p], WARNINGS)
            except OSError:
                texts.append(None)
    found: list[str] = []
    for (run, _), text in zip(built, texts, strict=True):
        found += run_warnings(run, text or "")
    return list(dict.fromkeys(found))


def _say_warnings(warned: list[str], first: int = 5) -> None:
    if warned:
        print(f"warnings: {len(warned)}" + (f" (the first {first})" if len(warned) > first
                                            else "") + "; all of them in the summaries' "
              "flumekit_warnings and in `flumekit report`:", file=sys.stderr)
        for w in warned[:first]:
            print(f"  {w}", file=sys.stderr)


def _results(graph, report) -> None:
    """Print the make summary's results: each waves run built now, with its first-harmonic Kr."""
    built = [t for t, *_ in report.ran if t.startswith("waves/")]
    if built:
        from flumekit.stages.waves_run import report as waves_report

        print("results:")
        lines = waves_report([graph.rules[t].outputs["dataset"] for t in built])
        for t, line in zip(built, lines, strict=True):
            print(f"  {t}: {line}")


def cmd_list(args) -> int:
    """Run ``flumekit list``: the scenes and every target, marking those out of date."""
    from flumekit.pipeline.engine import plan
    from flumekit.pipeline.state import State

    pipe = _pipeline(args)
    graph = _graph(pipe)
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


def cmd_graph(args) -> int:
    """Run ``flumekit graph``: print the dependency graph of the targets as DOT or Mermaid.

    The targets default to every scene.
    """
    from flumekit.pipeline.render import render

    pipe = _pipeline(args)
    graph = _graph(pipe)
    print(render(graph, graph.closure(_targets(pipe, graph, args.targets)), args.format))
    return 0


def cmd_clean(args) -> int:
    """Remove the outputs of the targets (default: every target) and forget their builds.

    Only files the pipeline declares as outputs under the processed folder are removed; raw
    data (and the virtual flume's synthesised campaign) is never touched.
    """
    from flumekit.pipeline.engine import remove_outputs
    from flumekit.pipeline.lock import build_lock
    from flumekit.pipeline.state import State

    pipe = _pipeline(args)
    graph = _graph(pipe)
    targets = _targets(pipe, graph, args.targets) if args.targets else list(graph.rules)
    with build_lock(pipe.processed, say=lambda s: _say(args, 0, s)):
        state = State(pipe.state_file)
        removed = remove_outputs(graph, state, targets, within=pipe.processed,
                                 dry_run=args.dry_run)
        if not args.dry_run:
            state.save()
    files = [p for t in targets for p in removed.get(t, [])]
    if args.dry_run:
        for p in files:
            print(f"would remove {p}")
    verb = "would remove" if args.dry_run else "removed"
    _say(args, 0, f"{verb} {len(files)} file(s) of {len(targets)} target(s) under "
                  f"{pipe.processed}")
    return 0


def cmd_synth(args) -> int:
    """Run ``flumekit synth``: write a virtual-flume campaign into a new folder."""
    from flumekit.synth.campaign import write_campaign

    out = Path(args.out)
    t0 = time.perf_counter()
    write_campaign(out, size=args.size, seed=args.seed, progress=_progress)
    print(f"wrote the '{args.size}' virtual-flume campaign to {out} in "
          f"{time.perf_counter() - t0:.1f} s")
    return 0


def cmd_new(args) -> int:
    """Run ``flumekit new``: write a commented campaign skeleton into an absent or empty folder.

    The skeleton holds a campaign file, one run and a pipeline file.

    Raises
    ------
    flumekit.errors.FlumekitError
        When the folder holds files.
    """
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
    """Run ``flumekit params``: print the stage parameters with defaults and units."""
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
    """Run ``flumekit clock``: estimate (never apply) an instrument's clock offset.

    The offset is that of a signal two instruments share
    (:func:`flumekit.signal.estimate_time_offset`).
    """
    from flumekit.campaign import load_campaign
    from flumekit.io.instruments import FLAP_VARIABLES, read_flap, read_probes
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
                             c.dialect("probes", run), units=c.probes.units)
            v = next(iter(ds.data_vars.values())).sel(probe=name)
            return v.values, ds["time"].values
        if inst == "flap" and c.encoder and name in FLAP_VARIABLES:
            ds = read_flap(run.file("flap"), c.encoder.sampling_rate,
                           c.dialect("flap", run))
            return ds[FLAP_VARIABLES[name]].values.astype(float), ds["time"].values
        raise FlumekitError(f"unknown channel {spec!r}: probes:<probe> or "
                            f"flap:{'|'.join(FLAP_VARIABLES)}")

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
    """Run ``flumekit bench``: the accuracy-versus-run-time benchmarks of one area.

    Raises
    ------
    flumekit.errors.FlumekitError
        For an area that has no benchmark.
    """
    import importlib

    from flumekit.bench import areas

    if args.area not in areas():
        raise FlumekitError(f"no benchmark '{args.area}'; available: {', '.join(areas())}")
    print(importlib.import_module(f"flumekit.bench.{args.area}").run(quick=args.quick))
    return 0


def cmd_report(args) -> int:
    """Run ``flumekit report``: write the campaign report from the processed data."""
    from flumekit.report import write_report

    pipe = _pipeline(args)
    t0 = time.perf_counter()
    title = None
    if (pipe.raw / "campaign.toml").is_file():
        from flumekit.campaign import load_campaign

        title = load_campaign(pipe.raw).title
    out = write_report(pipe.processed, out=args.out, title=title)
    print(f"wrote {out} in {time.perf_counter() - t0:.2f} s (open it in a browser; no server "
          "needed)")
    return 0


def _version() -> str:
    from flumekit import __version__  # not importlib.metadata, which is slow on every call

    return __version__


def _global_options(sub: bool) -> argparse.ArgumentParser:
    """Return the parser of --debug, -q and -v, accepted before and after the subcommand.

    The subcommand's copy must not reset what was given before it, hence SUPPRESS.
    """
    g = argparse.ArgumentParser(add_help=False)
    kw = {"default": argparse.SUPPRESS} if sub else {}
    g.add_argument("--debug", action="store_true", help="show tracebacks", **kw)
    g.add_argument("-q", "--quiet", action="count", help="say less (errors and the summary)",
                   **({"default": argparse.SUPPRESS} if sub else {"default": 0}))
    g.add_argument("-v", "--verbose", action="count", help="say more (every target)",
                   **({"default": argparse.SUPPRESS} if sub else {"default": 0}))
    return g


def parser() -> argparse.ArgumentParser:
    """Return the parser of the ``flumekit`` command line.

    Returns
    -------
    argparse.ArgumentParser
        With one subcommand per ``cmd_*`` function, each bound as ``func``.

    Examples
    --------
    >>> args = parser().parse_args(["make", "-n", "-j", "2", "waves/*"])
    >>> args.func.__name__, args.dry_run, args.jobs, args.targets
    ('cmd_make', True, 2, ['waves/*'])
    """
    from flumekit.bench import areas as bench_areas
    from flumekit.synth import DEFAULT_SEED

    p = argparse.ArgumentParser(prog="flumekit", description=DESCRIPTION,
                                parents=[_global_options(sub=False)])
    p.add_argument("--version", action="version", version=f"flumekit {_version()}")
    sub = p.add_subparsers(dest="command", required=True)
    common = [_global_options(sub=True)]

    def pipeline_opts(sp):
        sp.add_argument("--pipeline", default=str(DEFAULT_PIPELINE),
                        help="pipeline file (default: pipelines/default.toml, relative to the "
                             "current folder)")
        sp.add_argument("--processed", default=None,
                        help="write processed data here instead of the pipeline's folder")

    m = sub.add_parser("make", help="build targets or scenes (default: every scene)",
                       description="Build targets or scenes (default: every scene the "
                                   "pipeline file names); only what is out of date runs.",
                       parents=common)
    m.add_argument("targets", nargs="*", help="scene names, target names or glob patterns")
    m.add_argument("-n", "--dry-run", action="store_true", help="print what would run and why")
    m.add_argument("-j", "--jobs", type=int, default=None,
                   help="rules run in parallel locally (default: one per CPU this process may "
                        "use, at most one per GiB of memory; -j 1 runs them one after another "
                        "in this process)")
    m.add_argument("-k", "--keep-going", action="store_true",
                   help="after a failure, build everything that does not depend on it; list "
                        "the failures at the end (exit status 1)")
    m.add_argument("--executor", choices=("processes", "threads"), default="processes",
                   help="with -j N: run rules in worker processes (default) or in threads "
                        "of this process")
    m.add_argument("-f", "--force", action="store_true",
                   help="rebuild the named targets even if up to date (not their inputs)")
    m.add_argument("-F", "--forceall", action="store_true",
                   help="rebuild the named targets and everything they need")
    m.add_argument("--scheduler", default=None,
                   help="dask.distributed scheduler address (or DASK_SCHEDULER_ADDRESS)")
    m.add_argument("--dask-timeout", type=float, default=30.0,
                   help="seconds to reach the scheduler, and that a cluster may stay without "
                        "workers, before the build stops (default 30)")
    pipeline_opts(m)
    m.set_defaults(func=cmd_make)

    ls = sub.add_parser("list", help="targets and scenes with their state", parents=common,
                        description="List every target and scene of the pipeline with its "
                                    "state (up to date, out of date or missing).")
    pipeline_opts(ls)
    ls.set_defaults(func=cmd_list)

    g = sub.add_parser("graph", help="dependency graph of targets (DOT or Mermaid)",
                       description="Print the dependency graph of targets as DOT or "
                                   "Mermaid text.", parents=common)
    g.add_argument("targets", nargs="*", help="scene names, target names or glob patterns")
    g.add_argument("--format", choices=("dot", "mermaid"), default="dot",
                   help="output language (default: dot, for Graphviz)")
    pipeline_opts(g)
    g.set_defaults(func=cmd_graph)

    c = sub.add_parser("clean", help="remove built outputs (never raw data)", parents=common,
                       description="Remove built outputs of the named targets (never raw "
                                   "data).")
    c.add_argument("targets", nargs="*", help="scene names, target names or glob patterns "
                                              "(default: every target)")
    c.add_argument("-n", "--dry-run", action="store_true", help="print what would be removed")
    pipeline_opts(c)
    c.set_defaults(func=cmd_clean)

    s = sub.add_parser("synth", help="write a virtual-flume raw campaign and its truth",
                       description="Write a virtual-flume raw campaign (the raw format) "
                                   "and the truth it was made from.", parents=common)
    s.add_argument("--size", choices=("small", "default", "paper"), default="small",
                   help="how many runs: small (2 regular, 2 UVP and 1 irregular run, for trying "
                        "things), default (the shipped campaign: every period at 3 heights, "
                        "4 sea states) or paper (the papers' 78 UVP repeats and a 3 x 4 "
                        "power matrix); default small")
    s.add_argument("--seed", type=int, default=DEFAULT_SEED,
                   help=f"random seed (default {DEFAULT_SEED}, as the shipped pipelines)")
    s.add_argument("--out", default="raw/synthetic",
                   help="an absent or empty folder (existing files are never overwritten)")
    s.set_defaults(func=cmd_synth)

    n = sub.add_parser("new", help="write a commented campaign skeleton into an empty folder",
                       description="Write a commented campaign skeleton (campaign.toml, "
                                   "a run, a pipeline file) into an empty folder.")
    n.add_argument("dir", help="an absent or empty folder")
    n.set_defaults(func=cmd_new)

    pa = sub.add_parser("params", help="stage parameters: defaults and meaning",
                        description="Print the parameters of the stages ([stages.<name>] "
                                    "in a pipeline file): default, unit and meaning.")
    pa.add_argument("stage", nargs="?", help="one stage (default: all)")
    pa.add_argument("--markdown", action="store_true", help="the reference as Markdown")
    pa.set_defaults(func=cmd_params)

    ck = sub.add_parser("clock", help="estimate a clock offset by cross-correlation (reported, "
                        "never applied)",
                        description="Estimate the clock offset of one channel against "
                                    "another of the same run by cross-correlation (reported, "
                                    "never applied).")
    ck.add_argument("run", help="run name (its folder under runs/)")
    ck.add_argument("reference", help="probes:<probe> or flap:encoder|pressure")
    ck.add_argument("other", help="the channel whose clock offset is estimated")
    pipeline_opts(ck)
    ck.set_defaults(func=cmd_clock)

    r = sub.add_parser("report", help="one static HTML page for the processed campaign",
                       description="Write one static HTML page of the processed campaign "
                                   "(summaries, QC counts, figures).", parents=common)
    r.add_argument("--out", default=None,
                   help="file name in the processed folder (default: report.html there)")
    pipeline_opts(r)
    r.set_defaults(func=cmd_report)

    b = sub.add_parser("bench", help="accuracy-versus-run-time benchmarks", parents=common,
                       description="Run the accuracy-versus-run-time benchmarks of one area.")
    b.add_argument("area", help="one of: " + ", ".join(bench_areas()))
    b.add_argument("--quick", action="store_true", help="shorter runs, fewer cases")
    b.set_defaults(func=cmd_bench)
    return p


def os_problem(e: OSError) -> str:
    """Return one line for an operating-system error: the file, what failed, what to do.

    Parameters
    ----------
    e : OSError
        The error.

    Returns
    -------
    str
        The message, with a hint for a full disk, an exhausted quota, a read-only file system
        or a missing permission.

    Examples
    --------
    >>> import errno
    >>> os_problem(OSError(errno.EROFS, "Read-only file system", "out.nc"))[:36]
    'out.nc: Read-only file system (the f'
    """
    import errno

    where = f"{e.filename}: " if e.filename else ""
    what = e.strerror or str(e)
    hint = {errno.ENOSPC: "free some space on that disk, or point `processed` of the "
                          "pipeline file at another one; an interrupted build leaves no partial "
                          "output and resumes where it stopped",
            errno.EDQUOT: "the disk quota is exhausted: free some space",
            errno.EROFS: "the folder is on a read-only file system: point `processed` of the "
                         "pipeline file at a writable folder",
            errno.EACCES: "no permission to write there: point `processed` of the pipeline "
                          "file at a writable folder",
            errno.EPERM: "no permission to write there: point `processed` of the pipeline "
                         "file at a writable folder"}.get(e.errno)
    return f"{where}{what}" + (f" ({hint})" if hint else "")


def main(argv: list[str] | None = None) -> int:
    """Run the ``flumekit`` command line.

    Errors of the input or the machine are printed on one line (``--debug``: with the
    traceback); Ctrl-C ends with status 130.

    Parameters
    ----------
    argv : list of str, optional
        The arguments (default: ``sys.argv[1:]``).

    Returns
    -------
    int
        Exit status: 0 on success, 1 on an error, 130 when interrupted.
    """
    import os

    # one BLAS thread per process unless the user says otherwise: the analyses' linear algebra
    # is small (a few unknowns per bin, per draw), where threads cost more than they save,
    # and `make -j` already runs rules in parallel processes
    for var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
        os.environ.setdefault(var, "1")
    args = parser().parse_args(argv)
    try:
        return args.func(args)
    except FlumekitError as e:
        if args.debug:
            raise
        print(f"flumekit: error: {e}", file=sys.stderr)
        return 1
    except OSError as e:  # the machine's, not the program's: a full disk, a read-only folder
        if args.debug:
            raise
        print(f"flumekit: error: {os_problem(e)}", file=sys.stderr)
        return 1
    except KeyboardInterrupt:
        from flumekit.pipeline.executors import INTERRUPTED

        print(INTERRUPTED, file=sys.stderr)
        return 130


if __name__ == "__main__":
    sys.exit(main())
