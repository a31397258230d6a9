"""A rule's key holds the hash of the code its action runs (flumekit.pipeline.code): a change of
that code rebuilds the target, a change elsewhere does not."""

import textwrap
from pathlib import Path

import pytest

from flumekit.pipeline import code
from flumekit.pipeline.engine import Graph, make
from flumekit.pipeline.executors import SerialExecutor
from flumekit.pipeline.rules import Rule
from flumekit.pipeline.state import State


@pytest.fixture
def package(tmp_path, monkeypatch):
    """A small stand-in for the flumekit package: a stage, its domain package (a facade over
    two modules), a shared module, an unrelated one, and a stage that picks a module by name."""
    root = tmp_path / "flumekit"
    files = {
        "__init__.py": '__version__ = "1"\nfrom flumekit import everything  # not followed\n',
        "shared.py": "X = 1\n",
        "unrelated.py": "Y = 2\n",
        "stages/__init__.py": "",
        "stages/toy.py": textwrap.dedent("""
            from flumekit.shared import X

            def build(inputs, outputs, params):
                from flumekit import __version__
                from flumekit.toy import run  # a name of the facade
                return run(X)
        """),
        "stages/pick.py": textwrap.dedent("""
            import importlib

            def draw(inputs, outputs, params):
                return importlib.import_module(f"flumekit.figs.{params['m']}")
        """),
        "toy/__init__.py": "from flumekit.toy.model import run\n",
        "toy/model.py": "from flumekit.toy import (  # a submodule\n    helper,\n)\n"
                        "def run(x): return x\n",
        "toy/helper.py": "Z = 3\n",
        "other/__init__.py": "",
        "other/deep.py": "from flumekit.other import (\n    near,\n    far as f,\n)\n",
        "other/near.py": "",
        "other/far.py": "",
        "figs/__init__.py": "",
        "figs/a.py": "A = 1\n",
    }
    for rel, text in files.items():
        (root / rel).parent.mkdir(parents=True, exist_ok=True)
        (root / rel).write_text(text)
    monkeypatch.setattr(code, "PACKAGE_DIR", str(root))
    code._imports.cache_clear()
    code.code_hash.cache_clear()
    yield root
    code._imports.cache_clear()
    code.code_hash.cache_clear()


def fresh(action):
    code._imports.cache_clear()
    code.code_hash.cache_clear()
    return code.code_hash(action)


def test_the_closure_follows_function_imports_facades_and_named_modules(package):
    assert code.closure("flumekit.stages.toy") == [
        "flumekit", "flumekit.shared", "flumekit.stages.toy", "flumekit.toy",
        "flumekit.toy.helper", "flumekit.toy.model"]
    assert code.closure("flumekit.stages.pick") == ["flumekit.figs.a", "flumekit.stages.pick"]
    # submodules imported from a package in parentheses: they, not the package
    assert code.closure("flumekit.other.deep") == ["flumekit.other.deep", "flumekit.other.far",
                                                   "flumekit.other.near"]


@pytest.mark.parametrize("changed, rebuilds", [
    ("stages/toy.py", True),  # the stage module
    ("toy/model.py", True),  # the domain function's module, reached through the facade
    ("toy/helper.py", True),  # what that module imports
    ("shared.py", True),  # a module-level import of the stage
    ("__init__.py", True),  # the version
    ("unrelated.py", False),
    ("figs/a.py", False),
])
def test_a_change_rebuilds_only_what_reaches_it(package, changed, rebuilds):
    before = fresh("flumekit.stages.toy:build")
    assert len(before) == 64
    with open(package / changed, "a") as f:
        f.write("# changed\n")
    assert (fresh("flumekit.stages.toy:build") != before) == rebuilds


def test_actions_outside_the_package_are_not_tracked(package):
    assert fresh("my_lab_actions:build") == ""


def test_the_real_stages_reach_their_domain_modules_and_not_the_command_line():
    code._imports.cache_clear()
    reach = code.closure("flumekit.stages.waves")
    assert {"flumekit.stages.waves", "flumekit.waves.analysis", "flumekit.stages.runs",
            "flumekit.io.netcdf"} <= set(reach)
    assert not any(m == "flumekit.cli" or m.startswith("flumekit.bench") for m in reach)
    figures = code.closure("flumekit.stages.figures_run")  # the figure rules' action
    assert "flumekit.figures.flap" in figures  # chosen by a parameter, named in a string


TOY = textwrap.dedent('''
    from pathlib import Path

    def copy(inputs, outputs, params):
        Path(outputs["out"]).write_text(Path(inputs["src"]).read_text())
''')


def test_the_engine_rebuilds_a_target_whose_code_changed(tmp_path, monkeypatch, action_module):
    action_module("flumekit_code_actions", TOY)
    (tmp_path / "a.txt").write_text("1")
    source = {"hash": "A"}
    monkeypatch.setattr(code, "code_hash", lambda action: source["hash"])

    def build() -> list[tuple[str, str]]:
        g = Graph([Rule("copy", "flumekit_code_actions:copy", {"src": tmp_path / "a.txt"},
                        {"out": tmp_path / "b.txt"})])
        rep = make(g, ["copy"], State(tmp_path / "state.json"), SerialExecutor(),
                   log=lambda s: None)
        return [(t, reason) for t, reason, _ in rep.ran]

    assert build() == [("copy", "output out missing")]
    assert build() == []
    source["hash"] = "B"
    assert build() == [("copy", "code of flumekit_code_actions (or a module it imports) "
                                "changed")]
    assert build() == []
    assert Path(tmp_path / "b.txt").read_text() == "1"
