"""What the separation figures of regular and irregular runs share: the check and panel (a).

:func:`flumekit.figures.waves.separation` (a regular run) and
:func:`flumekit.figures.sea_state.separation` (an irregular run) both read the incident and
reflected elevations of a separated run and draw them over time in their first panel.
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from flumekit.figures.style import COLOURS, label


def separated_series(waves: xr.Dataset, need, producer: str
                     ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Return the times and the incident and reflected elevations of a separated run.

    Parameters
    ----------
    waves : xarray.Dataset
        A separated run: ``eta_incident``, ``eta_reflected`` [m] over ``time`` [s].
    need : iterable of str
        The variables the figure reads (these two among them).
    producer : str
        The function(s) whose output the figure takes, named in the error.

    Returns
    -------
    time, incident, reflected : numpy.ndarray
        Sample times [s] and the two elevations [m].

    Raises
    ------
    ValueError
        A variable of ``need`` is not in ``waves``.

    Examples
    --------
    >>> import xarray as xr
    >>> from flumekit.figures.separated import separated_series
    >>> separated_series(xr.Dataset({"eta_incident": ("time", [0.1])}),
    ...                  ["eta_incident", "eta_reflected"], "separate")
    Traceback (most recent call last):
    ...
    ValueError: the waves dataset lacks ['eta_reflected']: pass the output of separate
    """
    missing = [n for n in need if n not in waves.variables]
    if missing:
        raise ValueError(f"the waves dataset lacks {missing}: pass the output of {producer}")
    return (waves["time"].values, waves["eta_incident"].values,
            waves["eta_reflected"].values)


def separated_elevations(ax, time, incident, reflected, where: str, lw: float = 1.0) -> None:
    """Draw panel (a) of a separation figure: the incident and reflected elevations over time.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The panel, titled "(a) ``where``".
    time : numpy.ndarray
        Sample times [s] shown, ascending.
    incident, reflected : numpy.ndarray
        Incident and reflected elevation [m] at those times.
    where : str
        Where the waves are separated, for the title.
    lw : float, optional
        Line width [pt].

    Examples
    --------
    >>> import numpy as np
    >>> from flumekit.figures.style import new_figure
    >>> from flumekit.figures.separated import separated_elevations
    >>> fig, axes = new_figure()
    >>> t = np.linspace(0.0, 2.0, 5)
    >>> separated_elevations(axes[0, 0], t, 0.05 * np.sin(t), 0.01 * np.sin(t), "at x = 0 m")
    >>> axes[0, 0].get_title(), [float(x) for x in axes[0, 0].get_xlim()]
    ('(a) at x = 0 m', [0.0, 2.0])
    """
    for name, series in (("incident", incident), ("reflected", reflected)):
        ax.plot(time, series, color=COLOURS[name], lw=lw, label=name)
    ax.set_xlim(time[0], time[-1])
    ax.set_xlabel(label("time", "$t$"))
    ax.set_ylabel(label("eta", r"$\eta$", text="Elevation"))
    ax.set_title(f"(a) {where}")
