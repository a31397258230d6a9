"""Sphinx configuration of the flumekit documentation (built with warnings as errors).

Sphinx rather than mkdocs: the docstrings are numpydoc, which Sphinx's numpydoc extension
renders natively (Parameters/Returns/References tables, cross-references to numpy and xarray
through intersphinx when online); sphinx-gallery turns plain example scripts into a gallery
whose scripts are the same files the test suite runs; autosummary generates one page per
public function from the packages' ``__all__``.
"""

import os
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(Path(__file__).resolve().parent / "_ext"))

import flumekit  # noqa: E402

project = "flumekit"
author = "flumekit contributors"
copyright = "flumekit contributors, MIT licence"
version = release = flumekit.__version__

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.mathjax",
    "sphinx.ext.viewcode",
    "numpydoc",
    "myst_parser",
    "sphinx_gallery.gen_gallery",
]

source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
exclude_patterns = ["_build", "_ext", "auto_examples/*.ipynb", "auto_examples/*.py",
                    "auto_examples/*.zip", "auto_examples/*.md5", "auto_examples/*.json"]
root_doc = "index"

autosummary_generate = True
autodoc_default_options = {"members": False}
autodoc_typehints = "none"  # types are in the numpydoc sections
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False
# parameter types are prose ("array_like", "xarray.DataArray"); do not try to link each word
numpydoc_xref_param_type = False
numpydoc_validation_checks: set[str] = set()

myst_heading_anchors = 3
suppress_warnings = ["myst.header", "myst.xref_missing"]

# the gallery: examples/gallery/*.py, the same scripts tests/test_docs.py runs. FLUMEKIT_DOCS_
# RUN_GALLERY=0 builds the pages without executing them (the test suite runs them itself)
sphinx_gallery_conf = {
    "examples_dirs": str(ROOT / "examples" / "gallery"),
    "gallery_dirs": "auto_examples",
    "filename_pattern": r"/plot_",
    "plot_gallery": os.environ.get("FLUMEKIT_DOCS_RUN_GALLERY", "1") != "0",
    "download_all_examples": False,
    "remove_config_comments": True,
    "within_subsection_order": "FileNameSortKey",
    "matplotlib_animations": False,
    "abort_on_example_error": True,
    "ignore_pattern": r"(__init__|_data)\.py",
    "write_computation_times": False,
    # pyplot figures, and the pyplot-free Figures flumekit.plot returns (docs/_ext)
    "image_scrapers": ("matplotlib", "figure_scraper"),
}

html_theme = "alabaster"
html_title = f"flumekit {version}"
html_static_path = ["_static"]
# code blocks wrap (or scroll) instead of being cut off at the right of the text column
html_css_files = ["flumekit.css"]
html_theme_options = {"description": "Wave-flume experiments on wave energy converters",
                      "fixed_sidebar": True}


# --- the API reference, generated from the packages' __all__ so it cannot miss a name ------
API_PACKAGES = {
    "flumekit": "Top level: readers and processed data",
    "flumekit.io": "Readers and writers",
    "flumekit.waves": "Waves",
    "flumekit.waves.calibration": "Probe calibration",
    "flumekit.flap": "The flap",
    "flumekit.performance": "Performance in irregular seas",
    "flumekit.uvp": "UVP velocity fields",
    "flumekit.plot": "Figures for notebooks",
    "flumekit.report": "Campaign report",
    "flumekit.qc": "Quality control",
    "flumekit.hydro": "Hydrodynamics of one degree of freedom",
    "flumekit.flap.renzi_dias": "The Renzi-Dias flap model",
    "flumekit.synth": "The virtual flume",
    "flumekit.figures": "The papers' figures",
    "flumekit.ballscrew": "The ball-screw converter",
    "flumekit.ballscrew.thermal": "Thermal models of the ball screw",
    "flumekit.pipeline": "Pipeline internals",
    "flumekit.stages": "Stages (pipeline internals)",
    "flumekit.bench": "Benchmarks",
    "flumekit.uncertainty": "Uncertainty of the results",
}


def _write_api_page(srcdir: Path) -> None:
    import importlib

    lines = ["API reference", "=============", "",
             "Every public name, by package (the names in each package's ``__all__``). Most "
             "functions take numpy arrays, pandas objects or xarray objects; units are in "
             "square brackets in each docstring.", ""]
    for mod_name, heading in API_PACKAGES.items():
        mod = importlib.import_module(mod_name)
        names = [n for n in mod.__all__ if not n.startswith("_")
                 and callable(getattr(mod, n)) and not isinstance(getattr(mod, n), type(mod))]
        lines += [heading, "-" * len(heading), "", f".. automodule:: {mod_name}",
                  "   :no-members:", "", f".. currentmodule:: {mod_name}", "",
                  ".. autosummary::", "   :toctree: generated", ""]
        lines += [f"   {n}" for n in sorted(names)] + [""]
    text = "\n".join(lines)
    page = srcdir / "api.rst"
    if not page.exists() or page.read_text() != text:  # unchanged: no rebuild of everything
        page.write_text(text)


# written when the configuration is read, before autosummary looks for what to generate
_write_api_page(Path(__file__).resolve().parent)
