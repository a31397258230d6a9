"""The dependency graph of a pipeline, cached between makes so that planning does not rebuild it.

Building the rules of a paper-size campaign (parsing 141 run files, declaring 1 200 rules of
nine stages, making 5 000 paths) costs several times a bare ``flumekit --version``; a no-op
``make`` would spend most of its time there. The graph is kept in the processed folder with
its paths as strings (unpickling 5 000 ``Path`` objects costs as much as building them), under
a key that covers everything its rules are made of:

- the content of every file that defines them, given by the caller (pipeline's campaign files:
  ``campaign.toml``, each ``run.toml``, the virtual-flume marker) with absent files marked
  absent, so that a changed, added or removed file changes the key;
- the caller's other inputs (the parsed pipeline: folders, stage parameters, synthesis);
- the code: flumekit's version, the size and modification time of every file of the package,
  and the Python version.

A cache whose key differs is not used; so a stale cache cannot be read, it is only rebuilt.

A make that ends with every requested target up to date also records so
(:func:`record_up_to_date`): the size and modification time of every file its targets read or
wrote, and of the build state. The next make with the same request and graph key finds the
same and has nothing to do (:func:`up_to_date`) without reading the graph or the build state
at all: this is the check the engine makes itself (a file's hash is trusted while its size and
modification time stay), made on one flat list instead of 1 000 rules.
"""

from __future__ import annotations

import hashlib
import json
import os
import sys
from collections.abc import Callable, Iterable
from pathlib import Path
from typing import TYPE_CHECKING

if TYPE_CHECKING:  # imported when used: the make that is up to date needs neither
    from flumekit.pipeline.engine import Graph
    from flumekit.pipeline.raw import Synthesis
    from flumekit.pipeline.rules import Rule

#: bumped when the layout of the cached rows changes
_FORMAT = 1


def code_signature() -> list:
    """flumekit's version and (relative path, size, mtime) of every file of the package."""
    from flumekit import __version__

    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))  # the package
    out: list = [__version__, sys.version]
    for dirpath, dirnames, filenames in os.walk(root):
        dirnames[:] = sorted(d for d in dirnames if d != "__pycache__")
        for f in sorted(filenames):
            st = os.stat(os.path.join(dirpath, f))
            out.append((os.path.relpath(os.path.join(dirpath, f), root), st.st_size,
                        st.st_mtime_ns))
    return out


def graph_key(files: Iterable[str | Path], extra: object) -> str:
    """The digest of ``files``' contents (None for an absent file), ``extra`` (JSON-able, other
    values by ``str``) and :func:`code_signature`."""
    h = hashlib.sha256()
    for f in files:
        try:
            with open(f, "rb") as fh:
                data = fh.read()
            h.update(b"%d:%s:%s\n" % (len(os.fspath(f)), os.fsencode(f),
                                      hashlib.sha256(data).hexdigest().encode()))
        except FileNotFoundError:
            h.update(b"%d:%s:absent\n" % (len(os.fspath(f)), os.fsencode(f)))
    h.update(json.dumps([_FORMAT, extra, code_signature()], sort_keys=True,
                        default=str).encode())
    return h.hexdigest()


def pipeline_key(pipe) -> tuple[str | None, Synthesis | None]:
    """The key of a pipeline's graph (:func:`graph_key`: every campaign file its rules are made
    of, the pipeline, the code) and what the virtual flume is to synthesise
    (:func:`flumekit.pipeline.raw.synthesis_plan`; None: the campaign is there). Raises on a
    raw folder that may not be used (nothing is written)."""
    from flumekit.pipeline.raw import campaign_files, synthesis_plan

    lazy = synthesis_plan(pipe.raw, pipe.synth, pipe.path)
    plan = None if lazy is None else [lazy.size, lazy.seed]
    try:
        key = graph_key(campaign_files(pipe.raw),
                        [str(pipe.raw), str(pipe.processed), pipe.stages, pipe.synth, plan,
                         pipe.scenes])
    except OSError:  # a run.toml that is a folder, an unreadable file: load_campaign says so
        key = None
    return key, lazy


def _plain(rule: Rule) -> Rule:
    """``rule`` with its paths as strings and its parameters' hash memoised (both travel with
    it through the cache; hashing every rule's parameters again would cost a no-op make as
    much as reading them)."""
    from dataclasses import replace

    rule = replace(rule, inputs={k: os.fspath(v) for k, v in rule.inputs.items()},
                   outputs={k: os.fspath(v) for k, v in rule.outputs.items()})
    rule.params_hash()
    rule.code_hash()
    return rule


def cached_graph(path: Path, key: str | None, build: Callable[[], list[Rule]]) -> Graph:
    """The graph cached in ``path`` under ``key`` (:func:`graph_key`), else that of
    ``build()``'s rules (then cached in ``path`` when its folder exists; ``key`` None: never
    cached).

    Either way the rules hold their paths as strings, so that a build behaves the same whether
    its graph came from the cache or not.
    """
    import pickle

    from flumekit.pipeline.engine import Graph

    if key is not None:
        try:
            with open(path, "rb") as fh:
                old, graph = pickle.load(fh)
            if old == key and isinstance(graph, Graph):
                return graph
        except (OSError, pickle.UnpicklingError, EOFError, ValueError, TypeError,
                AttributeError, ImportError, IndexError):
            pass  # no cache, or an unreadable one: build the rules
    graph = Graph([_plain(r) for r in build()])
    if key is not None and path.parent.is_dir():
        from flumekit.io.atomic import atomic_path

        try:
            data = pickle.dumps((key, graph), protocol=pickle.HIGHEST_PROTOCOL)
        except (pickle.PicklingError, TypeError, AttributeError):
            data = None  # a parameter that does not pickle: plan without a cache
        if data is not None:
            with atomic_path(path) as tmp:
                tmp.write_bytes(data)
    return graph


def request_key(*parts: object) -> str:
    """A digest of JSON-able ``parts`` (other values by ``str``): what a make was asked."""
    return hashlib.sha256(json.dumps(parts, sort_keys=True, default=str).encode()).hexdigest()


def _stat(path) -> list[int] | None:
    try:
        st = os.stat(path)
    except OSError:
        return None
    return [st.st_size, st.st_mtime_ns]


def up_to_date(path: Path, request: str | None, state_file: Path) -> list[str] | None:
    """The targets a make of ``request`` left up to date (:func:`record_up_to_date`), if since
    then no file they read or wrote and not the build state changed size or modification time;
    None otherwise (and for ``request`` None)."""
    if request is None:
        return None
    try:
        with open(path) as fh:
            record = json.load(fh)
        if record["request"] != request or _stat(state_file) != record["state"]:
            return None
        files = record["files"]
    except (OSError, ValueError, KeyError, TypeError):
        return None
    for p, seen in files.items():
        if _stat(p) != seen:
            return None
    return record["targets"]


def record_up_to_date(path: Path, request: str | None, state_file: Path, graph: Graph,
                      targets: list[str]) -> None:
    """Record that ``targets`` (and everything they need) are up to date after a make of
    ``request``: the size and modification time of every file they read or write, and of the
    build state (see :func:`up_to_date`)."""
    if request is None:
        return
    order = graph.closure(targets)
    files: dict[str, list[int] | None] = {}
    for t in order:
        rule = graph.rules[t]
        for p in [*rule.inputs.values(), *rule.outputs.values()]:
            key = os.path.abspath(p)
            if key not in files:
                files[key] = _stat(key)
    state = _stat(state_file)
    if state is None or None in files.values():
        return  # a file that vanished meanwhile: nothing to record
    from flumekit.io.atomic import atomic_path

    with atomic_path(path) as tmp:
        tmp.write_text(json.dumps({"request": request, "state": state, "targets": order,
                                   "files": files}))


def forget_up_to_date(path: Path) -> None:
    """Remove the record of :func:`record_up_to_date` (a make that builds may change anything)."""
    try:
        os.unlink(path)
    except FileNotFoundError:
        pass
