"""The dependency graph cached between makes: used only while nothing it is
made of changed; a changed or added run file, pipeline parameter or code rebuilds it."""

import os
import shutil
from pathlib import Path

import pytest

from flumekit import cli
from flumekit.pipeline import cache
from flumekit.pipeline.config import load_pipeline
from flumekit.stages import plan

ROOT = Path(__file__).resolve().parents[2]
RUNS = ("T3.50_H0.250_r0", "T4.00_H0.250_r0")


@pytest.fixture
def project(tmp_path, monkeypatch):
    """Campaign and run files of two runs (planning reads no record), and a processed folder."""
    from flumekit.synth.campaign import campaign_toml, run_toml, virtual_campaign

    shutil.copytree(ROOT / "pipelines", tmp_path / "pipelines")
    raw = tmp_path / "raw" / "small"
    raw.mkdir(parents=True)
    (raw / "campaign.toml").write_text(campaign_toml("small"))
    probe_x = virtual_campaign(tmp_path / "unused", "small", 1).runs[0].probe_x
    for rid in RUNS:
        (raw / "runs" / rid).mkdir(parents=True)
        (raw / "runs" / rid / "run.toml").write_text(
            run_toml("waves", float(rid[1:5]), 0.25, 0, None, probe_x))
    (tmp_path / "processed" / "small").mkdir(parents=True)
    monkeypatch.chdir(tmp_path)
    return tmp_path


@pytest.fixture
def builds(monkeypatch):
    """How many times the rules were built rather than read from the cache."""
    calls = []
    real = plan.pipeline_rules

    def counted(pipe, lazy):
        calls.append(1)
        return real(pipe, lazy)

    monkeypatch.setattr(plan, "pipeline_rules", counted)
    return calls


def graph(pipeline="pipelines/small.toml"):
    return plan.pipeline_graph(load_pipeline(pipeline))


def test_an_unchanged_campaign_reads_the_cache_and_gets_the_same_rules(project, builds):
    first = graph()
    assert builds == [1] and (project / "processed/small/.flumekit-graph.pickle").is_file()
    second = graph()
    assert builds == [1]  # read, not built
    assert second.rules == first.rules and list(second.rules) == list(first.rules)
    assert all(second.deps(t) == first.deps(t) for t in first.rules)
    # paths are strings whichever way the graph came, so a build cannot tell the difference
    rule = second.rules[f"waves/{RUNS[0]}"]
    assert all(isinstance(p, str) for p in [*rule.inputs.values(), *rule.outputs.values()])
    assert rule.params_hash() == first.rules[f"waves/{RUNS[0]}"].params_hash()


def test_a_changed_run_file_rebuilds_even_with_its_size_and_time_unchanged(project, builds):
    before = graph().rules[f"waves/{RUNS[0]}"]
    path = project / "raw/small/runs" / RUNS[0] / "run.toml"
    st = path.stat()
    text = path.read_text()
    assert "period = 3.5\n" in text
    path.write_text(text.replace("period = 3.5\n", "period = 3.6\n"))
    os.utime(path, ns=(st.st_atime_ns, st.st_mtime_ns))  # same size, same time: content
    assert path.stat().st_size == st.st_size and path.stat().st_mtime_ns == st.st_mtime_ns
    after = graph().rules[f"waves/{RUNS[0]}"]
    assert builds == [1, 1]
    assert before.params["period"] == 3.5 and after.params["period"] == 3.6


def test_an_added_or_removed_run_rebuilds(project, builds):
    assert not any(RUNS[0].replace("r0", "r1") in t for t in graph().rules)
    runs = project / "raw/small/runs"
    shutil.copytree(runs / RUNS[0], runs / RUNS[0].replace("r0", "r1"))
    assert f"waves/{RUNS[0].replace('r0', 'r1')}" in graph().rules
    shutil.rmtree(runs / RUNS[1])
    assert f"waves/{RUNS[1]}" not in graph().rules
    assert builds == [1, 1, 1]


def test_a_changed_stage_parameter_or_code_rebuilds(project, builds, monkeypatch):
    graph()
    small = project / "pipelines/small.toml"
    small.write_text(small.read_text() + "\n[stages.waves]\nn_harmonics = 2\n")
    assert graph().rules[f"waves/{RUNS[0]}"].params["n_harmonics"] == 2
    assert builds == [1, 1]
    real = cache.code_signature
    monkeypatch.setattr(cache, "code_signature", lambda: [*real(), "another flumekit"])
    graph()
    assert builds == [1, 1, 1]


def test_an_unreadable_cache_is_rebuilt_not_an_error(project, builds):
    graph()
    (project / "processed/small/.flumekit-graph.pickle").write_bytes(b"\x80\x05garbage")
    assert f"waves/{RUNS[0]}" in graph().rules
    assert builds == [1, 1]


# --- the record of an up-to-date make: the next no-op make reads neither graph nor state -------

@pytest.fixture(scope="module")
def ballscrew(tmp_path_factory):
    """A project whose ball-screw figure is built (it reads no raw campaign)."""
    import subprocess
    import sys

    path = tmp_path_factory.mktemp("bs")
    shutil.copytree(ROOT / "pipelines", path / "pipelines")
    r = subprocess.run([sys.executable, "-m", "flumekit.cli", "make", "--pipeline",
                        "pipelines/small.toml", "figure/bs_fig11"], cwd=path,
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    return path


@pytest.fixture
def built(ballscrew, tmp_path, monkeypatch):
    """A copy of the built project (build state included) and the engine's makes in it."""
    import flumekit.pipeline.engine as engine

    path = tmp_path / "p"
    shutil.copytree(ballscrew, path)
    monkeypatch.chdir(path)
    calls = []
    real = engine.make

    def counted(*a, **kw):
        report = real(*a, **kw)
        calls.append(sorted(t for t, _, _ in report.ran))
        return report

    monkeypatch.setattr(engine, "make", counted)
    return path, calls


def make(*targets):
    return cli.main(["make", "-q", "--pipeline", "pipelines/small.toml", *targets])


def test_a_repeated_make_trusts_the_record_until_a_file_changes(built):
    path, calls = built
    out = path / "processed/small"
    # the copy moved every file: the first make checks each target and records the result
    assert make("figure/bs_fig11") == 0 and calls == [[]]
    assert (out / ".flumekit-up-to-date.json").is_file()
    assert make("figure/bs_fig11") == 0 and calls == [[]]  # the record, not the engine
    # another request is not the one recorded
    assert make("ballscrew/kinematics") == 0 and calls == [[], []]
    # a touched output: checked again (its hash is unchanged, nothing is built)
    fig = out / "figures/bs_fig11.png"
    os.utime(fig, ns=(fig.stat().st_atime_ns, fig.stat().st_mtime_ns + 10**9))
    assert make("figure/bs_fig11") == 0 and calls == [[], [], []]
    # a removed intermediate output: rebuilt
    (out / "ballscrew/efficiency.nc").unlink()
    assert make("figure/bs_fig11") == 0 and calls[-1] == ["ballscrew/efficiency"]
    assert make("figure/bs_fig11") == 0 and len(calls) == 4


def test_clean_force_or_a_failed_make_do_not_leave_a_record_to_trust(built, monkeypatch):
    path, calls = built
    stamp = path / "processed/small/.flumekit-up-to-date.json"
    make("figure/bs_fig11")
    assert calls == [[]] and stamp.is_file()
    assert cli.main(["clean", "-q", "--pipeline", "pipelines/small.toml",
                     "ballscrew/efficiency"]) == 0
    # clean forgot the target's build: what it feeds is rebuilt too
    assert make("figure/bs_fig11") == 0
    assert calls[-1] == ["ballscrew/efficiency", "figure/bs_fig11"]
    assert make("-f", "figure/bs_fig11") == 0 and calls[-1] == ["figure/bs_fig11"]
    assert make("figure/bs_fig11") == 0 and stamp.is_file()
    (path / "processed/small/ballscrew/efficiency.nc").unlink()
    monkeypatch.setattr("flumekit.stages.ballscrew.efficiency",
                        lambda inputs, outputs, params: 1 / 0)
    assert make("figure/bs_fig11") == 1
    assert not stamp.exists()
