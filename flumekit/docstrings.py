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

__all__ = ["PARAMETERS", "REFERENCES", "SECTIONS", "doc", "fill", "filler"]

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
    "hasselmann1973": (
        "Hasselmann, K. et al. (1973). Measurements of wind-wave growth and swell decay during "
        "the\nJoint North Sea Wave Project (JONSWAP). Dtsch. Hydrogr. Z. A8(12)"),
    "tucker1984": (
        "Tucker, M. J., Challenor, P. G. & Carter, D. J. T. (1984). Numerical simulation of a "
        "random\nsea: a common error and its effect upon wave group statistics. Appl. Ocean "
        "Res. 6(2),\n118-122"),
    "holthuijsen2007": (
        "Holthuijsen, L. H. (2007). Waves in oceanic and coastal waters. Cambridge University "
        "Press"),
    "goring_nikora2002": (
        "Goring, D. G. and Nikora, V. I. (2002). Despiking acoustic Doppler velocimeter data.\n"
        "J. Hydraul. Eng. 128(1), 117-126"),
    "ogilvie1964": (
        "Ogilvie, T. F. (1964). Recent progress toward the understanding and prediction of "
        "ship\nmotions. Proc. 5th Symposium on Naval Hydrodynamics, Bergen, 3-128"),
    "ancellin_dias2019": (
        "Ancellin, M. & Dias, F. (2019). Capytaine: a Python-based linear potential flow "
        "solver.\nJ. Open Source Software 4(36), 1341"),
}

#: parameters documented alike in several modules: key -> the numpydoc entry
PARAMETERS: dict[str, str] = {
    "run_dataset": ("ds : xarray.Dataset\n"
                    "    A run's dataset."),
    "angles": ("angles : array_like\n"
               "    Beam angles above the horizontal [rad], shape (n_beam,)."),
    "bore_area": ("bore_area : float\n"
                  "    Bore area A [m2], > 0."),
    "campaign_run": ("run : flumekit.campaign.Run\n"
                     "    The run."),
    "chamber_pressure": ("chamber_pressure : array_like\n"
                         "    Chamber gauge pressure P_int [Pa]."),
    "contact_angle": ("contact_angle : float\n"
                      "    Contact angle β [rad]."),
    "dataset_output": ("outputs : dict of str to pathlib.Path\n"
                       "    ``dataset``: the file to write."),
    "depth": ("depth : float\n"
              "    Still water depth h [m]."),
    "depth_array": ("depth : array_like\n"
                    "    Still water depth h [m]."),
    "dt": ("dt : float\n"
           "    Time step [s]."),
    "dt_sampling": ("dt : float\n"
                    "    Sampling interval [s]."),
    "eta": ("eta : xarray.DataArray or array_like\n"
            "    Surface elevation [m]: a DataArray with a uniformly sampled ``time`` dimension "
            "[s] and\n"
            "    any other dimensions (``probe``, ``run``, ...), each analysed as one record, or a "
            "1-D\n"
            "    array with ``sampling_rate``. Non-finite samples are an error."),
    "flap_width": ("flap_width : float\n"
                   "    Flap width w [m]."),
    "fluid_inertia": ("fluid_inertia : float\n"
                      "    I_p [Pa s2 rad-1]."),
    "g": ("g : float\n"
          "    Gravitational acceleration [m s-2]."),
    "hydro": ("hydro : xarray.Dataset\n"
              "    Coefficient container (:mod:`flumekit.hydro.coefficients`)."),
    "lead": ("lead : float\n"
             "    Screw lead [m]."),
    "max_iterations": ("max_iterations : int\n"
                       "    Iterations at most."),
    "nut_velocity": ("nut_velocity : float or array_like\n"
                     "    Nut velocity v [m s-1]."),
    "output_step": ("output_step : float, optional\n"
                    "    Output interval [s], a multiple of ``dt`` (default every step)."),
    "path": ("path : pathlib.Path\n"
             "    The file."),
    "period": ("period : float\n"
               "    Wave period [s]."),
    "period_array": ("period : array_like\n"
                     "    Wave period T [s]."),
    "probe_positions": ("x : sequence of float, optional\n"
                        "    Probe positions [m] when ``eta`` does not carry them."),
    "record": ("x : array_like\n"
               "    Record, time along the last axis [any unit]."),
    "rho": ("rho : float\n"
            "    Water density [kg m-3]."),
    "sampling_rate": ("sampling_rate : float\n"
                      "    Sampling rate [Hz]."),
    "sampling_rate_array": ("sampling_rate : float, optional\n"
                            "    Sampling rate [Hz]; required for an array."),
    "sampling_rate_eta": ("sampling_rate : float, optional\n"
                          "    Sampling rate [Hz] when ``eta`` has no time coordinate."),
    "seed": ("seed : int\n"
             "    Random seed of the campaign."),
    "size": ("size : str\n"
             "    Campaign size (\"small\", \"default\", \"paper\")."),
    "target_period": ("period : float\n"
                      "    Target wave period [s]."),
    "theta": ("theta : array_like\n"
              "    Flap angle [rad], positive towards the beach."),
    "theta_dot": ("theta_dot : array_like\n"
                  "    Flap angular velocity [rad s-1]."),
    "time": ("time : numpy.ndarray\n"
             "    Sample times [s]."),
    "time_uniform": ("time : array_like\n"
                     "    Sample times [s], uniform."),
    "wave_height": ("wave_height : float\n"
                    "    Wave height H [m]."),
    "wave_period": ("wave_period : float\n"
                    "    Wave period T [s]."),
}

#: whole numpydoc sections documented alike in several modules: key -> the section
SECTIONS: dict[str, str] = {
    "raises_bore_area": ("Raises\n"
                         "------\n"
                         "ValueError\n"
                         "    A non-positive bore area."),
    # the spectrum of the random sea and the random-phase method that realises it
    "references_random_sea": ("References\n"
                              "----------\n"
                              "%(hasselmann1973)s.\n"
                              "%(tucker1984)s."),
}

_PLACEHOLDER = re.compile(r"%\((\w+)\)s")
#: what every docstring can name: the shared parameters and sections, each citation as ``key``
#: and as a References section opening with it, ``references_key``
_CITATIONS = {**PARAMETERS, **SECTIONS, **REFERENCES,
              **{f"references_{key}": f"References\n----------\n{text}"
                 for key, text in REFERENCES.items()}}


def fill(doc: str | None, snippets: Mapping[str, str] | None = None) -> str | None:
    r"""Replace the ``%(key)s`` placeholders of a docstring by their snippets.

    Parameters
    ----------
    doc : str or None
        The docstring; None (as under ``python -OO``) is returned as it is.
    snippets : mapping of str to str, optional
        Key -> text; default the shared parameters and citations (see :func:`filler`). A
        snippet's second and later lines are indented to the column at which its placeholder
        starts; a snippet may hold placeholders of other snippets. Assigning
        ``__doc__ = fill(__doc__)`` after a module's imports fills the module's own docstring.

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
        # continuation lines align with the placeholder (e.g. the body of a ``.. [2]`` note)
        indent = lead if not lead.strip() else " " * len(lead)
        # a snippet may name other snippets (a section of shared entries)
        return fill(snippets[key], snippets).replace("\n", "\n" + indent)

    return _PLACEHOLDER.sub(one, doc)


def filler(snippets: Mapping[str, str] | None = None, **more: str
           ) -> Callable[[T], T]:
    r"""Return a decorator that fills a function's or class's docstring from snippets.

    Parameters
    ----------
    snippets : mapping of str to str, optional
        Key -> text, usually one dictionary per module.
    **more : str
        Further snippets by keyword. The shared :data:`PARAMETERS` and :data:`SECTIONS` are
        always available, and so is every work of :data:`REFERENCES`: ``%(key)s`` is the
        citation and ``%(references_key)s`` a whole References section opening with it (text
        after the placeholder continues its last line, e.g. the equation cited).

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
