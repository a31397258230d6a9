"""Shared docstring text: placeholders are filled everywhere, and a wrong key fails loudly."""

from __future__ import annotations

import importlib
import inspect
import pkgutil

import pytest

import flumekit
from flumekit.docstrings import PARAMETERS, REFERENCES, SECTIONS, fill, filler


def _public_objects():
    for info in pkgutil.walk_packages(flumekit.__path__, "flumekit."):
        module = importlib.import_module(info.name)
        yield info.name, module
        for name, obj in vars(module).items():
            if (inspect.isfunction(obj) or inspect.isclass(obj)) and \
                    getattr(obj, "__module__", None) == info.name:
                yield f"{info.name}.{name}", obj


def test_no_docstring_in_the_package_keeps_a_placeholder():
    left = [name for name, obj in _public_objects()
            if "%(" in (obj.__doc__ or "") and name != "flumekit.docstrings"
            and not name.startswith("flumekit.docstrings.")]
    assert left == []


def test_a_multi_line_snippet_takes_the_placeholders_indentation():
    doc = "Do.\n\n    Parameters\n    ----------\n    %(depth)s\n    "
    out = fill(doc, {"depth": "depth : float\n    Water depth h [m]."})
    assert out.splitlines()[-3:-1] == ["    depth : float", "        Water depth h [m]."]


def test_an_unknown_key_fails_at_decoration():
    def f():
        """Cite %(nobody1999)s."""

    with pytest.raises(KeyError, match="nobody1999"):
        filler()(f)


def test_the_references_are_always_available():
    @filler()
    def f():
        """Cite %(qartod)s (gross range test)."""

    # the continuation line aligns with the placeholder's column
    assert f.__doc__.startswith("Cite U.S. IOOS (2019)") and "\n     v2.1 (gross" in f.__doc__


def test_no_shared_snippet_shadows_another():
    # one table fills every docstring: a key in two of its sources would silently pick one text
    keys = [*PARAMETERS, *SECTIONS, *REFERENCES, *(f"references_{key}" for key in REFERENCES)]
    assert len(keys) == len(set(keys))
