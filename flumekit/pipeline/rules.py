"""Rules: what a target is built from, by which action, with which parameters and code.

A rule's action is named as ``"module:function"`` and imported only when the rule runs, so that
planning a build (and the no-op ``flumekit make``) never imports numpy, xarray or matplotlib.
The action is called as ``action(inputs, outputs, params)`` with dicts of paths and parameters;
it must write every output atomically, and returns what its writers returned
(:class:`flumekit.io.atomic.Written`, one or an iterable of them, or None): the content digests
of the datasets it wrote.
"""

from __future__ import annotations

import hashlib
import importlib
import json
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any


@dataclass(frozen=True)
class Rule:
    """What a target is built from, by which action, with which parameters.

    Parameters
    ----------
    target : str
        Unique target name, e.g. ``"waves/T3.50_H0.250_r00"``.
    action : str
        ``"module:function"``, imported only when the rule runs; called as
        ``action(inputs, outputs, params)``.
    inputs : dict of str to path-like
        Input name -> file it reads.
    outputs : dict of str to path-like
        Output name -> file it writes (atomically).
    params : dict, optional
        The action's parameters (JSON-able; their hash is part of the build signature).
    version : str, default "1"
        An extra that changes the build signature on its own (the code is tracked anyway).
    run : str, optional
        Run identifier, for messages.
    source : bool, default False
        A rule that creates raw data (the virtual flume): it runs only where its outputs are
        all absent, is never forced, and the engine never removes its outputs.

    Examples
    --------
    >>> r = Rule("waves/R01", "flumekit.stages.waves:build", {"eta": "R01/eta.nc"},
    ...          {"waves": "waves/R01.nc"}, {"depth": 0.5})
    >>> r.params_hash() == Rule("x", "m:f", {}, {}, {"depth": 0.5}).params_hash()
    True
    """

    target: str  # unique name, e.g. "waves/T3.50_H0.250_r00"
    action: str  # "module:function"
    # paths as Path or str (the cached rules of :mod:`flumekit.pipeline.cache` hold strings);
    # an action always receives Paths
    inputs: dict[str, Path | str]
    outputs: dict[str, Path | str]
    params: dict[str, Any] = field(default_factory=dict)
    # an extra that changes the key on its own: the action's code is tracked (code_hash)
    version: str = "1"
    run: str | None = None  # run identifier, for messages
    # True for a rule that creates raw data (the virtual flume): it runs only where its outputs
    # are all absent, is never forced, and its outputs are never removed by the engine
    source: bool = False

    def params_hash(self) -> str:
        """Return the SHA-256 hex digest of the parameters (memoised)."""
        h = self.__dict__.get("_params_hash")  # memoised: a no-op make asks for every rule's
        if h is None:
            h = digest(json.dumps(self.params, sort_keys=True, default=str).encode())
            object.__setattr__(self, "_params_hash", h)  # frozen: set past the dataclass
        return h

    def code_hash(self) -> str:
        """Return the hash of the source the action runs (memoised, kept in the cached graph).

        See :func:`flumekit.pipeline.code.code_hash`: a change of that code rebuilds the target.
        """
        h = self.__dict__.get("_code_hash")
        if h is None:
            from flumekit.pipeline.code import code_hash

            h = code_hash(self.action)
            object.__setattr__(self, "_code_hash", h)
        return h

    def resolve(self) -> Callable[[dict, dict, dict], None]:
        """Import and return the action function."""
        module, _, name = self.action.partition(":")
        return getattr(importlib.import_module(module), name)


def digest(data: bytes) -> str:
    """Return the SHA-256 hex digest of ``data``.

    Examples
    --------
    >>> digest(b"")[:16]
    'e3b0c44298fc1c14'
    """
    return hashlib.sha256(data).hexdigest()


def file_digest(path: Path) -> str:
    """Return the SHA-256 hex digest of a file's bytes (read in chunks of 1 MiB)."""
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for chunk in iter(lambda: f.read(1 << 20), b""):
            h.update(chunk)
    return h.hexdigest()


def execute(rule: Rule, provenance: dict | None = None) -> tuple[float, dict[str, str]]:
    """Run a rule's action, in whatever process the executor chose.

    A failing action leaves none of its outputs behind (a raw-data ``source`` rule removes
    nothing: its action writes atomically and may not touch what was there).

    Parameters
    ----------
    rule : Rule
        The rule to run.
    provenance : dict, optional
        Inputs with relative paths and content hashes (:func:`flumekit.pipeline.engine.provenance`),
        recorded in every dataset the action writes (:func:`flumekit.conventions.provenance`).

    Returns
    -------
    seconds : float
        Run time of the action [s].
    written : dict of str to str
        Path -> content digest of the datasets it wrote (:func:`written_digests`).

    Raises
    ------
    RuntimeError
        When the action did not write all its outputs.
    """
    import time

    from flumekit import conventions

    prov = {"target": rule.target, "version": rule.version, "params": rule.params,
            "inputs": {}, "paths": {}, **(provenance or {})}
    # the virtual flume's raw files and truth are the same whichever command writes them
    token = conventions.set_provenance(None if rule.source else prov)
    t0 = time.perf_counter()
    try:
        result = rule.resolve()({k: Path(v) for k, v in rule.inputs.items()},
                                {k: Path(v) for k, v in rule.outputs.items()},
                                dict(rule.params))
        written = written_digests(result)
        missing = [str(p) for p in rule.outputs.values() if not Path(p).exists()]
        if missing:
            raise RuntimeError(f"action did not write its outputs {missing}")
    except BaseException:
        if rule.source:
            raise
        for p in rule.outputs.values():
            Path(p).unlink(missing_ok=True)
        raise
    finally:
        conventions.reset_provenance(token)
    return time.perf_counter() - t0, written


def written_digests(result) -> dict[str, str]:
    """Return path -> content digest of what an action returned.

    Parameters
    ----------
    result : Written or list of Written or None
        A written file (anything with a ``path`` and a ``digest``,
        :class:`flumekit.io.atomic.Written`), a list of them, or None (no digest: the engine
        identifies the outputs by their bytes).

    Returns
    -------
    dict of str to str
        Path -> content digest.

    Raises
    ------
    TypeError
        For anything else.
    """
    if result is None:
        return {}
    if hasattr(result, "digest"):
        items = [result]
    elif isinstance(result, (list, tuple)):
        items = list(result)
    else:
        items = [result]
    bad = [r for r in items if not (hasattr(r, "path") and hasattr(r, "digest"))]
    if bad:
        raise TypeError(f"an action returns the files it wrote (Written) or None, not {bad[0]!r}")
    return {str(r.path): r.digest for r in items}
