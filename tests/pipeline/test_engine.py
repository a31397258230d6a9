"""The make engine on a toy graph: what is rebuilt, what is not, and failures."""

import os
import sys
import textwrap
from pathlib import Path

import pytest

from flumekit.errors import FlumekitError
from flumekit.pipeline.engine import Graph, make, plan
from flumekit.pipeline.executors import PoolExecutor, SerialExecutor
from flumekit.pipeline.rules import Rule
from flumekit.pipeline.state import State

TOY = textwrap.dedent('''
    from pathlib import Path

    def double(inputs, outputs, params):
        v = float(Path(inputs["src"]).read_text()) * params["factor"]
        if v < 0:
            raise ValueError("negative value")
        Path(outputs["out"]).write_text(str(v))

    def total(inputs, outputs, params):
        s = sum(float(Path(p).read_text()) for p in inputs.values())
        Path(outputs["out"]).write_text(str(s))
''')


@pytest.fixture
def toy(tmp_path, action_module):
    action_module("flumekit_toy_actions", TOY)
    raw = tmp_path / "raw"
    raw.mkdir()
    for name, v in (("a", 1), ("b", 2)):
        (raw / f"{name}.txt").write_text(str(v))
    return tmp_path


def graph(root: Path, factor_a: float = 2.0) -> Graph:
    out = root / "processed"
    rules = [
        Rule("double/a", "flumekit_toy_actions:double", {"src": root / "raw/a.txt"},
             {"out": out / "a.txt"}, {"factor": factor_a}),
        Rule("double/b", "flumekit_toy_actions:double", {"src": root / "raw/b.txt"},
             {"out": out / "b.txt"}, {"factor": 2.0}),
        Rule("total", "flumekit_toy_actions:total", {"a": out / "a.txt", "b": out / "b.txt"},
             {"out": out / "total.txt"}),
    ]
    out.mkdir(exist_ok=True)
    return Graph(rules)


def build(root, g=None, targets=("total",), ex=None, **kw):
    g = g or graph(root)
    state = State(root / "processed" / "state.json")
    return make(g, list(targets), state, ex or SerialExecutor(), log=lambda s: None, **kw)


def ran(report):
    return sorted(t for t, _, _ in report.ran)


def test_second_run_rebuilds_nothing(toy):
    assert ran(build(toy)) == ["double/a", "double/b", "total"]
    assert (toy / "processed/total.txt").read_text() == "6.0"
    assert ran(build(toy)) == []


def test_touch_without_change_rebuilds_nothing(toy):
    build(toy)
    st = (toy / "raw/a.txt").stat()
    os.utime(toy / "raw/a.txt", ns=(st.st_atime_ns, st.st_mtime_ns + 10**9))
    assert ran(build(toy)) == []


def test_changed_input_rebuilds_only_its_chain(toy):
    build(toy)
    (toy / "raw/a.txt").write_text("5")
    assert ran(build(toy)) == ["double/a", "total"]
    assert (toy / "processed/total.txt").read_text() == "14.0"


def test_changed_parameter_rebuilds_only_dependants(toy):
    build(toy)
    assert ran(build(toy, graph(toy, factor_a=3.0))) == ["double/a", "total"]


def test_identical_rebuilt_output_stops_propagation(toy):
    build(toy)
    (toy / "processed/a.txt").unlink()  # rebuilt with the same content
    assert ran(build(toy)) == ["double/a"]


def test_scene_runs_only_what_it_needs(toy):
    assert ran(build(toy, targets=["double/b"])) == ["double/b"]
    assert not (toy / "processed/a.txt").exists()


def test_dry_run_says_why(toy):
    g = graph(toy)
    state = State(toy / "processed" / "state.json")
    steps = dict(plan(g, ["total"], state))
    assert steps["double/a"].startswith("output")
    build(toy)
    (toy / "raw/b.txt").write_text("7")
    steps = dict(plan(g, ["total"], State(toy / "processed" / "state.json")))
    assert steps == {"double/b": "input src changed", "total": "input from double/b is rebuilt"}


def test_failed_rule_leaves_no_output_and_names_the_rule(toy):
    build(toy)
    (toy / "raw/a.txt").write_text("-1")
    with pytest.raises(FlumekitError, match=r"double/a.*negative value"):
        build(toy)
    assert not (toy / "processed/a.txt").exists()
    assert (toy / "processed/b.txt").exists()


def test_missing_raw_input_is_named(toy):
    (toy / "raw/b.txt").unlink()
    with pytest.raises(FlumekitError, match=r"raw/b\.txt.*missing"):
        build(toy)


def test_force_rebuilds(toy):
    build(toy)
    assert ran(build(toy, force=True)) == ["double/a", "double/b", "total"]


@pytest.mark.parametrize("kind", ["threads", "processes"])
def test_pool_executor_gives_the_same_result(toy, kind):
    with PoolExecutor(2, kind) as ex:
        assert ran(build(toy, ex=ex)) == ["double/a", "double/b", "total"]
    assert (toy / "processed/total.txt").read_text() == "6.0"


def test_dask_executor(toy):
    distributed = pytest.importorskip("distributed")
    import dask

    from flumekit.pipeline.executors import DaskExecutor

    before = dask.config.get("scheduler", None)
    with distributed.LocalCluster(n_workers=1, processes=False, dashboard_address=None) as cl:
        with DaskExecutor(cl.scheduler_address) as ex:
            assert ran(build(toy, ex=ex)) == ["double/a", "double/b", "total"]
            # the executor leaves dask's global scheduler alone (other dask code in the
            # process must not be routed to this cluster, nor fail once it is closed)
            assert dask.config.get("scheduler", None) == before
    assert (toy / "processed/total.txt").read_text() == "6.0"


def test_cycle_is_refused(tmp_path):
    a, b = tmp_path / "a", tmp_path / "b"
    g = Graph([Rule("x", "m:f", {"i": a}, {"o": b}), Rule("y", "m:f", {"i": b}, {"o": a})])
    with pytest.raises(FlumekitError, match="cycle"):
        g.closure(["x"])


def test_no_heavy_imports_when_planning(tmp_path):
    """Planning a campaign read from its files (every stage's rules, the graph) imports no
    numpy, xarray, scipy, pandas or matplotlib: a no-op make stays cheap, and so does planning
    after a campaign file changed. (A stage's rules importing flumekit.flap for one constant
    once made that planning 20 times slower.)"""
    import subprocess

    from flumekit.synth.campaign import campaign_toml, run_toml, virtual_campaign

    raw = tmp_path / "raw"
    raw.mkdir()
    (raw / "campaign.toml").write_text(campaign_toml("small"))
    for r in virtual_campaign(tmp_path / "unused", "small", 1).runs:  # waves, UVP, irregular
        (raw / "runs" / r.id).mkdir(parents=True)
        sea = None if r.sea_state is None else vars(r.sea_state)
        (raw / "runs" / r.id / "run.toml").write_text(
            run_toml(r.kind, r.period, r.height, r.repeat, r.uvp_elevation, r.probe_x, sea=sea))
    (tmp_path / "p.toml").write_text('[pipeline]\nname = "p"\nraw = "raw"\n'
                                     'processed = "processed"\n')
    code = ("import sys; from flumekit import cli; from flumekit.pipeline.config import "
            "load_pipeline; g = cli._graph(load_pipeline(sys.argv[1])); "
            "assert any(t.startswith('uvp/') for t in g.rules), list(g.rules); "
            "print(sorted(m for m in ('numpy', 'xarray', 'scipy', 'pandas', 'matplotlib') "
            "if m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code, str(tmp_path / "p.toml")],
                         capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == "[]"


def test_stage_choices_repeated_for_planning_agree_with_their_home():
    from flumekit.flap.comparison import LINEAR_PTO_DAMPING
    from flumekit.stages import models

    assert models.LINEAR_PTO_DAMPING == LINEAR_PTO_DAMPING


def test_failed_rebuild_removes_outputs_downstream(toy):
    build(toy)
    assert (toy / "processed/total.txt").exists()
    (toy / "raw/a.txt").write_text("-1")
    with pytest.raises(FlumekitError, match="negative value"):
        build(toy)
    # total.txt was built from the old a.txt: it must not outlive the failed rebuild
    assert not (toy / "processed/a.txt").exists()
    assert not (toy / "processed/total.txt").exists()
    assert (toy / "processed/b.txt").exists()


def test_keep_going_reports_failures_and_blocked_targets(toy):
    (toy / "raw/a.txt").write_text("-1")
    report = build(toy, keep_going=True)
    assert [f.target for f in report.failed] == ["double/a"]
    assert "negative value" in report.failed[0].problem
    assert report.blocked == ["total"]
    assert ran(report) == ["double/b"]


def test_force_one_target_does_not_force_its_inputs(toy):
    build(toy)
    # total is rebuilt; its inputs are not, and an identical output changes nothing else
    assert ran(build(toy, force_targets=["total"])) == ["total"]
    assert ran(build(toy, force_targets=["double/a"])) == ["double/a"]


def test_interrupt_propagates_and_is_not_a_rule_failure(toy, monkeypatch):
    import flumekit.pipeline.rules as rules

    def interrupted(rule, provenance=None):
        raise KeyboardInterrupt

    monkeypatch.setattr("flumekit.pipeline.engine.execute", interrupted)
    with pytest.raises(KeyboardInterrupt):
        build(toy)
    assert rules.execute is not interrupted


def test_dask_cluster_without_workers_is_an_error_within_the_timeout(toy):
    import time

    distributed = pytest.importorskip("distributed")
    from flumekit.pipeline.executors import DaskExecutor

    with distributed.LocalCluster(n_workers=0, processes=False, dashboard_address=None) as cl:
        with DaskExecutor(cl.scheduler_address, timeout=2.0) as ex:
            t0 = time.monotonic()
            with pytest.raises(FlumekitError, match="no worker for 2 s"):
                build(toy, ex=ex)
            assert time.monotonic() - t0 < 20


def test_atomic_writes_honour_the_umask(tmp_path):
    import stat

    from flumekit.io.atomic import atomic_path

    old = os.umask(0o022)
    try:
        with atomic_path(tmp_path / "x.txt") as tmp:
            tmp.write_text("x")
    finally:
        os.umask(old)
    assert stat.S_IMODE((tmp_path / "x.txt").stat().st_mode) == 0o644


def test_ctrl_c_while_a_temporary_is_made_removes_it(tmp_path, monkeypatch):
    # Ctrl-C pressed while atomic_path sets up its temporary (signals masked there, delivered
    # when they are unmasked; at once where another thread lets it through, as in a pytest-xdist
    # worker or a driver with a process pool): the KeyboardInterrupt must find the block that
    # removes the temporary, not leave it beside the output
    import signal

    from flumekit.io import atomic

    real = atomic.umask

    def umask_then_ctrl_c():
        os.kill(os.getpid(), signal.SIGINT)
        return real()

    monkeypatch.setattr(atomic, "umask", umask_then_ctrl_c)
    with pytest.raises(KeyboardInterrupt):
        with atomic.atomic_path(tmp_path / "state.json") as tmp:
            tmp.write_text("{}")
    assert list(tmp_path.iterdir()) == [] and not atomic._ACTIVE


HOLD = textwrap.dedent('''
    import os
    import signal
    import threading
    import time

    from flumekit.io.atomic import atomic_path

    LOCK = threading.Lock()

    def hold(inputs, outputs, params):
        # like xarray writing netCDF: a non-reentrant file lock, taken again by the cleanup; a
        # KeyboardInterrupt raised inside leaves it held and the cleanup waits forever
        with atomic_path(outputs["out"]) as tmp:
            tmp.write_text("partial")
            LOCK.acquire()
            # Ctrl-C once the lock is held, however long the imports and planning took
            threading.Timer(0.3, os.kill, (os.getpid(), signal.SIGINT)).start()
            try:
                time.sleep(60)
            finally:
                with LOCK:
                    LOCK.release()
''')

DRIVER = textwrap.dedent('''
    import signal, sys
    from pathlib import Path
    from flumekit.pipeline.engine import Graph, make
    from flumekit.pipeline.executors import SerialExecutor
    from flumekit.pipeline.rules import Rule
    from flumekit.pipeline.state import State

    out = Path(sys.argv[1])
    signal.signal(signal.SIGINT, signal.default_int_handler)
    g = Graph([Rule("hold", "flumekit_hold:hold", {}, {"out": out / "held.txt"})])
    make(g, ["hold"], State(out / "state.json"),
         SerialExecutor(exit_on_interrupt=sys.argv[2] == "exit"), log=lambda s: None)
''')


@pytest.mark.parametrize("exit_on_interrupt", [True, False])
def test_ctrl_c_inside_a_library_lock_ends_a_serial_cli_build(tmp_path, exit_on_interrupt):
    """The command line's serial build ends at once on Ctrl-C (status 130, the temporary
    removed) even inside library code that a KeyboardInterrupt would leave deadlocked; as a
    library (no exit_on_interrupt) the same build hangs, which is why the CLI does not raise."""
    import subprocess
    import time

    (tmp_path / "flumekit_hold.py").write_text(HOLD)
    out = tmp_path / "out"
    out.mkdir()
    env = {**os.environ, "PYTHONPATH": str(tmp_path) + os.pathsep
           + os.environ.get("PYTHONPATH", "")}
    p = subprocess.Popen([sys.executable, "-c", DRIVER, str(out),
                          "exit" if exit_on_interrupt else "raise"], env=env,
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    t0 = time.monotonic()
    try:
        _, err = p.communicate(timeout=30 if exit_on_interrupt else 4)
    except subprocess.TimeoutExpired:
        p.kill()
        p.communicate()
        assert not exit_on_interrupt, "the interrupted serial build did not end"
        return
    assert exit_on_interrupt, "a KeyboardInterrupt inside the lock should have deadlocked"
    assert p.returncode == 130 and "interrupted" in err and "Traceback" not in err, err
    assert time.monotonic() - t0 < 30
    assert sorted(x.name for x in out.iterdir()) == []  # no output, no temporary, no state
