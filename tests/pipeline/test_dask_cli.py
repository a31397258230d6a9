"""`flumekit make --scheduler` on a real dask.distributed cluster that loses every worker while
the build runs: a clear error within the stated timeout, no traceback,
nothing partial."""

import json
import shutil
import subprocess
import sys
import time
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


#: a cluster of thread workers in a process of its own, reachable over TCP: it prints its
#: address, loses every worker on the first line read from stdin, and closes on the second. Not
#: in pytest's process: the build's rules would run in worker threads here, and once the
#: workers left, xarray in this process kept routing its netCDF write locks to the closed
#: cluster (later tests then failed with "ConnectionPool is closed" or hung on the lock).
CLUSTER = """
import sys
from distributed import LocalCluster
with LocalCluster(n_workers=1, threads_per_worker=1, processes=False, protocol="tcp://",
                  dashboard_address=None) as cluster:
    print(cluster.scheduler_address, flush=True)
    sys.stdin.readline()
    cluster.scale(0)
    print("scaled", flush=True)
    sys.stdin.readline()
"""


def test_a_cluster_that_loses_its_workers_mid_build_is_a_clear_error(tmp_path):
    pytest.importorskip("distributed")
    shutil.copytree(ROOT / "pipelines", tmp_path / "pipelines")
    log_path = tmp_path / "make.log"
    cluster = subprocess.Popen([sys.executable, "-c", CLUSTER], stdin=subprocess.PIPE,
                               stdout=subprocess.PIPE, text=True)
    build = None
    try:
        address = cluster.stdout.readline().strip()
        assert address.startswith("tcp://"), address
        with open(log_path, "w") as log:
            build = subprocess.Popen(
                [sys.executable, "-m", "flumekit.cli", "make", "--pipeline",
                 "pipelines/small.toml", "--scheduler", address,
                 "--dask-timeout", "3", "ballscrew/thermal_fem"],
                cwd=tmp_path, stdout=log, stderr=log)
        deadline = time.monotonic() + 300
        while (time.monotonic() < deadline and build.poll() is None
               and "[1/" not in log_path.read_text()):
            time.sleep(0.05)
        assert build.poll() is None, log_path.read_text()
        cluster.stdin.write("scale\n")  # every worker leaves while the first rule runs or waits
        cluster.stdin.flush()
        assert cluster.stdout.readline().strip() == "scaled"
        t0 = time.monotonic()
        build.wait(timeout=120)
        elapsed = time.monotonic() - t0
    finally:
        if build is not None and build.poll() is None:
            build.kill()
        if cluster.poll() is None:
            try:
                cluster.stdin.write("close\n")
                cluster.stdin.flush()
                cluster.wait(timeout=30)
            except (OSError, subprocess.TimeoutExpired):
                cluster.kill()
    err = log_path.read_text()
    assert build.returncode == 1, err
    assert "has had no worker for 3 s" in err and "Traceback" not in err, err
    assert elapsed < 3 + 15, elapsed  # the timeout, a 1 s poll, and a loaded machine
    out = tmp_path / "processed" / "small"
    assert not [p for p in out.rglob("*") if ".flumekit-tmp" in p.name]
    state = out / ".flumekit-state.json"
    assert not state.exists() or json.loads(state.read_text())["targets"] == {}
    assert not (out / "ballscrew" / "thermal_fem.nc").exists()


def test_an_address_of_another_process_is_a_clear_error(tmp_path):
    pytest.importorskip("distributed")
    shutil.copytree(ROOT / "pipelines", tmp_path / "pipelines")
    r = subprocess.run([sys.executable, "-m", "flumekit.cli", "make", "--pipeline",
                        "pipelines/small.toml", "--scheduler", "inproc://192.0.2.2/1/1",
                        "--dask-timeout", "2", "ballscrew/kinematics"], cwd=tmp_path,
                       capture_output=True, text=True)
    assert r.returncode == 1 and "Traceback" not in r.stderr, r.stderr
    assert "not a Dask scheduler address this process can reach" in r.stderr
