"""The second bad-input corpus through the pipeline: a small virtual campaign (two runs of the
default template, 2.0 s and 3.5 s) copied with one fault each, built with ``flumekit make``.
Each case is a clear error naming the run's file and the problem, or the right result; the
raw files are hashed before and after."""

import hashlib
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).parent / "io"))
from virtual_run import RUN

from flumekit.cli import main

OTHER = "T3.50_H0.150_r0"


@pytest.fixture(scope="module")
def campaign(tmp_path_factory):
    """The raw campaign: the run of tests/io/virtual_run.py and a 3.5 s run."""
    from virtual_run import write_one_run

    from flumekit.campaign import load_campaign
    from flumekit.synth.campaign import Truth, _probe_gains, _write_run

    root = tmp_path_factory.mktemp("corpus") / "original"
    write_one_run(root)
    c = load_campaign(root)
    a, b = _probe_gains(c.probes.names, np.random.default_rng(5))
    _write_run(root, c, OTHER, "waves", 3.5, 0.15, 0, None, a, b, Truth(),
               np.random.default_rng(2), 20)
    return root


def _hashes(folder: Path) -> dict[str, str]:
    return {str(p.relative_to(folder)): hashlib.sha256(p.read_bytes()).hexdigest()
            for p in sorted(folder.rglob("*")) if p.is_file()}


def copy(campaign: Path, tmp_path: Path) -> Path:
    root = tmp_path / "raw"
    shutil.copytree(campaign, root)
    (tmp_path / "pipeline.toml").write_text(
        '[pipeline]\nname = "corpus"\nraw = "raw"\nprocessed = "processed"\n')
    return root


def make(tmp_path: Path, *targets: str, capsys=None) -> tuple[int, str]:
    code = main(["make", "--pipeline", str(tmp_path / "pipeline.toml"), *targets])
    if capsys is None:
        return code, ""
    out = capsys.readouterr()
    return code, out.out + out.err


def test_a_flap_record_of_another_run_is_refused(campaign, tmp_path, capsys):
    root = copy(campaign, tmp_path)
    before = _hashes(root)
    shutil.copy(root / "runs" / OTHER / "flap.csv", root / "runs" / RUN / "flap.csv")
    before = _hashes(root)
    code, err = make(tmp_path, f"qc/flap/{RUN}", capsys=capsys)
    assert code == 1
    # the 3.5 s record's period, to the spectral resolution of its 218 s
    assert re.search(rf"runs/{RUN}/flap.csv: dominant period 3\.(49|50)\d s \(encoder counts\)",
                     err)
    assert "declares period 2 s" in err
    assert "Traceback" not in err
    assert _hashes(root) == before
    # the run's own flap record passes
    shutil.copy(campaign / "runs" / RUN / "flap.csv", root / "runs" / RUN / "flap.csv")
    assert make(tmp_path, f"qc/flap/{RUN}")[0] == 0


def test_a_files_entry_outside_the_run_folder(campaign, tmp_path, capsys):
    root = copy(campaign, tmp_path)
    toml = root / "runs" / RUN / "run.toml"
    text = toml.read_text()
    toml.write_text(text + f'\n[files]\nflap = "../{OTHER}/flap.csv"\n')
    code, err = make(tmp_path, f"qc/flap/{RUN}", capsys=capsys)
    assert code == 1
    assert "field 'files.flap'" in err and "lies outside the run folder" in err
    assert 'shared = ["flap"]' in err
    # declared shared on purpose, the flap's own period still tells the records apart
    toml.write_text(text + f'\n[files]\nflap = "../{OTHER}/flap.csv"\nshared = ["flap"]\n')
    code, err = make(tmp_path, f"qc/flap/{RUN}", capsys=capsys)
    assert code == 1 and re.search(rf"runs/{OTHER}/flap.csv: dominant period 3\.(49|50)", err)
    toml.write_text(text + '\n[files]\nshared = ["flapp"]\n')
    code, err = make(tmp_path, f"qc/flap/{RUN}", capsys=capsys)
    assert code == 1 and "unknown instrument 'flapp'" in err and "did you mean" in err


def test_warnings_reach_the_make_summary_the_summaries_and_the_report(campaign, tmp_path,
                                                                      capsys):
    """A declared height 12 % off the measured one (a warning beyond 10 %, an error beyond
    25 %): before, only in each dataset's attribute; now printed, gathered, reported."""
    import xarray as xr

    root = copy(campaign, tmp_path)
    toml = root / "runs" / RUN / "run.toml"
    toml.write_text(toml.read_text().replace("height = 0.15", "height = 0.168"))
    code, err = make(tmp_path, "waves_summary", "flap_summary", capsys=capsys)
    assert code == 0
    lines = err.splitlines()
    k = next(i for i, line in enumerate(lines) if line.startswith("warnings: "))
    assert "flumekit report" in lines[k]
    shown = lines[k + 1:k + 6]
    height = [w for w in shown if "run.height" in w]
    assert len(height) == 1 and f"runs/{RUN}/run.toml" in height[0] and RUN in height[0]
    assert "declared height 0.168 m" in height[0]
    processed = tmp_path / "processed"
    with xr.open_dataset(processed / "waves_summary.nc") as s:
        warned = s.attrs["flumekit_warnings"].splitlines()
    assert any("declared height 0.168 m" in w and RUN in w for w in warned)
    assert not any(OTHER in w and "run.height" in w for w in warned)
    assert main(["report", "--pipeline", str(tmp_path / "pipeline.toml")]) == 0
    page = (processed / "report.html").read_text()
    assert 'id="warnings"' in page and "declared height 0.168 m" in page


# ---- no traceback text: the user's mistakes and a failing machine in one line each ---------

def _cli(*args, cwd) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "flumekit.cli", *args], cwd=cwd,
                          capture_output=True, text=True, timeout=600)


@pytest.mark.parametrize("fault", ["empty_runs", "run_toml_folder", "deep_water"])
def test_campaign_mistakes_are_clear_input_errors(campaign, tmp_path, capsys, fault):
    """Before: "must supply at least one object to concatenate", a raw IsADirectoryError, a
    FloatingPointError with a 60-number array from models/hydro."""
    root = copy(campaign, tmp_path)
    if fault == "empty_runs":
        for d in (root / "runs").iterdir():
            shutil.rmtree(d)
        expect = f"{root / 'runs'}: no run: each run is a folder runs/<run>/"
    elif fault == "run_toml_folder":
        (root / "runs" / RUN / "run.toml").unlink()
        (root / "runs" / RUN / "run.toml").mkdir()
        expect = f"{root / 'runs' / RUN / 'run.toml'}: is a folder, not a file"
    else:
        text = (root / "campaign.toml").read_text()
        (root / "campaign.toml").write_text(re.sub(r"water_depth = [0-9.]+",
                                                   "water_depth = 1e300", text))
        expect = (f"{root / 'campaign.toml'}, field 'flume.water_depth': 1e+300 m is no "
                  "flume's depth")
    before = _hashes(root)
    code, err = make(tmp_path, capsys=capsys)
    assert code == 1
    assert f"flumekit: error: {expect}" in err, err
    assert "Traceback" not in err and len(err.strip().splitlines()) == 1
    assert _hashes(root) == before


def test_a_domain_error_escaping_a_rule_names_the_rule_run_and_inputs(tmp_path, action_module):
    """A numpy message with an array in it: one line, at most 200 characters of it."""
    from flumekit.errors import FlumekitError
    from flumekit.pipeline.engine import Graph
    from flumekit.pipeline.engine import make as build
    from flumekit.pipeline.executors import SerialExecutor
    from flumekit.pipeline.rules import Rule
    from flumekit.pipeline.state import State

    action_module("flumekit_corpus_actions", (
        "import numpy as np\n"
        "def hydro(inputs, outputs, params):\n"
        "    raise FloatingPointError(f'singular at T = {np.linspace(0.25, 15.7, 60)} s')\n"))
    (tmp_path / "campaign.toml").write_text("")
    g = Graph([Rule("models/hydro", "flumekit_corpus_actions:hydro",
                    {"campaign": tmp_path / "campaign.toml"},
                    {"dataset": tmp_path / "out" / "hydro.nc"}, run="T2.00")])
    with pytest.raises(FlumekitError) as e:
        build(g, ["models/hydro"], State(tmp_path / "state.json"), SerialExecutor())
    msg = str(e.value)
    assert "\n" not in msg
    assert msg.startswith("rule 'models/hydro' (run T2.00) failed on its inputs "
                          "(campaign = campaign.toml) and parameters: FloatingPointError: "
                          "singular at T = [ 0.25")
    assert msg.endswith(" ...") and len(msg) < 360


def test_make_reads_its_outputs_before_releasing_the_lock(campaign, tmp_path, monkeypatch):
    """A `flumekit clean` waiting on the lock may remove the outputs as soon as it is free:
    the results and warnings are read while make holds it."""
    import fcntl

    from flumekit import cli

    copy(campaign, tmp_path)
    held = []
    real = cli._results

    def results(graph, report):
        fd = os.open(tmp_path / "processed" / ".flumekit.lock", os.O_RDWR)
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
            held.append(False)
        except BlockingIOError:
            held.append(True)
        finally:
            os.close(fd)
        real(graph, report)

    monkeypatch.setattr(cli, "_results", results)
    assert make(tmp_path, f"waves/{RUN}")[0] == 0
    assert held == [True]


def _mount(folder: Path, options: str) -> bool:
    folder.mkdir(parents=True, exist_ok=True)
    if os.geteuid() != 0:
        return False
    r = subprocess.run(["mount", "-t", "tmpfs", "-o", options, "tmpfs", str(folder)],
                       capture_output=True)
    return r.returncode == 0


def test_a_full_disk_and_a_read_only_processed_folder_are_one_line_each(campaign, tmp_path):
    """On a 256 kB tmpfs, then the same remounted read-only (root only)."""
    disk = tmp_path / "disk"
    if not _mount(disk, "size=256k"):
        pytest.skip("needs root to mount a small tmpfs")
    try:
        copy(campaign, tmp_path)
        (tmp_path / "pipeline.toml").write_text(
            '[pipeline]\nname = "corpus"\nraw = "raw"\nprocessed = "disk/processed"\n')
        r = _cli("make", "--pipeline", "pipeline.toml", cwd=tmp_path)
        assert r.returncode == 1
        assert "Traceback" not in r.stderr, r.stderr
        last = r.stderr.strip().splitlines()[-1]
        assert last.startswith("flumekit: error: ") and "No space left on device" in last
        assert "no space left on the disk of" in r.stderr  # the netCDF library's "HDF error"
        subprocess.run(["umount", str(disk)], check=True)
        assert _mount(disk, "size=64m")
        assert _cli("make", "--pipeline", "pipeline.toml", f"qc/probes/{RUN}",
                    cwd=tmp_path).returncode == 0
        subprocess.run(["mount", "-o", "remount,ro", str(disk)], check=True)
        r = _cli("make", "--pipeline", "pipeline.toml", f"qc/probes/{RUN}", cwd=tmp_path)
        assert r.returncode == 1 and "Traceback" not in r.stderr
        assert r.stderr.strip() == (
            f"flumekit: error: {disk / 'processed' / '.flumekit.lock'}: Read-only file system "
            "(the folder is on a read-only file system: point `processed` of the pipeline "
            "file at a writable folder)")
    finally:
        subprocess.run(["umount", str(disk)], capture_output=True)


CLUSTER = """
import sys
from distributed import LocalCluster
with LocalCluster(n_workers=1, threads_per_worker=1, processes=False, protocol="tcp://",
                  dashboard_address=None) as cluster:
    print(cluster.scheduler_address, flush=True)
    sys.stdin.readline()
"""


def test_a_lost_dask_scheduler_is_one_line(tmp_path):
    """The scheduler's process killed while a rule runs: before, a traceback of
    FuturesCancelledError and the client's logged reconnection tracebacks."""
    import time

    pytest.importorskip("distributed")
    root = Path(__file__).resolve().parents[1]
    shutil.copytree(root / "pipelines", tmp_path / "pipelines")
    cluster = subprocess.Popen([sys.executable, "-c", CLUSTER], stdin=subprocess.PIPE,
                               stdout=subprocess.PIPE, text=True)
    log_path = tmp_path / "make.log"
    build = None
    try:
        address = cluster.stdout.readline().strip()
        with open(log_path, "w") as log:
            build = subprocess.Popen(
                [sys.executable, "-m", "flumekit.cli", "make", "--pipeline",
                 "pipelines/small.toml", "--scheduler", address, "--dask-timeout", "3",
                 "ballscrew/thermal_fem"], cwd=tmp_path, stdout=log, stderr=log)
        deadline = time.monotonic() + 300
        while (time.monotonic() < deadline and build.poll() is None
               and "[1/" not in log_path.read_text()):
            time.sleep(0.05)
        assert build.poll() is None, log_path.read_text()
        cluster.kill()
        build.wait(timeout=120)
    finally:
        if build is not None and build.poll() is None:
            build.kill()
        if cluster.poll() is None:
            cluster.kill()
    err = log_path.read_text()
    assert build.returncode == 1, err
    assert "Traceback" not in err and " ERROR " not in err, err
    assert err.strip().splitlines()[-1].startswith(
        f"flumekit: error: lost the Dask scheduler at {address}")


def test_a_tdms_probe_file_cut_at_a_segment_boundary_is_refused(campaign, tmp_path, capsys):
    """The probes in TDMS, written in 10 segments, the last four lost: before, read without
    complaint (12 steady cycles instead of 66, Kr 0.180 instead of 0.192)."""
    from nptdms import ChannelObject, TdmsWriter

    root = copy(campaign, tmp_path)
    with open(root / "campaign.toml", "a") as f:
        f.write('\n[files.probes]\nfile = "probes.tdms"\nformat = "tdms"\n'
                'group = "Wave probes"\n')
    for run in (RUN, OTHER):
        p = np.loadtxt(root / "runs" / run / "probes.csv", delimiter=",", skiprows=1)
        keep = (6 if run == RUN else 10) * (p.shape[0] // 10)
        with TdmsWriter(root / "runs" / run / "probes.tdms") as w:
            for seg in np.array_split(np.arange(keep), 6 if run == RUN else 10):
                w.write_segment([ChannelObject("Wave probes", n, p[seg, j + 1],
                                               {"unit_string": "V", "wf_increment": 0.04})
                                 for j, n in enumerate(["WP1", "WP2", "WP3", "WP4"])])
    code, err = make(tmp_path, f"flap/{OTHER}", capsys=capsys)
    assert code == 0, err  # the whole record, its time from wf_increment
    code, err = make(tmp_path, f"flap/{RUN}", capsys=capsys)
    assert code == 1
    assert re.search(rf"runs/{RUN}/probes.tdms: the probe record lasts 130\.8 s, the run's "
                     r"other records flap 218\.0 s: more than 20% shorter", err), err
