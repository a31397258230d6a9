"""`flumekit make` end to end on the small virtual-flume campaign."""

import hashlib
import os
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
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


def test_make_builds_every_target_list_shows(built_once):
    """Every scene means every target: after `make`, `list` shows none missing (the QC
    summary and the QC figures belong to the default scenes)."""
    r = flumekit("list", "--pipeline", "pipelines/small.toml", cwd=built_once)
    assert r.returncode == 0, r.stderr
    missing = [line for line in r.stdout.splitlines() if "missing" in line]
    assert missing == []
    assert "qc_summary" in r.stdout and "figure/qc/" in r.stdout


def test_every_dataset_has_units_long_names_and_history(built_once):
    files = sorted((built_once / "processed" / "small").rglob("*.nc"))
    assert files
    for f in files:
        with xr.open_dataset(f, decode_times=False) as ds:  # time: seconds since start
            assert {"history", "source", "Conventions", "title"} <= set(ds.attrs), f
            # CF 7.1: a boundary variable takes its parent's units (xarray writes none)
            bounds = {v.attrs["bounds"] for v in ds.variables.values() if "bounds" in v.attrs}
            for name, var in {**ds.coords, **ds.data_vars}.items():
                assert "long_name" in var.attrs, (f, name)
                if var.dtype.kind not in "OSU" and name not in bounds:
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


# --- safety of the engine ---------------------------------------------------

def _popen(project, *args, **kw):
    return subprocess.Popen([sys.executable, "-m", "flumekit.cli", "make", "--pipeline",
                             "pipelines/small.toml", *args], cwd=project, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True, **kw)


def _temporaries(folder):
    return sorted(p for p in folder.rglob("*") if ".flumekit-tmp" in p.name or ".tmp" in p.name)


def test_failed_rebuild_leaves_no_stale_output_downstream(built_project):
    """A run whose raw file changes and whose rebuild fails loses its outputs and every output
    made from them (summaries, figures); the other runs' files stay."""
    project = built_project
    out = project / "processed/small"
    runs = sorted(d.name for d in (project / "raw/small/runs").iterdir())
    bad = runs[0]
    probes = project / "raw/small/runs" / bad / "probes.csv"
    text = probes.read_text()
    probes.write_text(text[: len(text) // 2].rsplit(",", 1)[0])  # truncated mid-line
    result = make(project, "-k")
    assert result.returncode == 1
    for stage in ("eta", "waves", "flap", "comparison"):
        assert not (out / stage / f"{bad}.nc").exists(), stage
        assert (out / stage / f"{runs[1]}.nc").exists(), stage  # other runs are kept
    assert not (out / "waves_summary.nc").exists()
    assert not (out / "flap_summary.nc").exists()
    assert (out / "calibration.nc").exists()
    # the failure list names the target, the run, the file and the problem
    tail = result.stderr.split("failures (target, run, file: problem):", 1)[1]
    # (the first rule to read the file fails: quality control or calibration of that run)
    assert f"/{bad}  run {bad}  {probes}:" in tail
    assert "truncated" in tail
    # -k built what does not depend on the bad run: the ball-screw figures, the other runs
    assert (out / "figures" / "bs_fig11.png").exists()
    # the README's way to read a folder of runs sees only runs built from the current data
    assert sorted(p.stem for p in (out / "flap").glob("*.nc")) == runs[1:]


def test_keep_going_builds_every_other_run_and_lists_both_failures(project):
    runs = sorted((project / "raw/small/runs").iterdir())
    (runs[0] / "probes.csv").write_text("time [s],WP1 [V]\n0.0,oops\n")
    flap = runs[1] / "flap.csv"
    flap.write_text(flap.read_text().splitlines()[0] + "\n")
    result = make(project, "-k", "eta/*", "flap/*")
    assert result.returncode == 1
    tail = result.stderr.split("failures (target, run, file: problem):", 1)[1]
    assert f"/{runs[0].name}  run {runs[0].name}  {runs[0] / 'probes.csv'}:" in tail
    assert f"/{runs[1].name}  run {runs[1].name}  {flap}:" in tail
    out = project / "processed/small"
    built_eta = sorted(p.stem for p in (out / "eta").glob("*.nc"))
    assert built_eta == sorted(r.name for r in runs[1:])
    assert (out / "flap" / f"{runs[2].name}.nc").exists()


def test_outputs_honour_the_umask(project):
    import stat

    result = subprocess.run(f"umask 022 && {sys.executable} -m flumekit.cli make --pipeline "
                            "pipelines/small.toml calibration", shell=True, cwd=project,
                            capture_output=True, text=True)
    assert result.returncode == 0, result.stderr
    files = [p for p in (project / "processed/small").rglob("*") if p.is_file()]
    assert len(files) >= 2  # the dataset and the build state
    for f in files:
        mode = stat.S_IMODE(f.stat().st_mode)
        assert mode & 0o044 == 0o044, (f, oct(mode))  # group and others can read


def test_two_concurrent_makes_end_with_a_correct_build_state(project):
    first = _popen(project, "eta/*")
    second = _popen(project, "eta/*")
    out1, err1 = first.communicate(timeout=600)
    out2, err2 = second.communicate(timeout=600)
    assert first.returncode == 0 and second.returncode == 0, err1 + err2
    assert "waiting for the build lock" in err1 + err2
    assert "held by pid" in err1 + err2
    # the builds were not duplicated: the one that waited found everything up to date
    both = (built(subprocess.CompletedProcess([], 0, "", err1)) +
            built(subprocess.CompletedProcess([], 0, "", err2)))
    assert len(both) == len(set(both))
    assert {f"eta/{d.name}" for d in (project / "raw/small/runs").iterdir()} <= set(both)
    assert "nothing to do" in make(project, "-n", "eta/*").stdout


def _children(pid):
    try:
        text = Path(f"/proc/{pid}/task/{pid}/children").read_text()
    except OSError:
        return []
    return [int(x) for x in text.split()]


def _alive(pid):
    try:
        return Path(f"/proc/{pid}/stat").read_text().split(") ")[1][0] != "Z"
    except OSError:
        return False


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="reads /proc")
def test_kill_9_of_a_parallel_driver_leaves_no_worker(project):
    import signal
    import time

    # output to a file, not a pipe: a surviving worker would hold a pipe open forever
    with open(project / "make.log", "w") as log:
        driver = subprocess.Popen([sys.executable, "-m", "flumekit.cli", "make", "--pipeline",
                                   "pipelines/small.toml", "-j", "2", "waves/*", "flap/*"],
                                  cwd=project, stdout=log, stderr=log)
    workers: list[int] = []
    deadline = time.monotonic() + 300
    while time.monotonic() < deadline and len(workers) < 2:
        workers = _children(driver.pid)
        time.sleep(0.2)
    assert len(workers) >= 2, "the pool workers did not start"
    time.sleep(2.0)  # the workers are busy building
    driver.send_signal(signal.SIGKILL)
    driver.wait()
    deadline = time.monotonic() + 20
    while time.monotonic() < deadline and any(_alive(p) for p in workers):
        time.sleep(0.2)
    assert not any(_alive(p) for p in workers), workers
    # the next make cleans the temporaries of the killed build and completes it
    result = make(project, "waves/*", "flap/*")
    assert result.returncode == 0, result.stderr
    assert _temporaries(project / "processed") == []


@pytest.mark.parametrize("jobs, stage", [("1", "qc"), ("2", "qc"), ("1", "uncertainty"),
                                         ("1", "uvp")])
def test_ctrl_c_exits_130_and_leaves_no_temporary_file(project, jobs, stage):
    """Ctrl-C during the first quality-control file, and (serial) while a later stage's target
    (the uncertainty's Monte Carlo, a UVP run: each takes seconds) runs: a serial build once
    hung there when the interrupt landed inside xarray's netCDF writing (its file lock left
    held)."""
    import signal
    import time

    targets = {"qc": ["waves/*", "flap/*"], "uncertainty": ["uncertainty/T3.50_H0.250_r0"],
               "uvp": ["uvp/uvp_z0.300_r0"]}[stage]
    log = open(project / "make.log", "w+")
    driver = subprocess.Popen([sys.executable, "-m", "flumekit.cli", "make", "--pipeline",
                               "pipelines/small.toml", "-j", jobs, *targets],
                              cwd=project, stdout=log, stderr=log, start_new_session=True,
                              # as from a terminal: a test runner started in the background
                              # of a non-interactive shell inherits SIGINT ignored, and a
                              # process that ignores SIGINT rightly never sees Ctrl-C
                              preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))

    def reached() -> bool:
        if stage == "qc":  # as soon as the first file is written: the build takes ~5 s idle
            return (project / "processed/small/qc").exists()
        # the serial build says "[i/n] <target>: <reason>" when a target starts (read through
        # a file description of its own: the child shares the offset of ``log``)
        text = (project / "make.log").read_text()
        return any(line.startswith("[") and f"] {stage}/" in line for line in text.splitlines())

    deadline = time.monotonic() + 600
    while time.monotonic() < deadline and driver.poll() is None and not reached():
        time.sleep(0.05)
    time.sleep(0.3 if stage == "qc" else 0.1)
    assert driver.poll() is None, "the build finished before the interrupt"
    os.killpg(driver.pid, signal.SIGINT)  # what a terminal's Ctrl-C sends: the whole group
    try:
        driver.wait(timeout=60)
    except subprocess.TimeoutExpired:
        driver.kill()
        raise
    log.seek(0)
    err = log.read()
    log.close()
    assert driver.returncode == 130, err
    assert "interrupted" in err and "Traceback" not in err
    assert _temporaries(project / "processed") == []
    assert _temporaries(project / "raw") == []
    if stage != "qc":  # interrupted in the named stage, after what it needs was built
        needs = "eta" if stage == "uncertainty" else "waves"  # what the stage reads
        assert f"] {stage}/" in err and (project / "processed/small" / needs).is_dir()
        assert not any((project / "processed/small").glob(f"{stage}/*.nc"))


def test_unreachable_dask_scheduler_is_a_clear_error_within_its_timeout(project):
    import socket
    import time

    pytest.importorskip("distributed")
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]  # nothing listens there once the socket is closed
    t0 = time.monotonic()
    result = make(project, "calibration", "--scheduler", f"tcp://127.0.0.1:{port}",
                  "--dask-timeout", "3")
    elapsed = time.monotonic() - t0
    assert result.returncode == 1
    assert "cannot reach the Dask scheduler" in result.stderr and "3 s" in result.stderr
    assert "Traceback" not in result.stderr
    assert elapsed < 30, elapsed


# --- determinism, cascade stop, provenance -------------------------------

def test_two_builds_in_different_folders_give_identical_bytes(tmp_path, built_once, small_raw):
    other = _project(tmp_path, small_raw)
    targets = ["calibration", "eta/*", "waves/*", "waves_summary", "figure/fig05a",
               "figure/fig06a", "figure/bs_fig11"]
    result = make(other, *targets)
    assert result.returncode == 0, result.stderr
    files = sorted(p.relative_to(other) for p in (other / "processed").rglob("*")
                   if p.is_file() and p.suffix in (".nc", ".png"))
    assert len(files) >= 2 * 4 + 5
    differ = [str(f) for f in files if (other / f).read_bytes() != (built_once / f).read_bytes()]
    assert differ == []


def test_parameter_that_leaves_the_output_unchanged_rebuilds_nothing_below(built_project):
    """The flap stage's tolerance for encoder samples outside Eq. (1): the virtual runs have
    none, so the flap datasets hold the same data and nothing built from them is rebuilt."""
    project = built_project
    pipe = project / "pipelines" / "small.toml"
    pipe.write_text(pipe.read_text() + "\n[stages.flap]\nmax_flagged_fraction = 0.01\n")
    rebuilt = built(make(project))
    runs = sorted(d.name for d in (project / "raw/small/runs").iterdir())
    assert [t for t in rebuilt if t.startswith("flap/")] == [f"flap/{r}" for r in runs]
    # the uncertainty stage reruns the flap analysis with the flap stage's parameters, so
    # its rules follow them; nothing built from the flap datasets is rebuilt
    unc = ("uncertainty/", "conditions", "figure/uncertainty_budget")
    assert [t for t in rebuilt if not t.startswith(("flap/", *unc))] == []


def test_provenance_names_rule_parameters_inputs_and_versions(built_once):
    import json

    import numpy

    with xr.open_dataset(built_once / "processed/small/flap" / "T3.50_H0.250_r0.nc") as ds:
        attrs = dict(ds.attrs)
    assert attrs["flumekit_rule"] == "flap/T3.50_H0.250_r0"
    assert json.loads(attrs["flumekit_parameters"])["cutoff"] == 4.0
    inputs = json.loads(attrs["flumekit_inputs"])
    raw = built_once / "raw/small/campaign.toml"
    assert inputs["campaign"]["file"] == "../raw/small/campaign.toml"
    assert inputs["campaign"]["sha256"] == hashlib.sha256(raw.read_bytes()).hexdigest()
    assert inputs["waves"]["file"] == "../processed/small/waves/T3.50_H0.250_r0.nc"
    assert len(inputs["waves"]["sha256"]) == 64
    assert f"numpy {numpy.__version__}" in attrs["flumekit_dependencies"]
    assert "flumekit_version" in attrs
    assert str(built_once) not in json.dumps(attrs)  # no absolute path


# --- lazy synthesis ---------------------------------------------------------

def test_a_scene_that_reads_no_raw_data_synthesises_nothing(fresh_project):
    project = fresh_project
    result = make(project, "figure/bs_fig11")
    assert result.returncode == 0, result.stderr
    assert not (project / "raw").exists()
    assert (project / "processed/small/figures/bs_fig11.png").exists()


def test_fig10_plans_the_synthesis_of_one_run(fresh_project):
    project = fresh_project
    result = make(project, "-n", "fig10")
    steps = [line.split()[2].rstrip(":") for line in result.stdout.splitlines()]
    assert [s for s in steps if s.startswith("synth/")] == ["synth/campaign",
                                                            "synth/T3.50_H0.250_r0"]
    assert not (project / "raw").exists()


def test_one_run_synthesised_alone_is_the_run_of_the_whole_campaign(tmp_path, small_raw):
    from flumekit.synth.campaign import write_virtual_base, write_virtual_run

    root = tmp_path / "small"
    write_virtual_base(root, "small", 7)
    write_virtual_run(root, "T2.00_H0.150_r0")
    assert sorted(p.name for p in (root / "runs").iterdir()) == ["T2.00_H0.150_r0"]
    for rel in ("calibration/probes.csv", "runs/T2.00_H0.150_r0/probes.csv",
                "runs/T2.00_H0.150_r0/flap.csv", "runs/T2.00_H0.150_r0/run.toml",
                "truth/T2.00_H0.150_r0/flap.nc"):
        assert (root / rel).read_bytes() == (small_raw / rel).read_bytes(), rel
    with pytest.raises(Exception, match="never writes over"):
        write_virtual_run(root, "T2.00_H0.150_r0")


# --- analyst-ready datasets -------------------------------------------------

def _readme_snippet() -> str:
    text = (ROOT / "README.md").read_text()
    blocks = [b.split("```", 1)[0] for b in text.split("```python")[1:]]
    (snippet,) = [b for b in blocks if "open_processed" in b and "import pandas" not in b]
    return snippet


@pytest.mark.parametrize("stage", ["eta", "waves", "flap", "comparison", "uvp", "qc/probes"])
def test_readme_recipe_keeps_every_run_and_its_coordinates(built_once, stage):
    """The README's one call: every run with its coordinates, and the very dataset that
    xarray's concatenation of the files gives (read with xarray, an independent reader)."""
    import warnings

    from flumekit.io.netcdf import read_dataset

    files = sorted((built_once / "processed/small" / stage).glob("*.nc"))
    assert files
    code = _readme_snippet().replace('"processed/default", "flap"',
                                     f'"{built_once / "processed/small"}", "{stage}"')
    scope: dict = {}
    with warnings.catch_warnings():
        warnings.simplefilter("error", FutureWarning)  # no default that xarray is changing
        exec(code, scope)
    ds = scope["ds"]
    runs = [read_dataset(f) for f in files]
    try:
        expected = xr.concat(runs, dim="run", join="outer", combine_attrs="drop_conflicts",
                             coords="different", compat="equals")
    except xr.MergeError:  # a coordinate differs between runs (the irregular run's probes)
        expected = None
    if expected is not None:
        xr.testing.assert_identical(ds, expected)
    for i, one in enumerate(runs):  # each run's values where its own coordinates put them
        sub = ds.isel(run=i)
        for name, var in one.data_vars.items():
            got = sub[name].sel({d: one[d].values for d in var.dims if d in ds.indexes})
            np.testing.assert_array_equal(got.values, var.values, err_msg=f"{files[i]} {name}")
    if stage.startswith("qc/"):  # QC products carry no run coordinates
        return
    assert ds.sizes["run"] == len(files)
    for i, f in enumerate(files):
        with xr.open_dataset(f) as one:
            for c in ("run", "wave_period", "wave_height", "repeat", "uvp_elevation"):
                got = ds[c].values if ds[c].ndim == 0 else ds[c].values[i]
                assert got == one[c].values or (got != got and one[c].values != one[c].values), (
                    f, c, got, one[c].values)


def test_flap_records_are_stored_as_they_are(built_once):
    """The flap stage's records, which open_processed reads in full for every run, are stored
    contiguous and not deflated: its float records deflate by a third only, and inflating them
    was most of the cost of opening the stage's runs."""
    import netCDF4

    files = sorted((built_once / "processed/small/flap").glob("*.nc"))
    assert files
    for f in files:
        with netCDF4.Dataset(f) as nc:
            records = [v for v in nc.variables.values() if v.dimensions == ("time",)]
            assert len(records) > 20
            for var in records:
                assert var.chunking() == "contiguous", (f.name, var.name)
                assert not any(var.filters()[k] for k in ("zlib", "shuffle", "zstd")), (
                    f.name, var.name)


# --- CF ---------------------------------------------------------------------

def _cf_errors(paths) -> dict[str, list[str]]:
    """The CF 1.8 errors compliance-checker finds in each file (tests/cf_check.py)."""
    import runpy

    return runpy.run_path(str(ROOT / "tests" / "cf_check.py"))["cf_errors"](paths)


def test_every_kind_of_file_has_no_cf_error(built_once):
    pytest.importorskip("compliance_checker")
    out = built_once / "processed/small"
    kinds = ["calibration.nc", "eta/T3.50_H0.250_r0.nc", "waves/T3.50_H0.250_r0.nc",
             "flap/T3.50_H0.250_r0.nc", "comparison/T3.50_H0.250_r0.nc",
             "uvp/uvp_z0.300_r0.nc", "uvp_field.nc", "waves_summary.nc", "flap_summary.nc",
             "comparison_summary.nc", "models/hydro.nc", "ballscrew/kinematics.nc",
             "ballscrew/efficiency.nc", "ballscrew/thermal_lumped.nc",
             "ballscrew/thermal_fem.nc", "qc/probes/T3.50_H0.250_r0.nc",
             "qc/uvp/uvp_z0.300_r0.nc"]
    errors = _cf_errors([out / k for k in kinds])
    assert len(errors) == len(kinds)
    assert {k: e for k, e in errors.items() if e} == {}
    # time in seconds since the record start, read back by flumekit as plain seconds
    from flumekit.io.netcdf import read_dataset

    with xr.open_dataset(out / "eta/T3.50_H0.250_r0.nc", decode_times=False) as ds:
        assert ds["time"].attrs["units"].startswith("seconds since ")
        # the virtual flume's CSV says nothing of the record's start: a stand-in, said so
        assert ds["time"].attrs["record_start"] == "unknown"
    # a UVP beam's time axis counts from its .mfprof header's start (the PC's clock)
    with xr.open_dataset(out / "qc/uvp/uvp_z0.300_r0.nc", decode_times=False) as ds:
        start = ds["time_UP2"].attrs["record_start"]
        assert start != "unknown" and not start.endswith("Z")
        assert ds["time_UP2"].attrs["units"] == f"seconds since {start}"
    assert read_dataset(out / "eta/T3.50_H0.250_r0.nc")["time"].dtype.kind == "f"


@pytest.mark.parametrize("name", sorted(p.name for p in (ROOT / "pipelines").glob("*.toml")))
def test_every_shipped_pipeline_plans_on_a_fresh_clone(fresh_project, name):
    """Each pipeline plans its whole build without writing anything (the small one is built by
    the tests above)."""
    project = fresh_project
    shutil.copy(ROOT / "pipelines" / name, project / "pipelines" / name)
    result = flumekit("make", "-n", "--pipeline", f"pipelines/{name}", cwd=project)
    assert result.returncode == 0, result.stderr
    steps = result.stdout.splitlines()
    assert any(s.startswith("would build synth/campaign") for s in steps)
    assert any(s.startswith("would build figure/fig10") for s in steps)
    assert not (project / "raw").exists() and not (project / "processed").exists()


def test_every_help_is_plain_text_and_describes_every_option():
    """`flumekit --help` and each subcommand's help: no reStructuredText markup, and every
    argument (option or positional) has a description."""
    import argparse
    import re

    from flumekit.cli import parser

    top = parser()
    subs = next(a for a in top._actions if isinstance(a, argparse._SubParsersAction))
    markup = re.compile(r"``|:(func|mod|class|meth|attr):|`[^`]+`_")
    for name, p in [("flumekit", top), *subs.choices.items()]:
        text = p.format_help()
        assert not markup.search(text), (name, markup.search(text).group(0))
        assert p.description, name
        for action in p._actions:
            if isinstance(action, (argparse._HelpAction, argparse._SubParsersAction)):
                continue
            assert action.help and action.help.strip(), (name, action.option_strings or
                                                         action.dest)
