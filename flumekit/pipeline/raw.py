"""The raw folder of a pipeline: a laboratory's campaign, or one the virtual flume writes.

Raw data is sacred. The policy, decided before anything is planned or written:

- a folder with ``campaign.toml`` is a campaign, read as it is. Its run folders must have names
  a build can carry into file names, target names and patterns (:func:`check_run_names`);
- a campaign the virtual flume wrote carries :data:`MARKER` (its size, seed, the runs it
  plans and the runs written so far). The virtual flume completes such a campaign only with
  runs it has never written: ``flumekit make`` synthesises lazily the runs a requested target
  reads (:class:`Synthesis`). A planned run that was written and is gone (deleted or renamed by
  hand), or a run folder it never planned, is an error naming the runs and what to do; the
  campaign is never re-synthesised in place;
- a folder without ``campaign.toml`` is synthesised only when the pipeline asks for it
  (``[synth]``) and the folder is absent or empty.

Planning reads the marker without importing the synthesis (and numpy). A marker of a campaign
written whole (``flumekit synth``) lists no written runs: every planned run counts as written
once any run folder exists.
"""

from __future__ import annotations

import json
import os
from dataclasses import dataclass
from pathlib import Path

from flumekit.docstrings import filler
from flumekit.errors import FlumekitError, InputError
from flumekit.synth import DEFAULT_SEED, MARKER

#: docstring text that several functions of this module share
_doc = filler(
    raw=("raw : pathlib.Path\n"
         "    The campaign folder."),
    raw_folder=("raw : Path\n"
                "    The campaign folder."))

#: characters a run folder's name may not hold: a path separator on some system (``\\`` is one
#: for the netCDF library, which would write outside the processed folder), and the wildcards
#: of target patterns (a run named ``*`` would make ``waves/*`` name one target or all)
FORBIDDEN_IN_RUN_NAMES = ("\\", "/", "*", "?", "[", "]", "\0")


@_doc
@dataclass(frozen=True)
class Synthesis:
    """What the virtual flume is to write into the raw folder (planned from its design).

    :func:`synthesis_plan` returns one for an absent or empty raw folder (where the pipeline
    allows it), or a virtual campaign with planned runs still missing; never for a lab's own
    recordings.

    Parameters
    ----------
    %(size)s
    %(seed)s
    """

    size: str
    seed: int


def is_synthesis_temporary(name: str) -> bool:
    """Return whether a name in ``runs/`` is the temporary folder of a run being synthesised.

    The virtual flume writes each run beside the others, then renames it into place.

    Parameters
    ----------
    name : str
        A folder name.

    Returns
    -------
    bool
        True for ``.<anything>.partial``.

    Examples
    --------
    >>> is_synthesis_temporary(".R01.partial"), is_synthesis_temporary("R01")
    (True, False)
    """
    return name.startswith(".") and name.endswith(".partial")


@_doc
def run_folders(raw: Path) -> list[str]:
    """Return the names of the run folders in ``raw/runs``, sorted.

    Every folder is listed except hidden ones without ``run.toml`` (a tool's folder, a
    synthesis temporary); a hidden folder with ``run.toml`` is listed (the campaign reader
    would read it as a run).

    Parameters
    ----------
    %(raw)s

    Returns
    -------
    list of str
        Folder names; empty when ``raw/runs`` is absent.
    """
    try:
        entries = list(os.scandir(raw / "runs"))
    except (FileNotFoundError, NotADirectoryError):
        return []
    return sorted(e.name for e in entries if e.is_dir() and not (
        e.name.startswith(".") and (is_synthesis_temporary(e.name)
                                    or not os.path.isfile(os.path.join(e.path, "run.toml")))))


@_doc
def check_run_names(raw: Path, names: list[str]) -> None:
    """Refuse run folders whose names a build cannot carry safely.

    A run's name becomes part of target names, patterns and output file names. Names with a
    path separator or a wildcard (:data:`FORBIDDEN_IN_RUN_NAMES`), a leading dot (a hidden
    folder, which globbing skips on some systems and which names a hidden output), control
    characters, or surrounding blanks are refused; any other name (unicode, inner dots, ``..``
    inside a name) is used as it is.

    Parameters
    ----------
    %(raw_folder)s
    names : list of str
        Names of the folders in ``raw/runs``.

    Raises
    ------
    InputError
        Naming the first offending run folder and the rule it breaks (nothing was written).
    """
    for name in names:
        bad = [c for c in FORBIDDEN_IN_RUN_NAMES if c in name]
        why = None
        if bad:
            why = f"holds {' '.join(repr(c) for c in bad)}"
        elif name.startswith("."):
            why = "starts with '.' (a hidden folder)"
        elif any(ord(c) < 32 or ord(c) == 127 for c in name):
            why = "holds a control character"
        elif name != name.strip():
            why = "starts or ends with a blank"
        if why:
            raise InputError(raw / "runs" / name,
                             f"run folder name {name!r} {why}: a run's name becomes part of "
                             "target and file names. Rename the folder (letters, digits, "
                             "'_', '-', '.'); nothing was built or written")


@_doc
def read_marker(raw: Path) -> dict | None:
    """Read the virtual flume's marker of a raw folder.

    The marker (:data:`flumekit.synth.MARKER`, JSON) is the file the virtual flume writes
    into every campaign it synthesises; a lab's own raw folder has none.

    Parameters
    ----------
    %(raw)s

    Returns
    -------
    dict or None
        ``{"size", "seed", "runs", "written"}`` (``written`` None for a campaign written
        whole); None when ``raw`` is not a virtual campaign.

    Raises
    ------
    flumekit.errors.InputError
        When the marker exists but cannot be read.
    """
    marker = raw / MARKER
    if not marker.is_file():
        return None
    try:
        info = json.loads(marker.read_text(encoding="utf-8"))
        planned = [str(r) for r in info["runs"]]
        written = info.get("written")
        return {"size": str(info["size"]), "seed": int(info["seed"]), "runs": planned,
                "written": None if written is None else [str(r) for r in written]}
    except (OSError, ValueError, KeyError, TypeError) as e:
        raise InputError(marker, f"not a readable virtual-flume marker ({e}); it was written "
                         "by the virtual flume: restore it, or synthesise a fresh campaign "
                         "into a new folder") from None


@_doc
def check_virtual_campaign(raw: Path, info: dict, present: list[str]) -> list[str]:
    """Return the planned runs still to synthesise in a virtual campaign, or raise.

    Parameters
    ----------
    %(raw_folder)s
    info : dict
        Its marker (:func:`read_marker`).
    present : list of str
        The run folders there (:func:`run_folders`).

    Returns
    -------
    list of str
        Planned runs never written (to be synthesised when a target reads them).

    Raises
    ------
    InputError
        A written run missing (deleted or renamed by hand) or a run folder the virtual flume
        never planned: the message names them and what to do.
    """
    planned, have = info["runs"], set(present)
    written = info["written"]
    if written is None:  # a campaign written whole: every planned run, once any is there
        written = planned if have else []
    extra = sorted(have - set(planned))
    gone = [r for r in planned if r in set(written) and r not in have]
    incomplete = [r for r in planned if r in have and not (raw / "runs" / r / "run.toml").is_file()]
    if extra or gone or incomplete:
        parts = []
        if gone:
            parts.append(f"written by the virtual flume and now missing (deleted or renamed): "
                         f"{', '.join(gone)}")
        if incomplete:
            parts.append(f"without run.toml: {', '.join(incomplete)}")
        if extra:
            parts.append(f"not planned by the virtual flume (added or renamed): "
                         f"{', '.join(repr(r) for r in extra)}")
        raise InputError(raw / "runs", "this virtual-flume campaign was changed by hand; runs "
                         + "; ".join(parts) + ". The virtual flume never writes into a changed "
                         "campaign (nothing was written): restore the runs, or write a fresh "
                         f"campaign into a new folder (`flumekit synth --size {info['size']} "
                         f"--seed {info['seed']} --out NEW_FOLDER`) and point 'raw' at it, or "
                         "delete this folder to let `flumekit make` synthesise it again")
    return [r for r in planned if r not in have]


def synthesis_plan(raw: Path, synth: dict | None, pipeline_file: Path) -> Synthesis | None:
    """Return what the virtual flume is to write into a raw folder.

    Parameters
    ----------
    raw : Path
        The pipeline's raw folder.
    synth : dict or None
        The pipeline's ``[synth]`` table (None: never synthesise).
    pipeline_file : Path
        The pipeline file, for messages.

    Returns
    -------
    Synthesis or None
        The size and seed to synthesise; None when the campaign is there and whole.

    Raises
    ------
    FlumekitError
        No campaign and no synthesis allowed, or a folder with other files (nothing changed).
    InputError
        Odd run folder names; a virtual campaign changed by hand (:func:`check_virtual_campaign`).
    """
    if (raw / "campaign.toml").exists():
        present = run_folders(raw)
        # the runs the campaign reader reads (a folder with run.toml), before anything else
        check_run_names(raw, [r for r in present if (raw / "runs" / r / "run.toml").is_file()])
        info = read_marker(raw)
        if info is None:
            return None
        todo = check_virtual_campaign(raw, info, present)
        return Synthesis(info["size"], info["seed"]) if todo else None
    # The virtual flume is written only into an absent or empty folder: a raw path one folder
    # off or a renamed campaign.toml must never cost a laboratory its files.
    empty = not raw.exists() or (raw.is_dir() and not any(raw.iterdir()))
    if not (synth is not None and empty):
        why = ("" if empty else "; the folder holds other files, so no virtual campaign is "
               "written there (nothing was changed)")
        raise FlumekitError(f"{raw / 'campaign.toml'}: campaign file not found{why}. "
                            f"Check 'raw' in {pipeline_file}")
    return Synthesis(str(synth.get("size", "default")), int(synth.get("seed", DEFAULT_SEED)))


@_doc
def campaign_files(raw: Path) -> list[str | Path]:
    """Return every file the rules of a campaign are made of.

    Parameters
    ----------
    %(raw)s

    Returns
    -------
    list of str or pathlib.Path
        ``campaign.toml``, the virtual-flume marker and each ``runs/<run>/run.toml`` (present
        or not); the run files as strings, which are cheaper than Paths for a large campaign.
    """
    runs = os.path.join(raw, "runs")
    return [raw / "campaign.toml", raw / MARKER,
            *(os.path.join(runs, r, "run.toml") for r in run_folders(raw))]


__all__ = ["FORBIDDEN_IN_RUN_NAMES", "Synthesis", "campaign_files",
           "check_run_names", "check_virtual_campaign", "is_synthesis_temporary", "read_marker",
           "run_folders", "synthesis_plan"]
