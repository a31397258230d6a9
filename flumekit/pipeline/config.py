"""Pipeline definitions (``pipelines/<campaign>.toml``).

A pipeline file says where the campaign lives, the stage parameters, how to synthesise the
campaign when it is missing, and the scenes (named target lists).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from flumekit.errors import InputError
from flumekit.schema import Key, Problem, raise_problems, read_toml, validate
from flumekit.synth import DEFAULT_SEED

#: a pipeline file; each file of an ``extends`` chain is checked on its own (so that a problem
#: names its file), the required keys once merged
PIPELINE = {
    "extends": Key("text", "pipeline file this one extends (tables merge key by key)",
                   required=False),
    "pipeline": Key("table", "name and folders", table={
        "name": Key("text", "pipeline name", required=False),
        "raw": Key("text", "raw campaign folder, relative to this file", required=False),
        "processed": Key("text", "processed data folder, relative to this file",
                         required=False)}),
    "synth": Key("table", "synthesise the virtual flume into 'raw' when it is absent",
                 required=False, table={
        "size": Key("text", "campaign size", required=False, default="default",
                    choices=("small", "default", "paper")),
        "seed": Key("integer", "random seed", required=False, default=DEFAULT_SEED)}),
    "stages": Key("table", "stage parameters, [stages.<stage>] (`flumekit params`)",
                  required=False, table={}, items=Key("table", "one stage's parameters",
                                                      items=Key("any"))),
    "scenes": Key("table", "named target lists", required=False, table={},
                  items=Key("names", "target names or patterns", kinds=("table",),
                            items=Key("any"))),
}


@dataclass(frozen=True)
class Pipeline:
    r"""A parsed pipeline file (:func:`load_pipeline`).

    Attributes
    ----------
    path : pathlib.Path
        The pipeline file.
    name : str
        The pipeline's name.
    raw : pathlib.Path
        The raw campaign folder, resolved.
    processed : pathlib.Path
        The processed data folder, resolved.
    synth : dict or None
        The ``[synth]`` table (virtual-flume size and seed); None: never synthesise.
    stages : dict
        Stage name -> its parameters (``[stages.<stage>]``).
    scenes : dict
        Scene name -> target names or patterns.

    Examples
    --------
    A pipeline that synthesises a small virtual campaign when its raw folder is missing and
    names a scene; the build state lives in the processed folder:

    >>> import pathlib, tempfile
    >>> from flumekit.pipeline.config import load_pipeline
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     root = pathlib.Path(folder).resolve()
    ...     _ = (root / "flume.toml").write_text(
    ...         '[pipeline]\nname = "flume"\nraw = "raw"\nprocessed = "out"\n'
    ...         '[synth]\nsize = "small"\n[scenes]\nwaves = ["waves/*"]\n')
    ...     pipe = load_pipeline(root / "flume.toml")
    ...     state = pipe.state_file.relative_to(root).as_posix()
    >>> pipe.synth, pipe.scenes, pipe.stages, state
    ({'size': 'small'}, {'waves': ['waves/*']}, {}, 'out/.flumekit-state.json')
    """

    path: Path
    name: str
    raw: Path
    processed: Path
    synth: dict[str, Any] | None
    stages: dict[str, dict[str, Any]]
    scenes: dict[str, list[str]] = field(default_factory=dict)

    @property
    def state_file(self) -> Path:
        """Path of the build state file in the processed folder."""
        return self.processed / ".flumekit-state.json"


def _merge(base: dict, over: dict) -> dict:
    out = dict(base)
    for k, v in over.items():
        out[k] = _merge(out[k], v) if isinstance(v, dict) and isinstance(out.get(k), dict) else v
    return out


def _read(path: Path, depth: int = 0) -> dict:
    """Read a pipeline file, merged over the file it ``extends`` (tables merge key by key)."""
    data = read_toml(path)
    schema = {**PIPELINE, "pipeline": Key("table", "", required="extends" not in data,
                                           table=PIPELINE["pipeline"].table)}
    raise_problems(path, validate(data, schema, path))
    parent = data.pop("extends", None)
    if parent is None:
        return data
    if depth > 8 or not isinstance(parent, str):
        raise InputError(path, "'extends' must name one pipeline file (no cycles)", field="extends")
    return _merge(_read(path.parent / parent, depth + 1), data)


def check_outside_raw(raw: Path, processed: Path, source: Path, key: str) -> None:
    """Refuse a processed folder among the raw files, before anything runs.

    Parameters
    ----------
    raw, processed : pathlib.Path
        The raw campaign and the processed folder, resolved (symlinks followed).
    source : pathlib.Path
        The pipeline file that declared them, named in the error.
    key : str
        Where ``processed`` came from (``"processed"`` or ``"--processed"``).

    Raises
    ------
    flumekit.errors.InputError
        When ``processed`` is the raw folder, lies in its ``runs/`` (or is ``runs/``), or
        holds the raw campaign: outputs would mix with raw files, and a later ``clean`` or a
        glob over a run folder would take one for the other. A processed folder beside
        ``runs/`` inside the campaign folder (``raw = "."``, ``processed = "processed"``, as a
        lab keeps one folder per campaign) is allowed: nothing reads it as raw.
    """
    runs = raw / "runs"
    if processed == raw:
        why = "is the raw campaign folder"
    elif processed == runs or runs in processed.parents:
        why = "lies in the runs/ folder of the raw campaign"
    elif processed in raw.parents:
        why = "contains the raw campaign"
    else:
        return
    where = "field 'pipeline.processed'" if key == "processed" else "option --processed"
    raise InputError(source, f"the processed folder {processed} ({where}) {why} {raw}: "
                     "outputs would be written among raw files. Choose a folder outside the raw "
                     "campaign (or beside its runs/ folder)")


def load_pipeline(path: str | Path, processed: str | Path | None = None) -> Pipeline:
    r"""Read a pipeline file.

    Relative paths in it are relative to the file's folder; a file that ``extends`` another
    is merged over it (tables merge key by key).

    Parameters
    ----------
    path : str or path-like
        The pipeline file (``pipelines/<campaign>.toml``).
    processed : str or path-like, optional
        Processed data folder replacing the file's ``pipeline.processed``.

    Returns
    -------
    Pipeline
        The parsed pipeline, with resolved folders.

    Raises
    ------
    flumekit.errors.InputError
        For a missing or malformed key (named with its file and field), an ``extends``
        cycle, or a processed folder among the raw files (:func:`check_outside_raw`).

    Examples
    --------
    A tank's pipeline that extends the lab's: its folders are relative to its own file, the
    ones it does not set come from the lab's, and its ``[stages.flap]`` is merged key by key
    over the lab's.

    >>> import tempfile
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     lab = Path(folder).resolve()
    ...     _ = (lab / "lab.toml").write_text(
    ...         '[pipeline]\nname = "lab"\nraw = "raw"\nprocessed = "processed/lab"\n'
    ...         '[stages.flap]\ncutoff = 4.0\nn_phase = 50\n')
    ...     _ = (lab / "tank2.toml").write_text(
    ...         'extends = "lab.toml"\n[pipeline]\nname = "tank2"\nprocessed = "tank2"\n'
    ...         '[stages.flap]\ncutoff = 3.0\n')
    ...     pipe = load_pipeline(lab / "tank2.toml")
    ...     folders = [p.relative_to(lab).as_posix() for p in (pipe.raw, pipe.processed)]
    >>> pipe.name, folders, pipe.stages["flap"]
    ('tank2', ['raw', 'tank2'], {'cutoff': 3.0, 'n_phase': 50})
    """
    path = Path(path)
    data = _read(path)
    missing = [k for k in ("name", "raw", "processed") if k not in data.get("pipeline", {})]
    raise_problems(path, [Problem(path, f"pipeline.{k}", "missing key (a string)")
                          for k in missing])
    p = data["pipeline"]  # its keys are strings: validated by PIPELINE
    base = path.parent
    raw = (base / p["raw"]).resolve()
    out = Path(processed).resolve() if processed else (base / p["processed"]).resolve()
    check_outside_raw(raw, out, path, "processed" if processed is None else "--processed")
    scenes = {}
    for name, targets in data.get("scenes", {}).items():
        if isinstance(targets, dict):
            targets = targets.get("targets")
        if not isinstance(targets, list) or not all(isinstance(x, str) for x in targets):
            raise InputError(path, "a scene is a list of target names or patterns",
                             field=f"scenes.{name}")
        scenes[name] = targets
    stages = data.get("stages", {})
    if not isinstance(stages, dict) or not all(isinstance(v, dict) for v in stages.values()):
        raise InputError(path, "expected [stages.<name>] tables", field="stages")
    synth = data.get("synth")
    return Pipeline(path=path, name=p["name"], raw=raw, processed=out, synth=synth,
                    stages=stages, scenes=scenes)
