"""The quality-control figure of one run: every channel as read, as QC'd, and what each flag marks.

Every probe and flap channel; for a UVP run, the beams' flags over time and per channel. The
flags are those of QARTOD (U.S. IOOS, 2020): pass, not evaluated, suspect, fail, missing.

References
----------
U.S. Integrated Ocean Observing System (2020). Manual for Real-Time Quality Control of In-situ
Data: a guide to QARTOD, Version 1.0.
"""

from __future__ import annotations

import numpy as np

from flumekit.figures.registry import register
from flumekit.figures.style import TWO_COLUMNS, new_figure, thin, units_text
from flumekit.qc.flags import FAIL, MISSING, NOT_EVALUATED, SUSPECT

#: marker colours of the QARTOD flags drawn (pass and not-evaluated samples are not marked)
FLAG_STYLE = {SUSPECT: ("suspect", "tab:orange", "o"), FAIL: ("fail", "tab:red", "x"),
              MISSING: ("missing", "tab:purple", "|")}
#: what each QC test of flumekit.qc.record.check_series flags, shortly (the panel of a channel
#: says it of the tests that flagged its samples)
TEST_MEANINGS = {
    "gap": "time gap",
    "gross_range": "out of range",
    "spike": "spike",
    "rate_of_change": "steep step",
    "flat_line": "flat line",
    "dropout": "dropout or held value",
    # lag-one autocorrelation below [stages.qc] noise_autocorrelation, with high-frequency
    # energy above noise_share of the channel's (flumekit.qc.qartod.noise_test)
    "noise": "noise, not signal",
}


def flag_summary(flags, index: int | None = None) -> str:
    """Summarise a flag variable of the qc stage as ``<test> <count> (<what it flags>), ...``.

    From its ``flagged_by_<test>`` attributes and :data:`TEST_MEANINGS`; the tests that
    flagged nothing are left out.

    Parameters
    ----------
    flags : xarray.DataArray
        A flag variable of the qc stage.
    index : int, optional
        The channel of a per-channel count.

    Returns
    -------
    str
        The summary, empty when nothing was flagged.

    Examples
    --------
    >>> import xarray as xr
    >>> from flumekit.figures.qc import flag_summary
    >>> flags = xr.DataArray([0], attrs={"flagged_by_gap": 3, "flagged_by_spike": 0})
    >>> flag_summary(flags)
    'gap 3 (time gap)'
    """
    parts = []
    for key, v in flags.attrs.items():
        if key.startswith("flagged_by_"):
            n = int(np.atleast_1d(v)[0 if index is None else index])
            test = key.removeprefix("flagged_by_")
            if n:
                parts.append(f"{test} {n}" + (f" ({TEST_MEANINGS[test]})"
                                              if TEST_MEANINGS.get(test, test) != test
                                              else ""))
    return ", ".join(parts)


#: line colours of the UVP beams
BEAM_COLOURS = ("tab:blue", "tab:green", "tab:brown", "tab:pink", "tab:olive", "tab:cyan")


def _channels(probes, flap, probes_raw, flap_raw):
    out = []
    # voltages to calibrate, or the elevations of calibrated probes
    name, units = (("probe_voltage", "V") if "probe_voltage" in probes
                   else ("probe_elevation", "m"))
    for p in probes["probe"].values:
        sel = {"probe": p}
        raw = None if probes_raw is None else probes_raw[name].sel(sel).values
        k = list(probes["probe"].values).index(p)
        out.append((str(p), probes["time"].values, raw, probes[name].sel(sel).values,
                    probes[f"{name}_qc"].sel(sel).values, units,
                    flag_summary(probes[f"{name}_qc"], k)))
    if flap is not None:
        for name, label, units in (("encoder_counts", "encoder", "counts"),
                                   ("chamber_pressure", "pressure", "Pa")):
            raw = None if flap_raw is None else flap_raw[name].values.astype(float)
            out.append((label, flap["time"].values, raw, flap[name].values,
                        flap[f"{name}_qc"].values, units, flag_summary(flap[f"{name}_qc"])))
    return out


def _uvp_beams(uvp):
    """Per beam: (name, time [s], channels x time flags)."""
    return [(str(b), uvp[f"time_{b}"].values,
             uvp[f"beam_velocity_qc_{b}"].transpose("channel", ...).values)
            for b in uvp["beam"].values]


def _draw_uvp(ax_time, ax_bin, uvp) -> None:
    """Draw the failed fraction of each beam's channels per profile and per channel.

    Over time (per profile) and per bin (of each channel's evaluated samples), from the flags
    of the qc stage.
    """
    totals = []
    for (name, t, f), colour in zip(_uvp_beams(uvp), BEAM_COLOURS, strict=False):
        failed = f == FAIL
        evaluated = (f != NOT_EVALUATED) & (f != MISSING)
        per_profile = failed.sum(axis=0) / np.maximum(evaluated.sum(axis=0), 1)
        inside = evaluated.any(axis=0)
        ax_time.plot(t[inside], 100 * per_profile[inside], color=colour, lw=0.6,
                     label=f"beam {name}")
        per_bin = failed.sum(axis=1) / np.maximum(evaluated.sum(axis=1), 1)
        ax_bin.plot(np.arange(f.shape[0]), 100 * per_bin, color=colour, lw=0.8)
        totals.append(f"{name} {int(failed.sum())}")
    lo, hi = uvp["evaluated_span"].values
    ax_time.set_title(f"UVP, checked {lo:.1f}-{hi:.1f} s, failed: " + ", ".join(totals),
                      loc="left")
    ax_time.set_ylabel("Failed [%]")
    ax_bin.set_title("UVP: failed share of each channel's evaluated samples", loc="left")
    ax_bin.set_ylabel("Failed [%]")
    ax_bin.set_xlabel("UVP channel (bin) [-]")


def _figure_qc_data(data, params) -> tuple[tuple, dict]:
    """Return the arguments of the QC figure: its datasets by keyword.

    QC products and raw records; the probes' product is labelled with the rule's run (the
    products carry no run coordinate).
    """
    return (), {**data, "probes": data["probes"].assign_coords(run=params["run"])}


@register("qc", prepare=_figure_qc_data)
def figure_qc(probes, flap=None, *, probes_raw=None, flap_raw=None, uvp=None):
    """Draw the QC'd records (black) of every probe and flap channel of a run, and as read (grey).

    The records as read are drawn where quality control changed them. The suspect, failed and
    missing samples are marked at their raw values with the tests that flagged them (counts
    and what each flags in the channel's title); with ``uvp``, two panels more: the share of
    each beam's channels that failed per profile, over time, and the share of each channel's
    evaluated samples that failed.

    Parameters
    ----------
    probes : xarray.Dataset
        Dataset of the qc stage for the probes (``probe_voltage`` [V] and ``_qc``).
    flap : xarray.Dataset, optional
        Dataset of the qc stage for the encoder and pressure.
    probes_raw, flap_raw : xarray.Dataset, optional
        The raw records as read by the instrument readers (the QC products do not repeat
        them); None: only the QC'd values are drawn.
    uvp : xarray.Dataset, optional
        Dataset of the qc stage for the UVP beams (``beam_velocity_qc_<beam>``).

    Returns
    -------
    matplotlib.figure.Figure
        One panel per channel (in its units) against time [s].

    References
    ----------
    U.S. Integrated Ocean Observing System (2020). Manual for Real-Time Quality Control of
    In-situ Data: a guide to QARTOD, Version 1.0.

    Examples
    --------
    A probe record with one spike, through the QC of the qc stage: the panel names the tests
    that flagged it and draws the record as read (grey) where QC changed it:

    >>> import numpy as np
    >>> import xarray as xr
    >>> from flumekit.figures import figure_qc
    >>> from flumekit.qc import Thresholds, qc_dataset
    >>> t = np.arange(2000) / 100.0  # [s]
    >>> volts = np.sin(np.pi * t)
    >>> volts[700] += 1.0
    >>> raw = xr.Dataset({"probe_voltage": (("probe", "time"), [volts])},
    ...                  coords={"probe": ["WP1"], "time": t})
    >>> probes = qc_dataset(raw, "probe_voltage", Thresholds(), channel_dim="probe")
    >>> named = probes.assign_coords(run="T2.00_H0.100_r0")  # products carry no run name
    >>> fig = figure_qc(named, probes_raw=raw)
    >>> fig.get_suptitle()
    'Quality control of run T2.00_H0.100_r0'
    >>> print(fig.axes[0].get_title(loc="left"))
    WP1: 1 suspect, 1 fail, 0 missing; flagged by spike 1, rate_of_change 2 (steep step)
    >>> [text.get_text() for text in fig.legends[0].get_texts()]
    ['as read', 'after QC', 'suspect', 'fail']
    """
    chans = _channels(probes, flap, probes_raw, flap_raw)
    rows = len(chans) + (2 if uvp is not None else 0)
    fig, axes = new_figure(rows, 1, width=TWO_COLUMNS, row_height=1.0)
    run = str(probes["run"].values) if "run" in probes.coords else ""
    time_axes = axes[:len(chans) + (1 if uvp is not None else 0), 0]
    for ax in time_axes[1:]:
        ax.sharex(time_axes[0])
    for ax in time_axes[:-1]:
        ax.tick_params(labelbottom=False)
    for ax, (label, t, raw, clean, flags, units, by) in zip(axes[:, 0], chans, strict=False):
        shown = clean if raw is None else raw
        if raw is not None:
            # the record as read only where quality control changed it (and the samples
            # either side, to join it to the line): elsewhere it lies under the QC'd line
            changed = ~((raw == clean) | (np.isnan(raw) & np.isnan(clean)))
            if changed.any():
                near = changed.copy()
                near[1:] |= changed[:-1]
                near[:-1] |= changed[1:]
                ax.plot(*thin(t, np.where(near, raw, np.nan), fig.get_figwidth()),
                        color="0.7", lw=0.6, label="as read")
        ax.plot(*thin(t, clean, fig.get_figwidth()), color="k", lw=0.5, label="after QC")
        counts = []
        for value, (meaning, colour, marker) in FLAG_STYLE.items():
            sel = flags == value
            counts.append(f"{int(sel.sum())} {meaning}")
            if sel.any():
                y = np.where(np.isfinite(shown[sel]), shown[sel], np.nanmedian(shown))
                ax.plot(t[sel], y, ls="none", marker=marker, color=colour, ms=3, mew=0.8,
                        label=meaning)
        ax.set_ylabel(f"[{units_text(units)}]")
        ax.set_title(f"{label}: " + ", ".join(counts) + (f"; flagged by {by}" if by else ""),
                     loc="left")
    if uvp is not None:
        _draw_uvp(axes[len(chans), 0], axes[-1, 0], uvp)
    time_axes[-1].set_xlabel("Time [s]")
    handles = {}
    for ax in axes[:, 0]:
        for h, lab in zip(*ax.get_legend_handles_labels(), strict=True):
            handles.setdefault(lab, h)
    fig.legend(list(handles.values()), list(handles), loc="outside lower center",
               ncols=min(len(handles), 7))
    fig.suptitle(f"Quality control of run {run}" if run else "Quality control")
    return fig
