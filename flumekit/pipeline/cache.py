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
    """Return flumekit's version and the size and mtime of every file of the package.

    Returns
    -------
    list
        ``[version, python_version, (relative_path, size [byte], mtime [ns]), ...]``, files
        in sorted walk order.
    """
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
    """Return the digest of some files' contents, extra inputs and the code.

    Parameters
    ----------
    files : iterable of str or path-like
        Files the graph's rules are made of; an absent file is hashed as absent, so that
        adding or removing it changes the key.
    extra : object
        Other inputs, JSON-able (other values hashed by ``str``).

    Returns
    -------
    str
        SHA-256 hex digest over the files, ``extra`` and :func:`code_signature`.
    """
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
    """Return the key of a pipeline's graph and what the virtual flume is to synthesise.

    Parameters
    ----------
    pipe : flumekit.pipeline.Pipeline
        The parsed pipeline.

    Returns
    -------
    key : str or None
        :func:`graph_key` over every campaign file the rules are made of, the pipeline and
        the code; None when a campaign file cannot be read (the campaign loader reports it).
    synthesis : Synthesis or None
        :func:`flumekit.pipeline.raw.synthesis_plan`; None when the campaign is there.

    Raises
    ------
    flumekit.errors.InputError
        For a raw folder that may not be used (nothing is written).
    """
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
    """Return ``rule`` with its paths as strings and its hashes memoised.

    Both travel with the rule through the cache; hashing every rule's parameters again would
    cost a no-op make as much as reading them.
    """
    from dataclasses import replace

    rule = replace(rule, inputs={k: os.fspath(v) for k, v in rule.inputs.items()},
                   outputs={k: os.fspath(v) for k, v in rule.outputs.items()})
    rule.params_hash()
    rule.code_hash()
    return rule


def cached_graph(path: Path, key: str | None, build: Callable[[], list[Rule]]) -> Graph:
    """Return the graph cached under a key, else build and cache it.

    Either way the rules hold their paths as strings, so that a build behaves the same whether
    its graph came from the cache or not.

    Parameters
    ----------
    path : pathlib.Path
        The cache file; written only when its folder exists.
    key : str or None
        :func:`graph_key` of the graph; None: never read or write the cache.
    build : callable
        Returns the list of rules when the cache cannot be used.

    Returns
    -------
    flumekit.pipeline.engine.Graph
        The graph of the cached or built rules.
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
    """Return a digest of what a make was asked.

    Parameters
    ----------
    *parts : object
        JSON-able parts of the request (other values by ``str``).

    Returns
    -------
    str
        SHA-256 hex digest.

    Examples
    --------
    >>> request_key(["all"], 1) == request_key(["all"], 1)
    True
    >>> len(request_key("all"))
    64
    """
    return hashlib.sha256(json.dumps(parts, sort_keys=True, default=str).encode()).hexdigest()


def _stat(path) -> list[int] | None:
    try:
        st = os.stat(path)
    except OSError:
        return None
    return [st.st_size, st.st_mtime_ns]


def up_to_date(path: Path, request: str | None, state_file: Path) -> list[str] | None:
    """Return the targets a previous make of the same request left up to date.

    Parameters
    ----------
    path : pathlib.Path
        The record written by :func:`record_up_to_date`.
    request : str or None
        :func:`request_key` of this make; None: no record applies.
    state_file : pathlib.Path
        The build state file, whose size and mtime the record holds.

    Returns
    -------
    list of str or None
        The targets, if since the record no file they read or wrote and not the build state
        changed size or modification time; None otherwise.
    """
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
    """Record that targets (and everything they need) are up to date after a make.

    The record holds the size and modification time of every file they read or write, and of
    the build state (see :func:`up_to_date`); nothing is recorded when a file vanished.

    Parameters
    ----------
    path : pathlib.Path
        The record file (written atomically).
    request : str or None
        :func:`request_key` of the make; None: record nothing.
    state_file : pathlib.Path
        The build state file.
    graph : flumekit.pipeline.engine.Graph
        The graph the make ran.
    targets : list of str
        The targets made.
    """
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
    """Remove the record of :func:`record_up_to_date` (a make that builds may change anything).

    Parameters
    ----------
    path : pathlib.Path
        The record file; absent is fine.
    """
    try:
        os.unlink(path)
    except FileNotFoundError:
        pass
