"""Shared docstring text, written once and filled into the docstrings that use it.

Sibling functions often document the same parameter, the same return value or cite the same
paper. Such text is kept in one dictionary and a docstring names it with a ``%(key)s``
placeholder; the decorator made by :func:`filler` replaces the placeholders when the module
is imported, so ``help()``, the API reference and doctests read the complete numpydoc text.
This is the pattern of SciPy's ``scipy._lib.doccer`` and Matplotlib's ``_docstring``.

A snippet is written without indentation; a multi-line snippet is indented to the column of
its placeholder, so one snippet can stand as a whole numpydoc section or as one entry of a
Parameters section.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Mapping
from typing import TypeVar

__all__ = ["REFERENCES", "doc", "fill", "filler"]

T = TypeVar("T")

#: works the package cites in more than one docstring: key -> the full citation, without its
#: closing punctuation (a docstring adds what it cites of the work: ", Eq. (2).")
REFERENCES: dict[str, str] = {
    "brito2020": (
        "Brito, M., Ferreira, R. M. L., Teixeira, L., Neves, M. G. & Gil, L. (2020). "
        "Experimental\ninvestigation of the flow field in the vicinity of an oscillating "
        "wave surge converter.\nJ. Mar. Sci. Eng. 8"),
    "renzi_dias2012": (
        "Renzi, E. & Dias, F. (2012). Resonant behaviour of an oscillating wave energy "
        "converter in\na channel. J. Fluid Mech. 701, 482-510"),
    "senatore2022": (
        "Senatore, A. and De Simone, A. (2022). Modeling and simulation of a wave energy "
        "converter:\nmultibody system coupled to fluid-film lubrication model and thermal "
        "analysis. Energies 15,\n9358. doi:10.3390/en15249358"),
    "qartod": (
        "U.S. IOOS (2019). QARTOD manual for real-time quality control of in-situ surface "
        "wave data,\nv2.1"),
    "hamrock1991": (
        "Hamrock, B. J. (1991). Fundamentals of fluid film lubrication. NASA RP-1255"),
    "ogilvie1964": (
        "Ogilvie, T. F. (1964). Recent progress toward the understanding and prediction of "
        "ship\nmotions. Proc. 5th Symposium on Naval Hydrodynamics, Bergen, 3-80"),
}

_PLACEHOLDER = re.compile(r"%\((\w+)\)s")
#: what every docstring can name: each citation as ``key`` and as a References section
#: opening with it, ``references_key``
_CITATIONS = {**REFERENCES, **{f"references_{key}": f"References\n----------\n{text}"
                               for key, text in REFERENCES.items()}}


def fill(doc: str | None, snippets: Mapping[str, str] | None = None) -> str | None:
    r"""Replace the ``%(key)s`` placeholders of a docstring by their snippets.

    Parameters
    ----------
    doc : str or None
        The docstring; None (as under ``python -OO``) is returned as it is.
    snippets : mapping of str to str, optional
        Key -> text; default the citations of :data:`REFERENCES` (see :func:`filler`). A
        snippet's second and later lines are indented to the column at which its placeholder
        starts. Assigning ``__doc__ = fill(__doc__)`` after a module's imports fills the
        module's own docstring.

    Returns
    -------
    str or None
        The filled docstring.

    Raises
    ------
    KeyError
        For a placeholder whose key is not in ``snippets``, so that a misspelt key fails at
        import instead of leaving a hole in the documentation.

    Examples
    --------
    >>> from flumekit.docstrings import fill
    >>> print(fill("    x : float\n        %(x)s", {"x": "Abscissa [m].\nNot NaN."}))
        x : float
            Abscissa [m].
            Not NaN.
    """
    if doc is None:
        return None
    snippets = _CITATIONS if snippets is None else snippets

    def one(match: re.Match) -> str:
        key = match.group(1)
        if key not in snippets:
            raise KeyError(f"docstring placeholder %({key})s has no snippet; known: "
                           f"{', '.join(sorted(snippets))}")
        line_start = doc.rfind("\n", 0, match.start()) + 1
        lead = doc[line_start:match.start()]
        indent = lead if not lead.strip() else lead[:len(lead) - len(lead.lstrip())]
        return snippets[key].replace("\n", "\n" + indent)

    return _PLACEHOLDER.sub(one, doc)


def filler(snippets: Mapping[str, str] | None = None, **more: str
           ) -> Callable[[T], T]:
    r"""Return a decorator that fills a function's or class's docstring from snippets.

    Parameters
    ----------
    snippets : mapping of str to str, optional
        Key -> text, usually one dictionary per module.
    **more : str
        Further snippets by keyword. :data:`REFERENCES` is always available: ``%(key)s``
        is the citation and ``%(references_key)s`` a whole References section opening with
        it (text after the placeholder continues its last line, e.g. the equation cited).

    Returns
    -------
    callable
        Decorator that replaces the object's ``__doc__`` by the filled text (:func:`fill`)
        and returns the object itself.

    References
    ----------
    SciPy's ``scipy._lib.doccer`` (``docformat``) and Matplotlib's ``_docstring.Substitution``,
    the same pattern.

    Examples
    --------
    >>> from flumekit.docstrings import filler
    >>> doc = filler(depth="depth : float\n    Water depth h [m].")
    >>> @doc
    ... def f(depth):
    ...     '''Do nothing.
    ...
    ...     Parameters
    ...     ----------
    ...     %(depth)s
    ...     '''
    >>> print(f.__doc__.splitlines()[-2].strip())
    Water depth h [m].
    """
    table = {**_CITATIONS, **(snippets or {}), **more}

    def decorate(obj: T) -> T:
        obj.__doc__ = fill(obj.__doc__, table)
        return obj

    return decorate


#: the decorator of a module that needs no snippets of its own: the citations only
doc = filler()
