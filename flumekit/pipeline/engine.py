"""Plan and run the rules a set of targets needs (DESIGN.md §4).

A target is rebuilt when an output is missing, or when the content hash of an input, the rule's
parameters or its code version differ from those of its last successful build. Only the rules
the requested targets depend on are considered.
"""

from __future__ import annotations

import fnmatch
import sys
import time
from collections.abc import Callable, Iterable
from dataclasses import dataclass
from pathlib import Path

from flumekit.errors import FlumekitError, InputError
from flumekit.pipeline.executors import Executor
from flumekit.pipeline.rules import Rule, execute
from flumekit.pipeline.state import State


class Graph:
    """Rules indexed by target and by output path, with their dependencies."""

    def __init__(self, rules: Iterable[Rule]):
        self.rules: dict[str, Rule] = {}
        self.producer: dict[Path, str] = {}
        for r in rules:
            if r.target in self.rules:
                raise ValueError(f"two rules build target '{r.target}'")
            self.rules[r.target] = r
            for p in r.outputs.values():
                self.producer[Path(p).resolve()] = r.target

    def deps(self, target: str) -> list[str]:
        r = self.rules[target]
        out = []
        for p in r.inputs.values():
            t = self.producer.get(Path(p).resolve())
            if t is not None:
                out.append(t)
        return out

    def match(self, patterns: Iterable[str]) -> list[str]:
        found: list[str] = []
        for pat in patterns:
            hits = [t for t in self.rules if fnmatch.fnmatchcase(t, pat)]
            if not hits:
                raise FlumekitError(f"no target matches '{pat}' (see `flumekit list`)")
            found += [t for t in hits if t not in found]
        return found

    def match_any(self, pattern: str) -> bool:
        """True if some target matches ``pattern``."""
        return any(fnmatch.fnmatchcase(t, pattern) for t in self.rules)

    def closure(self, targets: Iterable[str]) -> list[str]:
        """The targets and everything they depend on, in dependency (topological) order."""
        order: list[str] = []
        seen: set[str] = set()
        visiting: set[str] = set()

        def visit(t: str) -> None:
            if t in seen:
                return
            if t in visiting:
                raise FlumekitError(f"dependency cycle through '{t}'")
            visiting.add(t)
            for d in self.deps(t):
                visit(d)
            visiting.discard(t)
            seen.add(t)
            order.append(t)

        for t in targets:
            visit(t)
        return order


def signature(rule: Rule, state: State) -> dict:
    inputs = {}
    for name, p in sorted(rule.inputs.items()):
        p = Path(p)
        if not p.exists():
            raise InputError(p, f"input '{name}' of target '{rule.target}' is missing")
        inputs[name] = state.hash(p)
    return {"version": rule.version, "params": rule.params_hash(), "inputs": inputs}


def why(rule: Rule, state: State, force: bool, rebuilt: set[str], graph: Graph) -> str | None:
    """Reason to rebuild ``rule`` (None when it is up to date)."""
    for name, p in rule.inputs.items():
        if not Path(p).exists() and Path(p).resolve() not in graph.producer:
            raise InputError(p, f"input '{name}' of target '{rule.target}' is missing")
    if force:
        return "forced"
    missing = [n for n, p in rule.outputs.items() if not Path(p).exists()]
    if missing:
        return f"output {missing[0]} missing"
    upstream = [d for d in graph.deps(rule.target) if d in rebuilt]
    if upstream:
        return f"input from {upstream[0]} is rebuilt"
    old = state.targets.get(rule.target)
    if old is None:
        return "never built"
    new = signature(rule, state)
    if old.get("version") != new["version"]:
        return f"rule version {old.get('version')} -> {new['version']}"
    if old.get("params") != new["params"]:
        return "parameters changed"
    for name, h in new["inputs"].items():
        if old.get("inputs", {}).get(name) != h:
            return f"input {name} changed"
    return None


@dataclass
class Report:
    ran: list[tuple[str, str, float]]  # target, reason, seconds
    skipped: list[str]


def plan(graph: Graph, targets: list[str], state: State,
         force: bool = False) -> list[tuple[str, str]]:
    """What would run and why, for a dry run. Assumes every rebuilt input changes."""
    rebuilt: set[str] = set()
    out = []
    for t in graph.closure(targets):
        reason = why(graph.rules[t], state, force, rebuilt, graph)
        if reason:
            rebuilt.add(t)
            out.append((t, reason))
    return out


def make(graph: Graph, targets: list[str], state: State, executor: Executor, force: bool = False,
         log: Callable[[str], None] = lambda s: print(s, file=sys.stderr)) -> Report:
    """Build ``targets``; rules run on ``executor`` as soon as their inputs are up to date.

    A rule is judged just before it would run, with the real hashes of freshly built inputs, so
    an upstream rebuild that reproduces identical content rebuilds nothing downstream.
    """
    order = graph.closure(targets)
    pending = {t: set(graph.deps(t)) for t in order}
    done: set[str] = set()
    changed: set[str] = set()  # targets rebuilt in this make whose outputs changed
    running: dict = {}
    report = Report([], [])
    n_total = len(order)
    failure: BaseException | None = None
    t_start = time.perf_counter()

    def ready() -> list[str]:
        return [t for t in order if t not in done and t not in running.values()
                and pending[t] <= done]

    while len(done) < n_total:
        if failure is None:
            for t in ready():
                rule = graph.rules[t]
                reason = why(rule, state, force, changed, graph)
                if reason is None:
                    done.add(t)
                    report.skipped.append(t)
                    continue
                log(f"[{len(done) + len(running) + 1}/{n_total}] {t}: {reason}")
                running[executor.submit(execute, rule)] = t
        if not running:
            if failure is not None or len(done) == n_total:
                break
            continue
        for fut in executor.wait_any(list(running)):
            t = running.pop(fut)
            rule = graph.rules[t]
            try:
                seconds = fut.result()
            except BaseException as e:  # broad on purpose: reported with target and run
                state.targets.pop(t, None)
                if failure is None:
                    failure = _wrap(rule, e)
                done.add(t)
                continue
            old_out = state.targets.get(t, {}).get("outputs")
            sig = signature(rule, state)
            sig["outputs"] = {n: state.hash(Path(p)) for n, p in rule.outputs.items()}
            state.targets[t] = sig
            state.save()
            if sig["outputs"] != old_out or force:
                changed.add(t)
            done.add(t)
            report.ran.append((t, "", seconds))
            log(f"    {t} done in {seconds:.2f} s")
    state.save()
    if failure is not None:
        raise failure
    elapsed = time.perf_counter() - t_start
    if report.ran:
        log(f"built {len(report.ran)} target(s), {len(report.skipped)} up to date, "
            f"{elapsed:.2f} s")
    else:
        log(f"nothing to do: all {len(report.skipped)} target(s) up to date ({elapsed:.2f} s)")
    return report


def _wrap(rule: Rule, e: BaseException) -> BaseException:
    where = f"rule '{rule.target}'" + (f" (run {rule.run})" if rule.run else "")
    if isinstance(e, FlumekitError):
        err = type(e).__new__(type(e))
        err.__dict__.update(e.__dict__)
        err.args = (f"{where}: {e}",)
        return err
    err = FlumekitError(f"{where} failed: {type(e).__name__}: {e}")
    err.__cause__ = e
    return err
