"""The quality-control figure of one run: every probe and flap channel as read, as QC'd, and the
samples each flag marks."""

from __future__ import annotations

import numpy as np

from flumekit.figures.style import TWO_COLUMNS, new_figure, units_text

#: marker colours of the QARTOD flags drawn (pass and not-evaluated samples are not marked)
FLAG_STYLE = {3: ("suspect", "tab:orange", "o"), 4: ("fail", "tab:red", "x"),
              9: ("missing", "tab:purple", "|")}


def _channels(probes, flap):
    out = []
    # voltages to calibrate, or the elevations of calibrated probes
    name, units = (("probe_voltage", "V") if "probe_voltage" in probes
                   else ("probe_elevation", "m"))
    for p in probes["probe"].values:
        sel = {"probe": p}
        out.append((str(p), probes["time"].values, probes[f"{name}_raw"].sel(sel).values,
                    probes[name].sel(sel).values, probes[f"{name}_qc"].sel(sel).values, units))
    if flap is not None:
        for name, label, units in (("encoder_counts", "encoder", "counts"),
                                   ("chamber_pressure", "pressure", "Pa")):
            out.append((label, flap["time"].values, flap[f"{name}_raw"].values,
                        flap[name].values, flap[f"{name}_qc"].values, units))
    return out


def figure_qc(probes, flap=None):
    """Raw (grey) and QC'd (black) records of every probe and flap channel of a run, with the
    suspect, failed and missing samples marked at their raw values.

    Parameters
    ----------
    probes : Dataset of the qc stage for the probes (``probe_voltage``, ``_raw``, ``_qc``).
    flap : Dataset of the qc stage for the encoder and pressure, or None.

    Returns
    -------
    matplotlib.figure.Figure
    """
    chans = _channels(probes, flap)
    fig, axes = new_figure(len(chans), 1, width=TWO_COLUMNS, row_height=1.0, sharex=True)
    run = str(probes["run"].values) if "run" in probes.coords else ""
    for ax, (label, t, raw, clean, flags, units) in zip(axes[:, 0], chans, strict=True):
        ax.plot(t, raw, color="0.7", lw=0.6, label="as read")
        ax.plot(t, clean, color="k", lw=0.5, label="after QC")
        counts = []
        for value, (meaning, colour, marker) in FLAG_STYLE.items():
            sel = flags == value
            counts.append(f"{int(sel.sum())} {meaning}")
            if sel.any():
                y = np.where(np.isfinite(raw[sel]), raw[sel], np.nanmedian(raw))
                ax.plot(t[sel], y, ls="none", marker=marker, color=colour, ms=3, mew=0.8,
                        label=meaning)
        ax.set_ylabel(f"[{units_text(units)}]")
        ax.set_title(f"{label}: " + ", ".join(counts), loc="left")
    axes[-1, 0].set_xlabel("Time [s]")
    handles = {}
    for ax in axes[:, 0]:
        for h, lab in zip(*ax.get_legend_handles_labels(), strict=True):
            handles.setdefault(lab, h)
    fig.legend(list(handles.values()), list(handles), loc="outside lower center",
               ncols=len(handles))
    fig.suptitle(f"Quality control of run {run}" if run else "Quality control")
    return fig
