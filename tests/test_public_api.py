"""Every package states its public names, and the API reference lists every package."""

from __future__ import annotations

import ast
import importlib
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PACKAGES = sorted(".".join(p.parent.relative_to(ROOT).parts)
                  for p in (ROOT / "flumekit").rglob("__init__.py"))


def _api_packages() -> dict:
    """``API_PACKAGES`` of docs/conf.py, read without running Sphinx's configuration."""
    tree = ast.parse((ROOT / "docs" / "conf.py").read_text(encoding="utf-8"))
    for node in tree.body:
        if isinstance(node, ast.Assign) and any(getattr(t, "id", "") == "API_PACKAGES"
                                                for t in node.targets):
            return ast.literal_eval(node.value)
    raise AssertionError("docs/conf.py defines no API_PACKAGES")


def test_the_package_list_is_not_empty():
    assert {"flumekit", "flumekit.qc", "flumekit.hydro", "flumekit.synth"} <= set(PACKAGES)


@pytest.mark.parametrize("package", PACKAGES)
def test_every_package_has_all_and_each_name_resolves(package):
    mod = importlib.import_module(package)
    assert isinstance(getattr(mod, "__all__", None), list | tuple), f"{package}: no __all__"
    assert mod.__all__, package
    for name in mod.__all__:
        assert getattr(mod, name) is not None, f"{package}.{name}"
    assert len(set(mod.__all__)) == len(mod.__all__)


def test_every_package_is_in_the_api_reference():
    missing = sorted(set(PACKAGES) - set(_api_packages()))
    assert missing == []
