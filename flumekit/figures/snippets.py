"""Docstring text that several figure modules share, written once.

Each figure module's docstring decorator (:func:`flumekit.docstrings.filler`) takes
:data:`SNIPPETS` beside its own, so a docstring names an entry by its key (the placeholder
syntax of :mod:`flumekit.docstrings`).
"""

from __future__ import annotations

__all__ = ["SNIPPETS"]

#: key -> numpydoc entry: the window of the paper's Fig. 6, shared by Figs. 6a and 6b-d
SNIPPETS: dict[str, str] = {
    "fig6_window": ("start : float, optional\n"
                    "    First t/T shown [-] (the paper: 65).\n"
                    "n_waves : int, optional\n"
                    "    Number of periods shown [-]."),
}
