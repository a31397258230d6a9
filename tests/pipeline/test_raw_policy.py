"""The raw-folder policy (flumekit.pipeline.raw): a virtual campaign changed by hand is reported,
never re-synthesised in place; a campaign the virtual flume is still writing run by run is
completed; odd run folder names are refused or used, before anything is written.

The unit tests build the marker and run folders by hand (what the virtual flume leaves, without
synthesising); the command-line tests synthesise the small campaign for real.
"""

import hashlib
import json
import multiprocessing
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from flumekit.errors import FlumekitError, InputError
from flumekit.pipeline.raw import (
    Synthesis,
    check_run_names,
    read_marker,
    run_folders,
    synthesis_plan,
)
from flumekit.synth import DEFAULT_SEED, MARKER
from flumekit.synth.marker import record_written, start_record

ROOT = Path(__file__).resolve().parents[2]
PLANNED = ["T2.00_H0.150_r0", "T3.50_H0.250_r0", "uvp_z0.300_r0"]
PIPE = Path("pipelines/small.toml")


def virtual(tmp_path, present, written=None, planned=PLANNED) -> Path:
    """A campaign folder as the virtual flume leaves it: campaign.toml, the marker (with the
    runs written so far, or none: a campaign written whole) and the run folders ``present``."""
    raw = tmp_path / "raw"
    (raw / "runs").mkdir(parents=True)
    (raw / "campaign.toml").write_text("[campaign]\nname = 'x'\n")
    info = {"size": "small", "seed": 7, "runs": planned}
    if written is not None:
        info["written"] = written
    (raw / MARKER).write_text(json.dumps(info) + "\n")
    for r in present:
        (raw / "runs" / r).mkdir()
        (raw / "runs" / r / "run.toml").write_text("[run]\n")
    return raw


def hashes(folder: Path) -> dict[str, str]:
    return {str(p.relative_to(folder)): hashlib.sha256(p.read_bytes()).hexdigest()
            for p in sorted(folder.rglob("*")) if p.is_file()}


# --- a virtual campaign: complete, being written, changed by hand --------------------------------

def test_a_whole_campaign_needs_no_synthesis(tmp_path):
    assert synthesis_plan(virtual(tmp_path, PLANNED), {"size": "small"}, PIPE) is None


def test_runs_never_written_are_still_synthesised(tmp_path):
    raw = virtual(tmp_path, PLANNED[:1], written=PLANNED[:1])
    assert synthesis_plan(raw, None, PIPE) == Synthesis("small", 7)
    # the base written, no run yet
    raw2 = virtual(tmp_path / "b", [], written=[])
    assert synthesis_plan(raw2, None, PIPE) == Synthesis("small", 7)
    # the base written by a synthesis killed before it recorded the start: no run, no list
    raw3 = virtual(tmp_path / "c", [])
    assert synthesis_plan(raw3, None, PIPE) == Synthesis("small", 7)


@pytest.mark.parametrize("present, written, named", [
    # deleted by hand from a campaign written whole, or run by run
    (PLANNED[1:], None, ["T2.00_H0.150_r0", "deleted or renamed"]),
    (PLANNED[:1], PLANNED[:2], ["T3.50_H0.250_r0", "deleted or renamed"]),
    # renamed: the old name missing, the new one not planned
    (["T2.00_H0.150_r0_old", *PLANNED[1:]], None,
     ["renamed): T2.00_H0.150_r0;", "renamed): 'T2.00_H0.150_r0_old'"]),
    # added, with a name the build would accept in a lab campaign (unicode, '..' inside)
    ([*PLANNED, "extra_ä_波"], None, ["'extra_ä_波'", "not planned"]),
    ([*PLANNED, "run..1"], None, ["'run..1'"]),
])
def test_a_campaign_changed_by_hand_is_reported_not_resynthesised(tmp_path, present, written,
                                                                  named):
    raw = virtual(tmp_path, present, written)
    before = hashes(raw)
    with pytest.raises(InputError) as e:
        synthesis_plan(raw, {"size": "small"}, PIPE)
    text = str(e.value)
    for n in named:
        assert n in text, (n, text)
    assert "flumekit synth --size small --seed 7 --out" in text and "delete this folder" in text
    assert hashes(raw) == before


def test_a_planned_run_folder_without_run_toml_is_reported(tmp_path):
    raw = virtual(tmp_path, PLANNED[1:])
    (raw / "runs" / PLANNED[0]).mkdir()
    with pytest.raises(InputError, match=f"without run.toml: {PLANNED[0]}"):
        synthesis_plan(raw, None, PIPE)


def test_synthesis_temporaries_and_hidden_tool_folders_are_not_runs(tmp_path):
    raw = virtual(tmp_path, PLANNED)
    (raw / "runs" / ".T2.00_H0.150_r0.abc123.partial").mkdir()
    (raw / "runs" / ".ipynb_checkpoints").mkdir()
    (raw / "runs" / "notes.txt").write_text("a file is not a run")
    assert run_folders(raw) == PLANNED
    assert synthesis_plan(raw, None, PIPE) is None


# --- odd run names in any campaign ---------------------------------------------------------------

def lab(tmp_path, names) -> Path:
    raw = tmp_path / "lab"
    (raw / "runs").mkdir(parents=True)
    (raw / "campaign.toml").write_text("[campaign]\nname = 'lab'\n")
    for n in names:
        (raw / "runs" / n).mkdir()
        (raw / "runs" / n / "run.toml").write_text("[run]\n")
    return raw


@pytest.mark.parametrize("name, why", [
    ("\\..\\..\\escape", "'\\\\'"),
    ("*", "'*'"),
    ("run[1]", "'['"),
    (".hidden", "starts with '.'"),
    ("tab\there", "control character"),
    (" padded", "blank"),
])
def test_odd_run_names_are_refused_naming_the_folder(tmp_path, name, why):
    raw = lab(tmp_path, ["good", name])
    before = hashes(raw)
    with pytest.raises(InputError) as e:
        synthesis_plan(raw, None, PIPE)
    assert str(raw / "runs" / name) in str(e.value) and why in str(e.value)
    assert "nothing was built or written" in str(e.value)
    assert hashes(raw) == before


@pytest.mark.parametrize("name", ["Lauf_ä_波", "run..1", "x.y-z_1", "a" * 40])
def test_other_names_are_used_as_they_are(tmp_path, name):
    raw = lab(tmp_path, [name])
    assert synthesis_plan(raw, None, PIPE) is None
    check_run_names(raw, [name])


def test_a_folder_without_campaign_toml_is_synthesised_only_when_absent_or_empty(tmp_path):
    assert synthesis_plan(tmp_path / "absent", {}, PIPE) == Synthesis("default", DEFAULT_SEED)
    (tmp_path / "empty").mkdir()
    assert synthesis_plan(tmp_path / "empty", {"size": "small", "seed": 3}, PIPE) == \
        Synthesis("small", 3)
    with pytest.raises(FlumekitError, match="campaign file not found"):
        synthesis_plan(tmp_path / "absent", None, PIPE)  # no [synth]
    (tmp_path / "notes").mkdir()
    (tmp_path / "notes" / "README.txt").write_text("lab notes")
    with pytest.raises(FlumekitError, match="holds other files"):
        synthesis_plan(tmp_path / "notes", {}, PIPE)
    assert [p.name for p in (tmp_path / "notes").iterdir()] == ["README.txt"]


# --- the record of written runs --------------------------------------------------------------

def test_record_written_keeps_every_run_once(tmp_path):
    raw = virtual(tmp_path, [])
    start_record(raw)
    assert read_marker(raw)["written"] == []
    record_written(raw, PLANNED[1])
    record_written(raw, PLANNED[0])
    record_written(raw, PLANNED[1])
    info = read_marker(raw)
    assert info["written"] == sorted(PLANNED[:2]) and info["runs"] == PLANNED
    start_record(raw)  # never forgets what was recorded
    assert read_marker(raw)["written"] == sorted(PLANNED[:2])


def _record(args):
    record_written(*args)


def test_runs_recorded_by_parallel_processes_are_all_kept(tmp_path):
    names = [f"r{i:02d}" for i in range(16)]
    raw = virtual(tmp_path, [], written=[], planned=names)
    with multiprocessing.get_context("spawn").Pool(4) as pool:
        pool.map(_record, [(raw, n) for n in names])
    assert read_marker(raw)["written"] == names


def test_an_unreadable_marker_is_named(tmp_path):
    raw = virtual(tmp_path, PLANNED)
    (raw / MARKER).write_text("{not json")
    with pytest.raises(InputError, match=MARKER.replace(".", r"\.")):
        synthesis_plan(raw, None, PIPE)


# --- the command line, with the virtual flume ----------------------------------------------------

def flumekit(*args, cwd):
    return subprocess.run([sys.executable, "-m", "flumekit.cli", *args], cwd=cwd,
                          capture_output=True, text=True)


def test_lazy_synthesis_completes_but_a_deleted_run_is_an_error(fresh_project):
    p = fresh_project
    raw = p / "raw" / "small"
    r = flumekit("make", "--pipeline", "pipelines/small.toml", "synth/T2.00_H0.150_r0", cwd=p)
    assert r.returncode == 0, r.stderr
    assert run_folders(raw) == ["T2.00_H0.150_r0"]
    assert read_marker(raw)["written"] == ["T2.00_H0.150_r0"]
    # the other runs were never written: still planned for synthesis
    r = flumekit("make", "-n", "--pipeline", "pipelines/small.toml", "eta/T3.50_H0.250_r0", cwd=p)
    assert r.returncode == 0, r.stderr
    assert "would build synth/T3.50_H0.250_r0" in r.stdout
    # the written run deleted by hand: reported, nothing synthesised or built
    shutil.rmtree(raw / "runs" / "T2.00_H0.150_r0")
    before = hashes(raw)
    for args in (["make"], ["make", "-n"], ["make", "eta/T3.50_H0.250_r0"], ["list"]):
        r = flumekit(*args, "--pipeline", "pipelines/small.toml", cwd=p)
        assert r.returncode == 1, (args, r.stdout, r.stderr)
        assert "T2.00_H0.150_r0" in r.stderr and "deleted or renamed" in r.stderr
        assert "Traceback" not in r.stderr
        assert hashes(raw) == before
    assert not (raw / "runs" / "T3.50_H0.250_r0").exists()
    assert not (p / "processed" / "small" / "eta").exists()
