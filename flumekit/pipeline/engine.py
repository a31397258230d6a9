"""Plan and run the rules a set of targets needs.

A target is rebuilt when an output is missing, or when the content hash of an input, the rule's
parameters or its code version differ from those of its last successful build. Only the rules
the requested targets depend on are considered.

A target whose rebuild fails loses its outputs, and so does everything built from them
(:meth:`Graph.downstream`): no reader can pick up a result made from data that no longer
exists. The engine keeps going past a failure only when asked (``keep_going``), and then builds
everything that does not depend on a failed target.
"""

from __future__ import annotations

import errno
import fnmatch
import os
import re
import sys
import time
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field
from pathlib import Path

from flumekit.docstrings import filler
from flumekit.errors import FlumekitError, InputError
from flumekit.pipeline.executors import Executor
from flumekit.pipeline.rules import Rule, execute
from flumekit.pipeline.state import State

#: docstring text that several functions of this module share
_doc = filler(
    force=("force : bool, default False\n"
           "    Rebuild every target needed."),
    force_targets=("force_targets : iterable of str, optional\n"
                   "    Targets to rebuild regardless of the state."),
    graph=("graph : Graph\n"
           "    The pipeline's rules."),
    raises_missing_input=("Raises\n"
                          "------\n"
                          "flumekit.errors.InputError\n"
                          "    When an input is missing and no rule makes it."),
    state=("state : State\n"
           "    The build state."),
    targets=("targets : list of str\n"
             "    Requested targets."))


def _key(p) -> str:
    # no Path objects and no file-system call: the graph and the no-op make touch every path
    s = os.fspath(p)
    return s if s.startswith("/") else os.path.abspath(s)


class Graph:
    """Rules indexed by target and by output path, with their dependencies (computed once).

    A rule depends on the rule that writes one of its inputs.

    Parameters
    ----------
    rules : iterable of Rule
        The pipeline's rules, one per target.

    Raises
    ------
    ValueError
        When two rules have the same ``target``.

    Examples
    --------
    >>> from flumekit.pipeline.rules import Rule
    >>> g = Graph([Rule("a", "m:f", {}, {"o": "a.nc"}), Rule("b", "m:f", {"i": "a.nc"}, {})])
    >>> g.closure(["b"]), g.downstream("a")
    (['a', 'b'], ['b'])
    """

    def __init__(self, rules: Iterable[Rule]):
        self.rules: dict[str, Rule] = {}
        self.producer: dict[str, str] = {}
        for r in rules:
            if r.target in self.rules:
                raise ValueError(f"two rules build target '{r.target}'")
            self.rules[r.target] = r
            for p in r.outputs.values():
                self.producer[_key(p)] = r.target
        self._deps: dict[str, list[str]] = {}
        self._users: dict[str, list[str]] = {t: [] for t in self.rules}
        for t, r in self.rules.items():
            deps = []
            for p in r.inputs.values():
                d = self.producer.get(_key(p))
                if d is not None and d not in deps:
                    deps.append(d)
            self._deps[t] = deps
            for d in deps:
                self._users[d].append(t)

    def deps(self, target: str) -> list[str]:
        """Return the targets whose outputs ``target`` reads."""
        return self._deps[target]

    def produced(self, path) -> bool:
        """Return whether some rule of the graph writes ``path``."""
        return _key(path) in self.producer

    def downstream(self, target: str) -> list[str]:
        """Return every target built, directly or not, from a target's outputs.

        Parameters
        ----------
        target : str
            The target.

        Returns
        -------
        list of str
            The targets downstream of it (not ``target`` itself).
        """
        out: list[str] = []
        stack = list(self._users[target])
        while stack:
            t = stack.pop()
            if t not in out:
                out.append(t)
                stack += self._users[t]
        return out

    def match(self, patterns: Iterable[str]) -> list[str]:
        """Return the targets named by target names or glob patterns, in order, once each.

        Parameters
        ----------
        patterns : iterable of str
            Target names or ``fnmatch`` patterns (``*``, ``?``, ``[...]``).

        Returns
        -------
        list of str
            The matching targets.

        Raises
        ------
        flumekit.errors.FlumekitError
            When a pattern matches no target.
        """
        found: list[str] = []
        for pat in patterns:
            hits = (fnmatch.filter(self.rules, pat) if any(c in pat for c in "*?[")
                    else [pat] if pat in self.rules else [])
            if not hits:
                raise FlumekitError(f"no target matches '{pat}' (see `flumekit list`)")
            found += [t for t in hits if t not in found]
        return found

    def match_any(self, pattern: str) -> bool:
        """Return whether some target matches ``pattern`` (a name or a glob pattern)."""
        if not any(c in pattern for c in "*?["):
            return pattern in self.rules
        return any(map(re.compile(fnmatch.translate(pattern)).match, self.rules))

    def closure(self, targets: Iterable[str]) -> list[str]:
        """Return the targets and everything they depend on, in dependency order.

        Parameters
        ----------
        targets : iterable of str
            Target names.

        Returns
        -------
        list of str
            The targets and their dependencies, topologically sorted (a dependency before
            its users).

        Raises
        ------
        flumekit.errors.FlumekitError
            On a dependency cycle.
        """
        order: list[str] = []
        seen: set[str] = set()
        visiting: set[str] = set()

        def visit(t: str) -> None:
            if t in seen:
                return
            if t in visiting:
                raise FlumekitError(f"dependency cycle through '{t}'")
            visiting.add(t)
            for d in self._deps[t]:
                visit(d)
            visiting.discard(t)
            seen.add(t)
            order.append(t)

        for t in targets:
            visit(t)
        return order


def signature(rule: Rule, state: State) -> dict:
    """Return what a build of ``rule`` depends on: version, code, parameters, input hashes.

    Parameters
    ----------
    rule : Rule
        The rule.
    state : State
        The build state, which knows the content hash of each input.

    Returns
    -------
    dict
        ``{"version", "code", "params", "inputs"}``; compared with the stored signature of
        the last successful build to decide a rebuild.

    Raises
    ------
    flumekit.errors.InputError
        When an input file is missing.
    """
    inputs = {}
    for name, p in sorted(rule.inputs.items()):
        try:
            inputs[name] = state.identity(p)
        except FileNotFoundError:
            raise InputError(p, f"input '{name}' of target '{rule.target}' is missing") from None
    return {"version": rule.version, "code": rule.code_hash(), "params": rule.params_hash(),
            "inputs": inputs}


def provenance(rule: Rule, state: State, root: Path | None) -> dict:
    """Return what a rule's datasets record about their making.

    Parameters
    ----------
    rule : Rule
        The rule about to run.
    state : State
        The build state (content hashes of the inputs).
    root : pathlib.Path or None
        The pipeline file's folder, against which paths are made relative (None: file names).

    Returns
    -------
    dict
        ``"inputs"``: every input with its relative path and content hash; ``"paths"``:
        absolute path -> relative path, longest first, so that no machine path is recorded.
    """
    def rel(p) -> str:
        return os.path.relpath(p, root) if root is not None else Path(p).name

    paths = {os.path.abspath(p): rel(p) for p in [*rule.inputs.values(), *rule.outputs.values()]}
    inputs = {name: {"file": rel(p), "sha256": state.identity(Path(p))}
              for name, p in sorted(rule.inputs.items())}
    # longest first, so that a path is never replaced by the relative form of its prefix
    return {"inputs": inputs, "paths": dict(sorted(paths.items(), key=lambda kv: -len(kv[0])))}


@_doc
def why(rule: Rule, state: State, force: bool, rebuilt: set[str], graph: Graph) -> str | None:
    """Return the reason to rebuild a rule, or None when it is up to date.

    Parameters
    ----------
    rule : Rule
        The rule to judge.
    state : State
        The build state (signatures of the last successful builds, file hashes).
    force : bool
        Rebuild regardless of the state (never for a rule that creates raw data).
    rebuilt : set of str
        Targets rebuilt (with changed outputs) in this make.
    graph : Graph
        The graph the rule belongs to.

    Returns
    -------
    str or None
        A short reason (``"never built"``, ``"parameters changed"``, ...); None when the rule
        is up to date.

    %(raises_missing_input)s

    Examples
    --------
    The reasons of a run's wave analysis as its files appear, then within a make that has
    rebuilt the elevation it reads (no action runs here: the names are made up):

    >>> import tempfile
    >>> from flumekit.pipeline.rules import Rule
    >>> from flumekit.pipeline.state import State
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     lab = Path(folder)
    ...     eta = Rule("eta/r1", "lab:eta", {"raw": lab / "probes.csv"}, {"out": lab / "eta.nc"})
    ...     waves = Rule("waves/r1", "lab:waves", {"eta": lab / "eta.nc"}, {"out": lab / "w.nc"})
    ...     graph, state = Graph([eta, waves]), State(lab / "state.json")
    ...     reasons = []
    ...     for name in ("eta.nc", "w.nc"):
    ...         _ = (lab / name).write_text("0.0")
    ...         reasons.append(why(waves, state, False, set(), graph))
    ...     reasons += [why(waves, state, False, {"eta/r1"}, graph),
    ...                 why(waves, state, True, set(), graph)]
    >>> reasons
    ['output out missing', 'never built', 'input from eta/r1 is rebuilt', 'forced']

    An input that is missing and that no rule makes is an error naming it:

    >>> lost = Rule("eta/r2", "lab:eta", {"raw": "no/such/r2.csv"}, {"out": "no/such/eta.nc"})
    >>> why(lost, State(Path("no/such/state.json")), False, set(), Graph([lost]))
    Traceback (most recent call last):
    ...
    flumekit.errors.InputError: no/such/r2.csv: input 'raw' of target 'eta/r2' is missing
    """
    exists = state.exists
    missing = [n for n, p in rule.outputs.items() if not exists(p)]
    if rule.source:
        # a rule that creates raw data (the virtual flume) runs only where nothing exists yet:
        # it is never forced and never re-run over files that are there
        return f"output {missing[0]} missing" if missing else None

    def check_inputs() -> None:
        for name, p in rule.inputs.items():
            if not exists(p) and not graph.produced(p):
                raise InputError(p, f"input '{name}' of target '{rule.target}' is missing")

    if force:
        check_inputs()
        return "forced"
    if missing:
        check_inputs()
        return f"output {missing[0]} missing"
    upstream = [d for d in graph.deps(rule.target) if d in rebuilt]
    if upstream:
        return f"input from {upstream[0]} is rebuilt"
    old = state.targets.get(rule.target)
    if old is None:
        check_inputs()
        return "never built"
    new = signature(rule, state)  # an input missing here is an error naming it
    if old.get("version") != new["version"]:
        return f"rule version {old.get('version')} -> {new['version']}"
    if old.get("code") != new["code"]:
        return f"code of {rule.action.partition(':')[0]} (or a module it imports) changed"
    if old.get("params") != new["params"]:
        return "parameters changed"
    for name, h in new["inputs"].items():
        if old.get("inputs", {}).get(name) != h:
            return f"input {name} changed"
    return None


@dataclass
class Failure:
    """A target whose build failed: the target, its run, the file at fault and the problem."""

    target: str
    run: str | None
    file: str | None
    problem: str


@dataclass
class Report:
    """What a make did: targets run (with reason and duration [s]), skipped, failed, blocked."""

    ran: list[tuple[str, str, float]]  # target, reason, seconds
    skipped: list[str]  # up to date
    failed: list[Failure] = field(default_factory=list)
    blocked: list[str] = field(default_factory=list)  # not built: an input's rebuild failed
    removed: list[str] = field(default_factory=list)  # outputs invalidated by a failure
    seconds: float = 0.0


class Events:
    """What a build tells its user; the command line gives a progress bar or plain lines."""

    def __init__(self, log: Callable[[str], None] = lambda s: print(s, file=sys.stderr), *,
                 finished: bool = True):
        """``log`` prints a line; ``finished``: also a line when a target is done."""
        self.log = log
        self.say_finished = finished

    def start(self, n_total: int) -> None:
        """Announce a build of ``n_total`` targets."""

    def started(self, i: int, n: int, target: str, reason: str) -> None:
        """Announce target ``i`` of ``n`` started, with the reason it runs."""
        self.log(f"[{i}/{n}] {target}: {reason}")

    def finished(self, target: str, seconds: float) -> None:
        """Announce a target done after ``seconds`` [s]."""
        if self.say_finished:
            self.log(f"    {target} done in {seconds:.2f} s")

    def skipped(self, target: str) -> None:
        """Announce a target up to date."""

    def failed(self, failure: Failure) -> None:
        """Announce a failure."""
        self.log(f"    {failure.target} FAILED: {failure.problem}")

    def close(self) -> None:
        """End the build's output."""


@_doc
def plan(graph: Graph, targets: list[str], state: State, force: bool = False,
         force_targets: Iterable[str] = ()) -> list[tuple[str, str]]:
    r"""Return what a make would run and why (a dry run).

    Assumes every rebuilt input changes, so everything downstream of a rebuild is listed.

    Parameters
    ----------
    %(graph)s
    %(targets)s
    %(state)s
    %(force)s
    %(force_targets)s

    Returns
    -------
    list of tuple of (str, str)
        ``(target, reason)`` in the order they would run.

    %(raises_missing_input)s

    Examples
    --------
    A run's elevation, then its wave analysis from it, never built: both would run, the
    elevation first. Planning imports no action (the names here are made up) and writes
    nothing.

    >>> import tempfile
    >>> from flumekit.pipeline.rules import Rule
    >>> from flumekit.pipeline.state import State
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     lab = Path(folder)
    ...     _ = (lab / "probes.csv").write_text("time,WP1\n0.0,2.51\n")
    ...     graph = Graph([
    ...         Rule("waves/r1", "lab:waves", {"eta": lab / "eta.nc"}, {"out": lab / "w.nc"}),
    ...         Rule("eta/r1", "lab:eta", {"raw": lab / "probes.csv"}, {"out": lab / "eta.nc"})])
    ...     steps = plan(graph, ["waves/r1"], State(lab / "state.json"))
    ...     only_eta = plan(graph, ["eta/r1"], State(lab / "state.json"))
    ...     untouched = sorted(p.name for p in lab.iterdir())
    >>> steps
    [('eta/r1', 'output out missing'), ('waves/r1', 'output out missing')]
    >>> only_eta, untouched
    ([('eta/r1', 'output out missing')], ['probes.csv'])
    """
    rebuilt: set[str] = set()
    forced = set(force_targets)
    out = []
    with state.scan():
        for t in graph.closure(targets):
            reason = why(graph.rules[t], state, force or t in forced, rebuilt, graph)
            if reason:
                rebuilt.add(t)
                out.append((t, reason))
    return out


@_doc
def remove_outputs(graph: Graph, state: State, targets: Iterable[str], *,
                   within: Path | None = None, dry_run: bool = False) -> dict[str, list[Path]]:
    """Remove the outputs of ``targets`` and forget their build signatures.

    Rules that create raw data (``source``) are never touched.

    Parameters
    ----------
    %(graph)s
    state : State
        The build state, whose signatures of ``targets`` are forgotten.
    targets : iterable of str
        The targets to clean.
    within : pathlib.Path, optional
        Only files under this folder are removed (symbolic links resolved).
    dry_run : bool, default False
        Remove and forget nothing; the result says what would be removed.

    Returns
    -------
    dict
        Target -> the files removed (only targets that had some).
    """
    inside = None if within is None else Path(within).resolve()
    removed: dict[str, list[Path]] = {}
    for t in targets:
        rule = graph.rules[t]
        if rule.source:
            continue
        if not dry_run:
            state.targets.pop(t, None)
        for p in map(Path, rule.outputs.values()):
            if not p.is_file() or (inside is not None and not p.resolve().is_relative_to(inside)):
                continue
            if not dry_run:
                p.unlink()
            removed.setdefault(t, []).append(p)
    return removed


@_doc
def invalidate(graph: Graph, state: State, target: str) -> list[str]:
    """Remove the outputs of a target and of everything downstream of it.

    Their build signatures are forgotten too (:func:`remove_outputs`).

    Parameters
    ----------
    %(graph)s
    %(state)s
    target : str
        The target invalidated.

    Returns
    -------
    list of str
        The targets whose outputs were removed.
    """
    return list(remove_outputs(graph, state, [target, *graph.downstream(target)]))


#: time between two writes of the state while a build runs [s]: a build killed outright
#: (kill -9, a power cut) builds again at most the targets of that last second, and a build of
#: a thousand targets does not write its whole state a thousand times (an interrupt, a failure
#: and the end of the build write it at once)
SAVE_EVERY = 1.0


@_doc
def make(graph: Graph, targets: list[str], state: State, executor: Executor, force: bool = False,
         log: Callable[[str], None] | None = None, *, force_targets: Iterable[str] = (),
         keep_going: bool = False, events: Events | None = None,
         root: Path | None = None, interrupted: Callable[[], bool] = lambda: False) -> Report:
    r"""Build ``targets``; rules run on ``executor`` as soon as their inputs are up to date.

    A rule is judged just before it would run, with the real hashes of freshly built inputs, so
    an upstream rebuild that reproduces identical content rebuilds nothing downstream.
    ``force`` rebuilds every target needed; ``force_targets`` only those named (what they feed
    is rebuilt only if their outputs change). With ``keep_going`` a failure does not stop the
    build: the report lists the failures and the targets they blocked; otherwise the first
    failure is raised once the running rules have finished. An interrupt (Ctrl-C) is not a
    failure: it propagates as soon as the state of finished rules is saved.

    Parameters
    ----------
    %(graph)s
    %(targets)s
    state : State
        The build state, saved at most every :data:`SAVE_EVERY` seconds while rules finish,
        after a failure, and at the end (an interrupt included).
    executor : Executor
        Where rules run (:func:`flumekit.pipeline.executor_for`).
    %(force)s
    log : callable, optional
        Prints a line of progress (default: standard error); ignored when ``events`` is given.
    %(force_targets)s
    keep_going : bool, default False
        Build everything that does not depend on a failure, then report.
    events : Events, optional
        Receives the progress of the build.
    root : pathlib.Path, optional
        The pipeline file's folder; recorded paths are relative to it (:func:`provenance`).
    interrupted : callable, optional
        Returns True when the user asked to stop (a Ctrl-C a library swallowed).

    Returns
    -------
    Report
        What ran, was skipped, failed, was blocked or removed, and the build time [s].

    Raises
    ------
    flumekit.errors.FlumekitError
        The first failure, naming its rule and run, unless ``keep_going``.
    KeyboardInterrupt
        When interrupted, after the state of finished rules is saved.

    Examples
    --------
    ``flumekit make calibration`` on a small virtual campaign, in a temporary folder: the
    first make synthesises the campaign-wide raw files and fits the probes' calibration, the
    second finds nothing to do.

    >>> import tempfile
    >>> from flumekit.pipeline import load_pipeline
    >>> from flumekit.pipeline.executors import SerialExecutor
    >>> from flumekit.pipeline.state import State
    >>> from flumekit.stages.plan import pipeline_graph
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     _ = (Path(folder) / "tank.toml").write_text(
    ...         '[pipeline]\nname = "tank"\nraw = "raw"\nprocessed = "out"\n'
    ...         '[synth]\nsize = "small"\n')
    ...     pipe = load_pipeline(Path(folder) / "tank.toml")
    ...     graph = pipeline_graph(pipe)
    ...     first = make(graph, ["calibration"], State(pipe.state_file), SerialExecutor(),
    ...                  log=lambda line: None)
    ...     again = make(graph, ["calibration"], State(pipe.state_file), SerialExecutor())
    ...     written = (pipe.processed / "calibration.nc").is_file()
    >>> for target, reason, seconds in first.ran:
    ...     print(f"{target}: {reason}")
    synth/campaign: output calibration/probes.csv missing
    calibration: output dataset missing
    >>> written, again.ran, again.skipped
    (True, [], ['synth/campaign', 'calibration'])
    """
    events = events or Events(log or (lambda s: print(s, file=sys.stderr)))
    forced = set(force_targets)
    order = graph.closure(targets)
    pending = {t: set(graph.deps(t)) for t in order}
    done: set[str] = set()
    bad: set[str] = set()  # failed or blocked
    changed: set[str] = set()  # targets rebuilt in this make whose outputs changed
    running: dict = {}  # future -> (target, reason)
    busy: set[str] = set()  # targets running
    report = Report([], [])
    n_total = len(order)
    first_error: BaseException | None = None
    t_start = saved = time.perf_counter()
    events.start(n_total)

    def fail(t: str, e: BaseException) -> None:
        nonlocal first_error
        rule = graph.rules[t]
        full = _full_disk(rule)
        if full and not isinstance(e, FlumekitError):
            # libraries report a full disk in their own words ("NetCDF: HDF error")
            e = FlumekitError(f"{full} ({_short(e)})")
        f = Failure(t, rule.run, str(getattr(e, "path", "") or "") or None, _problem(e))
        report.failed.append(f)
        events.failed(f)
        report.removed += invalidate(graph, state, t)
        state.save()
        if first_error is None:
            first_error = _wrap(rule, e)
        bad.add(t)
        done.add(t)
        for u in graph.downstream(t):
            if u in pending and u not in done:
                bad.add(u)
                done.add(u)
                report.blocked.append(u)

    try:
        while len(done) < n_total:
            if interrupted():  # a Ctrl-C that a library swallowed still stops the build
                raise KeyboardInterrupt
            if first_error is None or keep_going:
                with state.scan():  # each file stat-ed once while judging the targets
                    for t in order:
                        if t in done or t in busy or not pending[t] <= done:
                            continue
                        rule = graph.rules[t]
                        try:
                            reason = why(rule, state, force or t in forced, changed, graph)
                        except FlumekitError as e:
                            fail(t, e)
                            continue
                        if reason is None:
                            done.add(t)
                            report.skipped.append(t)
                            events.skipped(t)
                            continue
                        events.started(len(done) + len(running) + 1, n_total, t, reason)
                        try:
                            prov = provenance(rule, state, root)
                        except FlumekitError as e:
                            fail(t, e)
                            continue
                        running[executor.submit(execute, rule, prov)] = (t, reason)
                        busy.add(t)
                        if first_error is not None and not keep_going:
                            break
            if not running:
                break
            for fut in executor.wait_any(list(running)):
                t, reason = running.pop(fut)
                busy.discard(t)
                rule = graph.rules[t]
                try:
                    seconds, written = fut.result()
                except (KeyboardInterrupt, SystemExit):
                    raise
                except BaseException as e:  # broad on purpose: reported with target and run
                    fail(t, e)
                    continue
                old_out = state.targets.get(t, {}).get("outputs")
                outputs = {os.path.abspath(p) for p in rule.outputs.values()}
                for p, digest in written.items():
                    if os.path.abspath(p) in outputs:
                        state.written(Path(p), digest)
                sig = signature(rule, state)
                sig["outputs"] = {n: state.identity(Path(p)) for n, p in rule.outputs.items()}
                # the time of a build lives here, never in the products
                sig["built"] = time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime())
                sig["seconds"] = round(seconds, 3)
                state.targets[t] = sig
                if time.perf_counter() - saved >= SAVE_EVERY:
                    state.save()
                    saved = time.perf_counter()
                if sig["outputs"] != old_out or force:
                    changed.add(t)
                done.add(t)
                report.ran.append((t, reason, seconds))
                events.finished(t, seconds)
    finally:
        if state.dirty or report.ran or report.failed:  # a no-op make writes nothing
            state.save()
        events.close()
    report.seconds = time.perf_counter() - t_start
    if first_error is not None and not keep_going:
        raise first_error
    return report


#: longest message of an unexpected exception shown to the user (an array in a numpy message
#: runs to thousands of characters)
MESSAGE_LENGTH = 200


def _short(e: BaseException) -> str:
    """Return ``Type: message`` of an unexpected exception on one line.

    The message is cut at :data:`MESSAGE_LENGTH` characters.
    """
    if isinstance(e, OSError) and e.strerror:
        text = e.strerror + (f": {e.filename}" if e.filename else "")
    else:
        text = " ".join(str(e).split())
    if len(text) > MESSAGE_LENGTH:
        text = text[:MESSAGE_LENGTH].rstrip() + " ..."
    return f"{type(e).__name__}: {text}"


def _problem(e: BaseException) -> str:
    if isinstance(e, InputError):  # the file is reported on its own
        return e.problem + (f" (line {e.line})" if e.line else "") + (
            f" (field '{e.field}')" if e.field else "")
    if isinstance(e, FlumekitError):
        return str(e)
    return _short(e)


#: free space below which a failed write is put down to a full disk [bytes]
FULL_DISK = 1 << 20


def _full_disk(rule: Rule) -> str | None:
    """Return what to say when the disk of ``rule``'s outputs is full, else None.

    Full: less than :data:`FULL_DISK` free.
    """
    for p in rule.outputs.values():
        folder = Path(p).parent
        while not folder.exists() and folder != folder.parent:
            folder = folder.parent
        try:
            st = os.statvfs(folder)
        except OSError:
            continue
        free = st.f_bavail * st.f_frsize
        if free < FULL_DISK:
            # the system's own words too, as an OSError of a full disk would say
            return (f"no space left on the disk of {folder} ({os.strerror(errno.ENOSPC)}, "
                    f"{free // 1024} kB free): free some space or point `processed` of the "
                    "pipeline file at another disk")
    return None


def _inputs(rule: Rule, most: int = 3) -> str:
    """Return the input files of ``rule`` by name, the first ``most`` of them."""
    names = [f"{k} = {Path(p).name}" for k, p in rule.inputs.items()]
    more = f" and {len(names) - most} more" if len(names) > most else ""
    return ", ".join(names[:most]) + more


def _wrap(rule: Rule, e: BaseException) -> BaseException:
    where = f"rule '{rule.target}'" + (f" (run {rule.run})" if rule.run else "")
    if isinstance(e, FlumekitError):
        err = type(e).__new__(type(e))
        err.__dict__.update(e.__dict__)
        err.args = (f"{where}: {e}",)
        return err
    # an error the rule's code did not expect: say what it computed from, on one line
    err = FlumekitError(f"{where} failed on its inputs ({_inputs(rule) or 'none'}) and "
                        f"parameters: {_short(e)}")
    err.__cause__ = e
    return err
