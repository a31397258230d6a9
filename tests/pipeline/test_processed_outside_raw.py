"""The engine never writes among raw files: a processed folder that is the raw folder, lies in
its runs/ or contains the campaign is refused before anything runs (symlinks resolved); one
beside runs/ in the campaign folder stays allowed."""

import hashlib
import subprocess
import sys

import pytest

from flumekit.errors import InputError
from flumekit.pipeline.config import load_pipeline


def _campaign(root):
    (root / "runs" / "run1").mkdir(parents=True)
    (root / "campaign.toml").write_text("[campaign]\nname = 'lab'\n")
    (root / "runs" / "run1" / "run.toml").write_text("[run]\nperiod = 2.0\n")
    (root / "runs" / "run1" / "probes.csv").write_text("time,WP1\n0,0\n")
    return root


def _pipeline(folder, raw, processed):
    path = folder / "pipeline.toml"
    path.write_text(f'[pipeline]\nname = "p"\nraw = "{raw}"\nprocessed = "{processed}"\n')
    return path


@pytest.mark.parametrize("processed, why", [
    ("lab", "is the raw campaign folder"),
    ("lab/runs", "runs/ folder"),
    ("lab/runs/run1", "runs/ folder"),
    ("lab/runs/run1/out", "runs/ folder"),
    (".", "contains the raw campaign"),
    ("link", "runs/ folder"),  # a symlink to a run folder
])
def test_processed_among_raw_files_is_refused(tmp_path, processed, why):
    _campaign(tmp_path / "lab")
    (tmp_path / "link").symlink_to(tmp_path / "lab" / "runs" / "run1")
    with pytest.raises(InputError) as e:
        load_pipeline(_pipeline(tmp_path, "lab", processed))
    msg = str(e.value)
    assert why in msg and "pipeline.toml" in msg and str(tmp_path / "lab") in msg


def test_processed_override_is_checked_too(tmp_path):
    _campaign(tmp_path / "lab")
    with pytest.raises(InputError, match="--processed"):
        load_pipeline(_pipeline(tmp_path, "lab", "out"), processed=tmp_path / "lab" / "runs")


def test_processed_beside_runs_is_allowed(tmp_path):
    """One folder per campaign, as a lab keeps it: raw = ".", processed = "processed"."""
    _campaign(tmp_path / "lab")
    pipe = load_pipeline(_pipeline(tmp_path / "lab", ".", "processed"))
    assert pipe.processed == (tmp_path / "lab" / "processed").resolve()


def test_make_refuses_before_writing_anything(tmp_path):
    lab = _campaign(tmp_path / "lab")
    before = {p: hashlib.sha256(p.read_bytes()).hexdigest() for p in lab.rglob("*")
              if p.is_file()}
    pipe = _pipeline(tmp_path, "lab", "lab/runs/run1")
    for args in (["make"], ["make", "-n"], ["list"], ["clean"]):
        r = subprocess.run([sys.executable, "-m", "flumekit.cli", *args, "--pipeline",
                            str(pipe)], cwd=tmp_path, capture_output=True, text=True)
        assert r.returncode == 1, (args, r.stderr)
        assert "among raw files" in r.stderr and "Traceback" not in r.stderr
    after = {p: hashlib.sha256(p.read_bytes()).hexdigest() for p in lab.rglob("*")
             if p.is_file()}
    assert after == before
