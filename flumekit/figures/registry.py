"""The figures that a pipeline can draw, by name: each figure module registers its own.

A figure module decorates each drawable figure function with :func:`register`, giving its
name and, when the function takes more than one dataset, how to make its arguments from the
datasets a rule reads (``prepare``). The figures stage looks a name up with :func:`figure`
and wires the datasets to it; it knows no figure function and parses no name.

Examples
--------
>>> from flumekit.figures.registry import figure
>>> figure("fig05a").function.__name__
'figure_5a'
"""

from __future__ import annotations

import importlib
import inspect
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any

#: the figure modules that register figures (imported on the first look-up)
MODULES = ("waves", "sea_state", "flap", "performance", "qc", "uvp", "ballscrew", "uncertainty")

Prepare = Callable[[Mapping[str, Any], Mapping[str, Any]], tuple[tuple, dict]]


def one_dataset(data: Mapping[str, Any], params: Mapping[str, Any]) -> tuple[tuple, dict]:
    """Return the arguments of a figure drawn from one dataset: that dataset.

    Parameters
    ----------
    data : mapping of str to xarray.Dataset
        The one dataset its rule reads, by input name.
    params : mapping
        The rule's parameters (unused).

    Returns
    -------
    args : tuple
        ``(dataset,)``.
    kwargs : dict
        Empty.

    Examples
    --------
    >>> one_dataset({"waves": "ds"}, {})
    (('ds',), {})
    """
    (ds,) = data.values()
    return (ds,), {}


@dataclass(frozen=True)
class Figure:
    """A registered figure: its drawing function and how its arguments are made.

    Attributes
    ----------
    name : str
        The name a pipeline gives it (the target ``figure/<name>``, or its prefix).
    function : callable
        Draws it: returns a :class:`matplotlib.figure.Figure`.
    prepare : callable
        ``(datasets by input name, rule parameters) -> (args, kwargs)`` of ``function``.
    stacked : bool
        Its rule's inputs, one small file per run, are read as one dataset stacked along
        ``run`` (in input-name order), given to ``prepare`` as ``{"runs": dataset}``.
    """

    name: str
    function: Callable
    prepare: Prepare = one_dataset
    stacked: bool = False

    def draw(self, data: Mapping[str, Any], params: Mapping[str, Any] | None = None):
        """Draw the figure from the datasets ``data`` read by its rule.

        Parameters
        ----------
        data : mapping of str to xarray.Dataset
            The datasets by input name.
        params : mapping, optional
            The rule's parameters.

        Returns
        -------
        matplotlib.figure.Figure
        """
        args, kwargs = self.prepare(data, params or {})
        return self.function(*args, **kwargs)

    @property
    def description(self) -> str:
        """Say what the figure shows, from its function's docstring, as one line.

        The summary without its imperative verb ("Draw the power matrix" reads "The power
        matrix") and the paragraph after it, if that is prose rather than a numpydoc section.
        """
        blocks = (inspect.getdoc(self.function) or "").split("\n\n")
        text = blocks[0]
        if text.startswith("Draw "):
            text = text[len("Draw "):]
            text = text[:1].upper() + text[1:]  # "(a) the ..." keeps its panel letter
        more = blocks[1].splitlines() if len(blocks) > 1 else []
        if more and not (len(more) > 1 and set(more[1].strip()) == {"-"}):  # not a section
            text += " " + " ".join(more)
        return " ".join(text.split())


FIGURES: dict[str, Figure] = {}


def register(name: str, prepare: Prepare = one_dataset,
             stacked: bool = False) -> Callable[[Callable], Callable]:
    """Register a figure function under ``name`` (a decorator).

    Parameters
    ----------
    name : str
        The figure's name; unique.
    prepare : callable, default :func:`one_dataset`
        How its arguments are made from the datasets its rule reads.
    stacked : bool, default False
        Read the rule's inputs stacked along ``run`` (:attr:`Figure.stacked`): a figure of
        many runs' small datasets, whose opening one by one costs more than drawing it.

    Returns
    -------
    callable
        The decorator. It returns, and registers, the function built in the package style
        (:func:`flumekit.figures.style.styled`), so that a figure drawn by hand looks as the
        pipeline draws it.

    Raises
    ------
    ValueError
        When the decorator is applied, if another function is registered under ``name``.
    """
    def decorate(function: Callable) -> Callable:
        from flumekit.figures.style import styled

        known = FIGURES.get(name)
        if known is not None and known.function.__wrapped__ is not function:
            raise ValueError(f"figure '{name}' registered twice ({known.function.__module__}."
                             f"{known.function.__name__} and {function.__module__}."
                             f"{function.__name__})")
        drawn = known.function if known is not None else styled(function)
        FIGURES[name] = Figure(name, drawn, prepare, stacked)
        return drawn

    return decorate


def figure(name: str) -> Figure:
    """Return the registered figure ``name``, importing the figure modules until one has it.

    In the order of :data:`MODULES`: a figure's worker imports the modules before its own, not
    those after it (the ball-screw figures' models and their imports are not a QC figure's).

    Parameters
    ----------
    name : str
        The figure's registered name, e.g. ``"fig05a"``.

    Returns
    -------
    Figure

    Raises
    ------
    KeyError
        No figure of that name, naming the known ones.
    """
    for module in MODULES:
        if name in FIGURES:
            break
        importlib.import_module(f"flumekit.figures.{module}")
    try:
        return FIGURES[name]
    except KeyError:
        raise KeyError(f"no figure '{name}'; known: {', '.join(sorted(FIGURES))}") from None


def every_figure() -> dict[str, Figure]:
    """Return every registered figure by name (every figure module imported).

    Returns
    -------
    dict of str to Figure

    Examples
    --------
    >>> from flumekit.figures.registry import every_figure
    >>> "qc" in every_figure()
    True
    """
    for module in MODULES:
        importlib.import_module(f"flumekit.figures.{module}")
    return dict(FIGURES)
