"""Public names of a package imported on first use (PEP 562).

Importing a package stays cheap: ``import flumekit.qc`` loads no numba, ``import
flumekit.hydro`` no scipy.
"""

from __future__ import annotations

import importlib
from collections.abc import Callable

__all__ = ["lazy_names"]


def lazy_names(package: str, names: dict[str, str], namespace: dict
               ) -> tuple[Callable[[str], object], Callable[[], list[str]]]:
    """Return the module ``__getattr__`` and ``__dir__`` of a package whose names load lazily.

    Parameters
    ----------
    package : str
        The package's ``__name__``.
    names : dict of str to str
        Public name -> the module of ``package`` that defines it.
    namespace : dict
        The package's ``globals()``: a name, once loaded, is kept there.

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
