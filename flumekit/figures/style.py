"""The package figure style and atomic figure saving (used by every figure function)."""

from __future__ import annotations

from contextlib import contextmanager
from pathlib import Path

STYLE = {
    "figure.dpi": 100,
    "savefig.dpi": 150,
    "font.size": 9,
    "axes.grid": True,
    "grid.alpha": 0.3,
    "axes.spines.top": False,
    "axes.spines.right": False,
    "legend.frameon": False,
    "lines.linewidth": 1.2,
}

#: colours by role, so experiment/model/simulator look the same in every figure
COLOURS = {"experiment": "k", "analytical": "tab:blue", "simulator": "tab:red",
           "incident": "tab:blue", "reflected": "tab:orange", "truth": "tab:green"}


@contextmanager
def style():
    import matplotlib

    with matplotlib.rc_context(STYLE):
        yield


def new_figure(nrows: int = 1, ncols: int = 1, **kw):
    """A figure not registered with pyplot (no global state, safe in worker processes)."""
    from matplotlib.figure import Figure

    fig = Figure(layout="constrained", **kw)
    axes = fig.subplots(nrows, ncols, squeeze=False)
    return fig, axes


def figure_axes(ax=None, figsize=(6.5, 2.4)):
    """``(figure, axes)``: those of ``ax`` if given, else a new one-axes figure."""
    if ax is not None:
        return ax.figure, ax
    with style():
        fig, axes = new_figure(figsize=figsize)
    return fig, axes[0, 0]


def save(fig, path: str | Path) -> Path:
    """Write a figure atomically (temporary file in the same folder, then rename)."""
    from flumekit.io.atomic import atomic_path

    with atomic_path(path) as tmp:
        fig.savefig(tmp)
    return Path(path)
