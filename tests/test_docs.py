"""The documentation: gallery scripts run, docstring examples hold, the site builds clean.

The gallery scripts are the files under ``examples/gallery``; each runs here as a notebook
would run it. The real-data ones skip where ``shared/data`` (or a vendored copy) is absent.
The site build needs the ``docs`` extra (Sphinx, numpydoc, sphinx-gallery, myst-parser; part
of the ``test`` extra) and turns every warning into an error.
"""

import doctest
import importlib
import importlib.util
import os
import runpy
import subprocess
import sys
from pathlib import Path

import matplotlib
import pytest

matplotlib.use("Agg")

ROOT = Path(__file__).resolve().parents[1]
GALLERY = ROOT / "examples" / "gallery"
EXAMPLES = sorted(p.name for p in GALLERY.glob("plot_*.py"))
#: real data each example reads (relative to the gallery, where it runs), skipped where absent
NEEDS = {"plot_wavelabx_separation.py": "../wavelabx/wavedata.csv",
         "plot_uvp_file.py": "../../../shared/data/metflow/data_sample.mfprof"}


def _run(name: str, monkeypatch) -> dict:
    monkeypatch.chdir(GALLERY)
    monkeypatch.syspath_prepend(str(GALLERY))
    if name in NEEDS and not (GALLERY / NEEDS[name]).exists():
        pytest.skip(f"{(GALLERY / NEEDS[name]).resolve()} not found")
    import matplotlib.pyplot as plt

    try:
        return runpy.run_path(str(GALLERY / name), run_name="__main__")
    finally:
        plt.close("all")


def test_every_gallery_script_is_tested():
    assert set(EXAMPLES) == {"plot_wavelabx_separation.py", "plot_uvp_file.py",
                             "plot_simulator_run.py", "plot_ballscrew_efficiency.py",
                             "plot_irregular_sea.py"}


@pytest.mark.parametrize("name", EXAMPLES)
def test_gallery_scripts_import_only_public_names(name):
    """A notebook can copy a gallery script: no private module or name, no helper module of
    the gallery's own."""
    import ast

    local = {p.stem for p in GALLERY.glob("*.py")}
    for node in ast.walk(ast.parse((GALLERY / name).read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            mods, names = [a.name for a in node.names], []
        elif isinstance(node, ast.ImportFrom):
            mods, names = [node.module or ""], [a.name for a in node.names]
        else:
            continue
        for mod in mods:
            assert mod.split(".")[0] not in local, (name, mod)
            assert not any(part.startswith("_") for part in mod.split(".")), (name, mod)
            if mod.startswith("flumekit"):
                m = importlib.import_module(mod)
                for n in names:  # a package's public names are its __all__
                    assert not n.startswith("_"), (name, mod, n)
                    assert not hasattr(m, "__all__") or n in m.__all__ or (
                        importlib.util.find_spec(f"{mod}.{n}") is not None), (name, mod, n)


@pytest.mark.parametrize("name", EXAMPLES)
def test_gallery_script_runs(name, monkeypatch):
    _run(name, monkeypatch)


def test_wavelabx_example_gets_the_first_harmonic_kr_without_an_option(monkeypatch):
    g = _run("plot_wavelabx_separation.py", monkeypatch)
    result = g["result"]
    import flumekit

    explicit = flumekit.waves.separate(g["eta"], depth=0.25, x=[0.0, 0.6, 0.9],
                                       sampling_rate=100.0, regular=True, bound_harmonics=True)
    assert result.attrs["regular"] == 1 and result.attrs["regular_detection"].startswith(
        "regular")
    assert float(result.reflection_coefficient) == float(explicit.reflection_coefficient)
    # the separating cell: at most six lines from the imports to the figure, Kr printed
    source = (GALLERY / "plot_wavelabx_separation.py").read_text(encoding="utf-8")
    cell = source[source.index("import pandas"):]
    code = [ln for ln in cell.splitlines() if ln.strip() and not ln.startswith("#")]
    end = code.index("flumekit.plot.separation(result)")
    assert end + 1 <= 6 and any(ln.startswith('print(f"Kr') for ln in code[:end]), code


def test_simulator_example_matches_the_exact_decay(monkeypatch):
    g = _run("plot_simulator_run.py", monkeypatch)
    assert g["error"] < 1e-6  # [rad], of a 0.1 rad decay: fourth-order scheme at dt = 0.01 s


def test_ballscrew_example_efficiency_within_the_papers_range(monkeypatch):
    eta = _run("plot_ballscrew_efficiency.py", monkeypatch)["eta"]
    # Senatore & De Simone (2022), abstract: indirect efficiency from 73 % to 97 %
    assert 0.72 < float(eta.min()) and float(eta.max()) < 0.975


def test_irregular_sea_example_recovers_the_target_sea_state(monkeypatch):
    g = _run("plot_irregular_sea.py", monkeypatch)
    # the synthesised record holds Hm0 = 0.10 m exactly; Welch's taper weighting moves the
    # estimate by ~1 % (tests/waves/test_spectra.py), the peak lies within a bin of 0.5 Hz
    assert float(g["params"].hm0) == pytest.approx(0.10, rel=0.02)
    assert abs(1 / float(g["params"].tp) - 0.5) <= 1.000001 * g["spec"].frequency_resolution
    assert 0.93 < float(g["waves"].h1_3) / float(g["params"].hm0) < 1.0


#: the modules whose docstring examples run as doctests: every module that has one
DOCTESTED = ["flumekit.waves.records", "flumekit.waves.separation",
                                    "flumekit.waves.calibration", "flumekit.waves.spectra",
                                    "flumekit.waves.statistics",
                                    "flumekit.qc.checks", "flumekit.qc.clock",
                                    "flumekit.qc.despike", "flumekit.qc.fill",
                                    "flumekit.qc.flags", "flumekit.qc.qartod",
                                    "flumekit.qc.record",
                                    "flumekit.uncertainty.repeats",
                                    "flumekit.uncertainty.html",
                                    "flumekit.uncertainty.combine",
                                    "flumekit.ballscrew.buoy", "flumekit.ballscrew.ehl",
                                    "flumekit.ballscrew.screw",
                                    "flumekit.ballscrew.scenario",
                                    "flumekit.bench", "flumekit.bench.flume",
                                    "flumekit.bench.truth",
                                    "flumekit.hydro.coefficients", "flumekit.hydro.excitation",
                                    "flumekit.hydro.radiation", "flumekit.hydro.rigid_body",
                                    "flumekit.hydro.response", "flumekit.hydro.bem_layout",
                                    "flumekit.flap.bem", "flumekit.flap.comparison",
                                    "flumekit.flap.summary", "flumekit.flap.power",
                                    "flumekit.flap.torque", "flumekit.flap.encoder",
                                    "flumekit.flap.geometry", "flumekit.flap.pressure",
                                    "flumekit.figures.style", "flumekit.figures.check",
                                    "flumekit.figures.groups", "flumekit.figures.qc",
                                    "flumekit.figures.simulator", "flumekit.figures.separated",
                                    "flumekit.pipeline.cache", "flumekit.pipeline.code",
                                    "flumekit.pipeline.engine", "flumekit.pipeline.executors",
                                    "flumekit.pipeline.raw", "flumekit.pipeline.render",
                                    "flumekit.pipeline.rules",
                                    "flumekit.stages", "flumekit.stages.common",
                                    "flumekit.stages.performance", "flumekit.stages.runs",
                                    "flumekit.lazy", "flumekit.docstrings", "flumekit.units",
                                    "flumekit.scaling",
                                    "flumekit.schema", "flumekit.performance.capture",
                                    "flumekit.performance.matrix",
                                    "flumekit.performance.statistics",
                                    "flumekit.conventions", "flumekit.campaign",
                                    "flumekit.cli",
                                    "flumekit.synth.campaign", "flumekit.synth.flap",
                                    "flumekit.synth.flume", "flumekit.synth.irregular",
                                    "flumekit.synth.uvp", "flumekit.synth.waves",
                                    "flumekit.hydro.simulation", "flumekit.flap.simulator",
                                    "flumekit.figures.registry",
                                    "flumekit.io.atomic", "flumekit.io.netcdf",
                                    "flumekit.io.instruments", "flumekit.io.mfprof",
                                    "flumekit.io.tables", "flumekit.io.dialects",
                                    "flumekit.io.processed", "flumekit.io.run_files",
                                    "flumekit.io.hdf5_headers", "flumekit.waves.steady",
                                    "flumekit.waves.theory", "flumekit.waves.layout",
                                    "flumekit.waves.analysis",
                                    "flumekit.uvp.geometry", "flumekit.uvp.decomposition",
                                    "flumekit.uvp.turbulence", "flumekit.uvp.phase",
                                    "flumekit.uvp.field", "flumekit.flap.friction",
                                    "flumekit.flap.analysis", "flumekit.hydro.capytaine",
                                    "flumekit.hydro.wamit", "flumekit.figures",
                                    "flumekit.figures.waves", "flumekit.figures.flap",
                                    "flumekit.figures.uvp", "flumekit.figures.performance",
                                    "flumekit.pipeline.config", "flumekit.stages.catalogue",
                                    "flumekit.uncertainty.propagation", "flumekit.errors",
                                    "flumekit.hydro.memory", "flumekit.signal",
                                    "flumekit.waves.irregular", "flumekit.waves.stream_function"]


def test_every_module_with_an_example_runs_it():
    """A module whose docstrings hold an example (``>>>``) is in :data:`DOCTESTED`: an example
    nobody runs goes wrong unseen."""
    have = set()
    for path in (ROOT / "flumekit").rglob("*.py"):
        if ">>>" in path.read_text(encoding="utf-8"):
            parts = path.relative_to(ROOT).with_suffix("").parts
            have.add(".".join(parts[:-1] if parts[-1] == "__init__" else parts))
    assert sorted(have - set(DOCTESTED)) == []
    assert sorted(set(DOCTESTED) - have) == []  # no stale entry


@pytest.mark.parametrize("module", DOCTESTED)
def test_docstring_examples(module):
    result = doctest.testmod(importlib.import_module(module), optionflags=doctest.ELLIPSIS)
    assert result.attempted > 0 and result.failed == 0


@pytest.mark.slow
def test_docs_build_without_warnings(tmp_path):
    pytest.importorskip("sphinx")
    pytest.importorskip("numpydoc")
    pytest.importorskip("sphinx_gallery")
    pytest.importorskip("myst_parser")
    # the gallery scripts run above; the build renders their pages without executing them
    env = {**os.environ, "FLUMEKIT_DOCS_RUN_GALLERY": "0", "MPLBACKEND": "Agg"}
    res = subprocess.run([sys.executable, "-m", "sphinx", "-W", "--keep-going", "-E", "-q",
                          "-b", "html", str(ROOT / "docs"), str(tmp_path / "html")],
                         capture_output=True, text=True, env=env, cwd=ROOT)
    assert res.returncode == 0, res.stderr[-4000:]
    assert res.stderr.strip() == ""
    html = tmp_path / "html"
    for page in ("index.html", "getting_started.html", "raw_format.html", "pipeline.html",
                 "physics.html", "api.html", "auto_examples/index.html",
                 "generated/flumekit.waves.separate.html"):
        assert (html / page).is_file(), page
    # the parameter reference holds the code's defaults
    from flumekit.stages.flap import DEFAULTS

    text = (html / "parameters.html").read_text(encoding="utf-8")
    assert "[stages.flap]" in text and all(k in text for k in DEFAULTS)
    assert 'href="parameters.html"' in (html / "pipeline.html").read_text(encoding="utf-8")
    # code blocks wrap: the style sheet is copied and linked from every page
    assert "pre-wrap" in (html / "_static" / "flumekit.css").read_text(encoding="utf-8")
    assert "_static/flumekit.css" in (html / "getting_started.html").read_text(encoding="utf-8")


def test_code_blocks_wrap_or_scroll():
    """The docs' style sheet makes a long code line wrap (or scroll) instead of being cut."""
    import re

    css = (ROOT / "docs" / "_static" / "flumekit.css").read_text(encoding="utf-8")
    rule = re.search(r"div\.highlight pre[^{]*\{([^}]*)\}", css)
    assert rule and "white-space: pre-wrap" in rule.group(1) and "overflow-x: auto" in rule.group(1)
    conf = (ROOT / "docs" / "conf.py").read_text(encoding="utf-8")
    assert 'html_css_files = ["flumekit.css"]' in conf and 'html_static_path = ["_static"]' in conf
