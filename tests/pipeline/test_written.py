"""The content digest of a written file reaches the engine as the action's return value.

A toy action writes a file whose bytes hold its parameter (as a product's provenance does) and
returns the digest of the data alone: a parameter that changes the bytes but not the data must
rebuild nothing downstream; an action that returns nothing is identified by its bytes.
"""

import hashlib
import os
import textwrap
from pathlib import Path

import pytest

from flumekit.io.atomic import Written
from flumekit.pipeline.engine import Graph, make
from flumekit.pipeline.executors import SerialExecutor
from flumekit.pipeline.rules import Rule, execute, written_digests
from flumekit.pipeline.state import State

TOY = textwrap.dedent('''
    import hashlib
    from pathlib import Path

    from flumekit.io.atomic import Written

    def tagged(inputs, outputs, params):
        data = Path(inputs["src"]).read_text()
        # the bytes carry the parameter (provenance), the digest only the data
        Path(outputs["out"]).write_text(data + "\\n# made with " + str(params["tag"]))
        if params.get("report", True):
            return Written(Path(outputs["out"]), hashlib.sha256(data.encode()).hexdigest())
        return None

    def copy(inputs, outputs, params):
        Path(outputs["out"]).write_text(Path(inputs["src"]).read_text())

    def bad(inputs, outputs, params):
        Path(outputs["out"]).write_text("x")
        return "not a written file"
''')


@pytest.fixture
def toy(tmp_path, action_module):
    action_module("flumekit_written_actions", TOY)
    (tmp_path / "raw").mkdir()
    (tmp_path / "raw/a.txt").write_text("42")
    (tmp_path / "processed").mkdir()
    return tmp_path


def build(root: Path, tag: str, report: bool = True) -> list[str]:
    out = root / "processed"
    g = Graph([
        Rule("tagged", "flumekit_written_actions:tagged", {"src": root / "raw/a.txt"},
             {"out": out / "tagged.txt"}, {"tag": tag, "report": report}),
        Rule("copy", "flumekit_written_actions:copy", {"src": out / "tagged.txt"},
             {"out": out / "copy.txt"}),
    ])
    rep = make(g, ["copy"], State(out / "state.json"), SerialExecutor(), log=lambda s: None)
    return sorted(t for t, _, _ in rep.ran)


def test_a_returned_digest_stops_the_cascade(toy):
    assert build(toy, "one") == ["copy", "tagged"]
    # other bytes, same data: the copy below is not rebuilt
    assert build(toy, "two") == ["tagged"]
    assert "two" in (toy / "processed/tagged.txt").read_text()
    assert "one" in (toy / "processed/copy.txt").read_text()


def test_without_a_returned_digest_the_bytes_decide(toy):
    assert build(toy, "one", report=False) == ["copy", "tagged"]
    assert build(toy, "two", report=False) == ["copy", "tagged"]


def test_execute_returns_the_digests_of_what_the_action_returned(toy):
    out = toy / "processed/tagged.txt"
    rule = Rule("tagged", "flumekit_written_actions:tagged", {"src": toy / "raw/a.txt"},
                {"out": out}, {"tag": "x"})
    _, written = execute(rule)
    assert written == {str(out): hashlib.sha256(b"42").hexdigest()}


def test_an_action_returning_something_else_fails_and_leaves_no_output(toy):
    out = toy / "processed/bad.txt"
    rule = Rule("bad", "flumekit_written_actions:bad", {}, {"out": out})
    with pytest.raises(TypeError, match="not a written file"):
        execute(rule)
    assert not out.exists()


def test_written_digests_of_one_many_or_none():
    a, b = Written(Path("a.nc"), "1" * 64), Written(Path("b.nc"), "2" * 64)
    assert written_digests(None) == {}
    assert written_digests(a) == {"a.nc": "1" * 64}
    assert written_digests([a, b]) == {"a.nc": "1" * 64, "b.nc": "2" * 64}
    assert os.fspath(a) == "a.nc"  # opens as its path


def test_write_dataset_returns_the_content_digest(tmp_path):
    import numpy as np
    import xarray as xr

    from flumekit import conventions
    from flumekit.io.netcdf import read_dataset, write_product

    ds = xr.Dataset({"theta": ("time", np.linspace(0, 1, 5), {"units": "rad"})},
                    coords={"time": ("time", np.arange(5.0), {"units": "s"})})
    first = write_product(ds.copy(), tmp_path / "a.nc", "t", "s", {"p": 1})
    second = write_product(ds.copy(), tmp_path / "b.nc", "t", "s", {"p": 2})
    assert first.path == tmp_path / "a.nc"
    assert first.digest == conventions.content_digest(read_dataset(first))
    # other parameters (provenance), same data: same digest
    assert first.digest == second.digest
