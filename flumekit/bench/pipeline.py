"""Pipeline benchmark: synthesis, a full build serial and with 2 processes, and the no-op build.

Run time is what the make engine adds or saves; accuracy is not traded here, so the table
reports wall-clock seconds and how many targets ran.
"""

from __future__ import annotations

import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def _make(project: Path, *args: str) -> tuple[float, str]:
    t0 = time.perf_counter()
    r = subprocess.run([sys.executable, "-m", "flumekit.cli", "make", "--pipeline",
                        "pipelines/small.toml", *args], cwd=project, capture_output=True,
                       text=True)
    if r.returncode:
        raise RuntimeError(r.stderr)
    return time.perf_counter() - t0, r.stderr.strip().splitlines()[-1]


def run(quick: bool = False) -> str:
    from flumekit.synth.campaign import write_campaign

    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        project = Path(tmp)
        shutil.copytree(ROOT / "pipelines", project / "pipelines")
        t0 = time.perf_counter()
        write_campaign(project / "raw" / "small", size="small", seed=1)
        rows.append(("synthesise small campaign", time.perf_counter() - t0, ""))
        rows.append(("make (serial, all scenes)", *_make(project)))
        rows.append(("make again (no-op)", *_make(project)))
        if not quick:
            rows.append(("make --force -j 2 (processes)", *_make(project, "--force", "-j", "2")))
            rows.append(("make -n (dry run)", *_make(project, "-n")))
    width = max(len(r[0]) for r in rows)
    lines = [f"{'step':<{width}}  {'wall [s]':>8}  result", "-" * (width + 40)]
    lines += [f"{name:<{width}}  {sec:8.2f}  {msg}" for name, sec, msg in rows]
    return "\n".join(lines)


if __name__ == "__main__":
    print(run())
