"""Imports cost what they are used for.

``import flumekit.waves`` (and the other analysis packages) must not import the heavy modules
that only some of their functions need (scipy.signal and scipy.stats take seconds each to
import, matplotlib only draws), and the command line must start without numpy. Every worker
process and every notebook pays these imports, so they are checked here in a fresh interpreter:
counted modules, not timings, so the test is deterministic on a loaded machine.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]

#: imported only inside the functions (or figure modules) that use them
HEAVY = ("scipy.signal", "scipy.stats", "scipy.optimize", "matplotlib", "numba", "dask")


def _modules_after(code: str) -> list[str]:
    """Names in sys.modules after running ``code`` in a fresh interpreter of this worktree."""
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join([str(ROOT), env.get("PYTHONPATH", "")]).rstrip(os.pathsep)
    script = f"import sys, json\n{code}\nprint(json.dumps(sorted(sys.modules)))"
    out = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                         env=env, cwd=ROOT)
    assert out.returncode == 0, out.stderr
    return json.loads(out.stdout.strip().splitlines()[-1])


def _heavy(modules: list[str]) -> list[str]:
    return [m for m in modules if any(m == h or m.startswith(h + ".") for h in HEAVY)]


@pytest.mark.parametrize("package", ["flumekit.waves", "flumekit.flap", "flumekit.uvp",
                                     "flumekit.qc", "flumekit.io", "flumekit.hydro",
                                     "flumekit.figures", "flumekit.stages", "flumekit.signal"])
def test_analysis_packages_import_no_heavy_modules(package):
    mods = _modules_after(f"import {package}")
    assert package in mods  # the import happened in the interpreter that was inspected
    assert _heavy(mods) == []


def test_waves_imports_only_its_own_modules_and_the_shared_core():
    mods = [m for m in _modules_after("import flumekit.waves") if m.startswith("flumekit")]
    # the shared core, layer 0 (docstrings: the text several docstrings share, filled at import)
    shared = {"flumekit", "flumekit.errors", "flumekit.conventions", "flumekit.signal",
              "flumekit.units", "flumekit.schema", "flumekit.docstrings"}
    others = [m for m in mods if m not in shared and not m.startswith("flumekit.waves")]
    assert others == []
    # the waves package itself: a dozen modules today; a bound, not an exact count, so that
    # new analysis modules may join without touching this test
    assert len(mods) <= 30


def test_waves_functions_still_reach_scipy_when_called():
    """The lazy imports are real imports: calling a function that filters loads scipy.signal."""
    mods = _modules_after("import numpy as np\nfrom flumekit.signal import lowpass\n"
                          "lowpass(np.zeros(64), 50.0, 5.0)")
    assert "scipy.signal" in mods


def test_cli_version_and_top_package_import_no_numpy():
    for code in ("import flumekit",
                 "from flumekit import cli\ntry:\n    cli.main(['--version'])\n"
                 "except SystemExit:\n    pass"):
        mods = _modules_after(code)
        assert [m for m in mods if m.split(".")[0] in ("numpy", "xarray", "pandas", "scipy")
                ] == [], code
