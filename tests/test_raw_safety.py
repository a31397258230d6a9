"""Raw data is sacred: no command deletes, moves or rewrites a file under a raw folder that it did
not create in the same call."""

import hashlib
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


def _flumekit(*args, cwd):
    return subprocess.run([sys.executable, "-m", "flumekit.cli", *args], cwd=cwd,
                          capture_output=True, text=True)


def _hashes(folder: Path) -> dict[str, str]:
    return {str(p.relative_to(folder)): hashlib.sha256(p.read_bytes()).hexdigest()
            for p in sorted(folder.rglob("*")) if p.is_file()}


def _lab_folder(path: Path) -> Path:
    """A folder as a laboratory keeps it: notes, another campaign's files, a renamed campaign."""
    path.mkdir(parents=True)
    (path / "README.txt").write_text("lab notes: flume 2026, do not delete\n")
    (path / "Campaign.TOML").write_text("[campaign]\nname = 'misnamed'\n")
    (path / "other").mkdir()
    (path / "other" / "probes.csv").write_text("time [s],WP1 [V]\n0.0,1.0\n")
    return path


def _project(tmp_path: Path, raw: str) -> Path:
    (tmp_path / "pipelines").mkdir()
    shutil.copy(ROOT / "pipelines" / "default.toml", tmp_path / "pipelines" / "default.toml")
    text = (ROOT / "pipelines" / "small.toml").read_text().replace('"../raw/small"', f'"{raw}"')
    (tmp_path / "pipelines" / "small.toml").write_text(text)
    return tmp_path


@pytest.mark.parametrize("raw", ["../raw/small", "../raw"])
def test_make_never_touches_a_raw_folder_without_campaign_toml(tmp_path, raw):
    """A misnamed campaign.toml, or a raw path that points at the parent folder: an error that
    names the missing file, exit 1, and every file kept byte for byte."""
    project = _project(tmp_path, raw)
    lab = _lab_folder(project / "raw" / "small")
    watched = project / "raw"
    before = _hashes(watched)
    for args in (["make"], ["make", "-n"], ["list"], ["make", "ballscrew"]):
        r = _flumekit(*args, "--pipeline", "pipelines/small.toml", cwd=project)
        assert r.returncode == 1, (args, r.stdout, r.stderr)
        assert "campaign.toml" in r.stderr and "Traceback" not in r.stderr
        assert _hashes(watched) == before
    assert (lab / "README.txt").exists()
    assert sorted(p.name for p in watched.iterdir()) == ["small"]  # no sibling left behind


def test_synth_refuses_a_folder_with_files(tmp_path):
    lab = _lab_folder(tmp_path / "lab")
    before = _hashes(lab)
    r = _flumekit("synth", "--size", "small", "--out", str(lab), cwd=tmp_path)
    assert r.returncode == 1 and "empty folder" in r.stderr and "Traceback" not in r.stderr
    assert _hashes(lab) == before
    assert sorted(p.name for p in tmp_path.iterdir()) == ["lab"]


def test_synthesis_fills_an_empty_folder_and_cleans_up_after_failure(tmp_path, monkeypatch):
    from flumekit.synth import campaign as synth_campaign

    out = tmp_path / "raw" / "new"
    out.mkdir(parents=True)

    def boom(*a, **k):
        raise RuntimeError("disk full")

    monkeypatch.setattr(synth_campaign, "_write_calibration", boom)
    with pytest.raises(RuntimeError):
        synth_campaign.write_campaign(out, size="small")
    assert sorted(p.name for p in out.parent.iterdir()) == ["new"]  # temporary folder removed
    assert not any(out.iterdir())
