"""`flumekit make` end to end on the small virtual-flume campaign (issue 2 acceptance)."""

import hashlib
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
import xarray as xr

ROOT = Path(__file__).resolve().parents[1]


def flumekit(*args, cwd):
    return subprocess.run([sys.executable, "-m", "flumekit.cli", *args], cwd=cwd,
                          capture_output=True, text=True)


@pytest.fixture(scope="module")
def small_raw(tmp_path_factory):
    from flumekit.synth.campaign import write_campaign

    raw = tmp_path_factory.mktemp("raw") / "small"
    write_campaign(raw, size="small", seed=7)
    return raw


def _project(path, small_raw):
    (path / "pipelines").mkdir()
    for name in ("default.toml", "small.toml"):
        shutil.copy(ROOT / "pipelines" / name, path / "pipelines" / name)
    shutil.copytree(small_raw, path / "raw" / "small")
    return path


@pytest.fixture
def project(tmp_path, small_raw):
    """A project with the small raw campaign and nothing built."""
    return _project(tmp_path, small_raw)


@pytest.fixture(scope="module")
def built_once(tmp_path_factory, small_raw):
    path = _project(tmp_path_factory.mktemp("built"), small_raw)
    first = make(path)
    assert first.returncode == 0, first.stderr
    assert "calibration" in built(first)
    return path


@pytest.fixture
def built_project(tmp_path, built_once):
    """A copy of a project on which `flumekit make` has run (the build state copies along)."""
    shutil.copytree(built_once, tmp_path / "p")
    return tmp_path / "p"


def make(project, *args):
    return flumekit("make", "--pipeline", "pipelines/small.toml", *args, cwd=project)


def raw_hashes_of(folder):
    return {p: hashlib.sha256(p.read_bytes()).hexdigest()
            for p in sorted(folder.rglob("*")) if p.is_file()}


def built(result):
    return sorted(line.split("] ", 1)[1].split(":")[0] for line in result.stderr.splitlines()
                  if line.startswith("["))


def test_make_builds_then_rebuilds_nothing(built_once, small_raw):
    second = make(built_once)
    assert second.returncode == 0
    assert built(second) == []
    assert "nothing to do" in second.stderr
    fresh = {p.relative_to(small_raw): h for p, h in raw_hashes_of(small_raw).items()}
    after = {p.relative_to(built_once / "raw" / "small"): h
             for p, h in raw_hashes_of(built_once / "raw" / "small").items()}
    assert after == fresh  # raw data untouched by the builds


def test_every_dataset_has_units_long_names_and_history(built_once):
    files = sorted((built_once / "processed" / "small").rglob("*.nc"))
    assert files
    for f in files:
        with xr.open_dataset(f) as ds:
            assert {"history", "source", "Conventions", "title"} <= set(ds.attrs), f
            for name, var in {**ds.coords, **ds.data_vars}.items():
                assert "long_name" in var.attrs, (f, name)
                if var.dtype.kind not in "OSU":
                    assert "units" in var.attrs, (f, name)


def test_touch_rebuilds_nothing_and_change_rebuilds_one_run(built_project):
    project = built_project
    run_dir = sorted((project / "raw/small/runs").iterdir())[0]
    probes = run_dir / "probes.csv"
    os.utime(probes)  # touched, unchanged
    assert built(make(project)) == []
    lines = probes.read_text().splitlines()
    lines[5] = lines[5][:-1] + ("1" if lines[5][-1] != "1" else "2")  # change one voltage digit
    probes.write_text("\n".join(lines) + "\n")
    rebuilt = built(make(project))
    assert rebuilt, "a changed run must rebuild"
    other_runs = [d.name for d in (project / "raw/small/runs").iterdir() if d != run_dir]
    assert not any(r in t for t in rebuilt for r in other_runs), rebuilt
    assert any(run_dir.name in t for t in rebuilt)


def test_changing_a_stage_parameter_rebuilds_only_its_dependants(built_project):
    project = built_project
    pipe = project / "pipelines" / "small.toml"
    pipe.write_text(pipe.read_text() + "\n[stages.flap]\ncutoff = 3.0\n")
    rebuilt = built(make(project))
    assert any(t.startswith("flap/") for t in rebuilt)
    # upstream of the flap stage, and the ball-screw models, do not depend on it
    assert not any(t.startswith(("calibration", "eta/", "waves", "ballscrew", "figure/bs_"))
                   for t in rebuilt), rebuilt


def test_dry_run_lists_reasons_and_builds_nothing(project):
    result = make(project, "-n")
    assert result.returncode == 0
    assert "would build calibration: output dataset missing" in result.stdout
    assert not (project / "processed" / "small" / "calibration.nc").exists()


def test_malformed_input_is_a_clear_error_without_output(project):
    run_dir = sorted((project / "raw/small/runs").iterdir())[0]
    probes = run_dir / "probes.csv"
    text = probes.read_text()
    probes.write_text(text[: len(text) // 2].rsplit(",", 1)[0])  # truncated mid-line
    result = make(project, f"eta/{run_dir.name}")
    assert result.returncode == 1
    assert "Traceback" not in result.stderr
    assert str(probes) in result.stderr and "truncated" in result.stderr
    assert not (project / "processed/small/eta" / f"{run_dir.name}.nc").exists()
    debug = flumekit("--debug", "make", "--pipeline", "pipelines/small.toml",
                     f"eta/{run_dir.name}", cwd=project)
    assert "Traceback" in debug.stderr


def test_scene_runs_only_what_it_needs(project):
    fig10 = built(make(project, "fig10"))
    runs = {t.split("/", 1)[1] for t in fig10
            if t.startswith(("eta/", "waves/", "flap/", "comparison/"))}
    assert len(runs) == 1, fig10  # figure 10 processes one run, not the campaign
    efficiency = built(make(project, "ballscrew_efficiency"))
    assert "ballscrew/efficiency" in efficiency
    assert "ballscrew/thermal_fem" not in efficiency
    assert "ballscrew/thermal_lumped" not in efficiency


def test_list_shows_scenes_and_state(project):
    result = flumekit("list", "--pipeline", "pipelines/small.toml", cwd=project)
    assert result.returncode == 0, result.stderr
    assert "1 of 1 to build" in result.stdout and "output dataset missing" in result.stdout
