"""Public names of a package imported on first use (PEP 562).

Importing a package stays cheap: ``import flumekit.qc`` loads no numba, ``import
flumekit.hydro`` no scipy.
"""

from __future__ import annotations

import importlib
from collections.abc import Callable

from flumekit.docstrings import filler

#: docstring text that several functions of this module share
_doc = filler(
    namespace=("namespace : dict\n"
               "    The package's ``globals()``: a name, once loaded, is kept there."),
    package=("package : str\n"
             "    The package's ``__name__``."))

__all__ = ["attach", "lazy_names"]


@_doc
def lazy_names(package: str, names: dict[str, str], namespace: dict
               ) -> tuple[Callable[[str], object], Callable[[], list[str]]]:
    """Return the module ``__getattr__`` and ``__dir__`` of a package whose names load lazily.

    Parameters
    ----------
    %(package)s
    names : dict of str to str
        Public name -> the module of ``package`` that defines it.
    %(namespace)s

    Returns
    -------
    tuple of callable
        ``(__getattr__, __dir__)`` to assign in the package's ``__init__``.

    References
    ----------
    PEP 562 -- Module __getattr__ and __dir__ (2017).

    Examples
    --------
    >>> from flumekit.lazy import lazy_names
    >>> ns = {}
    >>> getattr_, dir_ = lazy_names("flumekit", {"dominant_period": "qc.checks"}, ns)
    >>> getattr_("dominant_period").__name__, "dominant_period" in ns
    ('dominant_period', True)
    """
    def __getattr__(name: str):
        if name not in names:
            raise AttributeError(f"module {package!r} has no attribute {name!r}")
        value = getattr(importlib.import_module(f"{package}.{names[name]}"), name)
        namespace[name] = value
        return value

    def __dir__() -> list[str]:
        return sorted(set(namespace) | set(names))

    return __getattr__, __dir__


@_doc
def attach(package: str, namespace: dict, **submodule_names: list[str]
           ) -> tuple[Callable[[str], object], Callable[[], list[str]], list[str]]:
    """Return a package's ``__getattr__``, ``__dir__`` and ``__all__``, names grouped by module.

    The form of scientific-python's ``lazy_loader.attach``: each submodule lists the public
    names it defines, and the package's ``__init__`` is one call.

    Parameters
    ----------
    %(package)s
    %(namespace)s
    **submodule_names : list of str
        Submodule of ``package`` -> the public names it defines.

    Returns
    -------
    tuple
        ``(__getattr__, __dir__, __all__)`` to assign in the package's ``__init__``;
        ``__all__`` is the sorted list of every name.

    Raises
    ------
    ValueError
        For a name listed under two submodules.

    References
    ----------
    Scientific Python, SPEC 1 -- Lazy loading of submodules and functions (2022).

    Examples
    --------
    >>> from flumekit.lazy import attach
    >>> getattr_, dir_, all_ = attach("flumekit.qc", {}, checks=["dominant_period"])
    >>> all_, getattr_("dominant_period").__name__
    (['dominant_period'], 'dominant_period')
    """
    names = {name: module for module, listed in submodule_names.items() for name in listed}
    if len(names) != sum(map(len, submodule_names.values())):
        raise ValueError(f"{package}: a public name is listed under two submodules")
    return (*lazy_names(package, names, namespace), sorted(names))
