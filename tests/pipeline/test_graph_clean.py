"""`flumekit graph` and `flumekit clean` on the ball-screw scene, which
needs no raw campaign: planning writes nothing, clean removes exactly the named outputs."""

import shutil
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def _flumekit(*args, cwd):
    return subprocess.run([sys.executable, "-m", "flumekit.cli", *args, "--pipeline",
                           "pipelines/small.toml"], cwd=cwd, capture_output=True, text=True)


def test_graph_names_every_edge_and_writes_nothing(tmp_path):
    shutil.copytree(ROOT / "pipelines", tmp_path / "pipelines")
    dot = _flumekit("graph", "figure/bs_fig11", cwd=tmp_path)
    assert dot.returncode == 0, dot.stderr
    labels = dict(line.strip().rstrip("];").split(" [label=") for line in dot.stdout.splitlines()
                  if "[label=" in line)
    names = {k: v.strip('"') for k, v in labels.items()}
    edges = {(names[a], names[b]) for a, _, b in
             (line.strip().rstrip(";").partition(" -> ") for line in dot.stdout.splitlines()
              if " -> " in line)}
    assert edges == {("ballscrew/kinematics", "ballscrew/efficiency"),
                     ("ballscrew/efficiency", "figure/bs_fig11")}
    mermaid = _flumekit("graph", "figure/bs_fig11", "--format", "mermaid", cwd=tmp_path)
    assert mermaid.stdout.startswith("flowchart LR") and mermaid.stdout.count("-->") == 2
    assert sorted(p.name for p in tmp_path.iterdir()) == ["pipelines"]  # no raw, no processed


def test_clean_removes_only_the_named_outputs(tmp_path):
    shutil.copytree(ROOT / "pipelines", tmp_path / "pipelines")
    built = _flumekit("make", "figure/bs_fig11", cwd=tmp_path)
    assert built.returncode == 0, built.stderr
    out = tmp_path / "processed" / "small"
    kept = [out / "ballscrew" / "kinematics.nc", out / "figures" / "bs_fig11.png"]
    assert (out / "ballscrew" / "efficiency.nc").exists() and all(p.exists() for p in kept)
    r = _flumekit("clean", "ballscrew/efficiency", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    assert not (out / "ballscrew" / "efficiency.nc").exists()
    assert all(p.exists() for p in kept)
    again = _flumekit("make", "-n", "figure/bs_fig11", cwd=tmp_path)
    assert "ballscrew/efficiency" in again.stdout  # the cleaned target is due again
