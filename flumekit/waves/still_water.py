"""The still-water level of probe records given in length units, by a declared rule.

A probe that records elevation (capacitance gauges with their own calibration, a lab's
processed files) carries the offset of its zero: the still-water level must be removed before
the separation, by a rule the campaign declares (raw/README.md):

* ``"mean"``: the record mean of each probe (a regular-wave record over whole periods has
  zero-mean linear waves; the second-order set-down is O(a² k / sinh 2kh), 0.1 mm for the
  WaveLabX record);
* ``[start, end]``: the mean of a still segment [s] before the waves arrive (the right rule
  when the record starts in still water);
* a number: one level for every probe [m]; a table ``probe = level`` [m]: one per probe;
* ``"none"``: nothing removed (calibrated voltages already refer to still water).
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from flumekit import conventions


def still_water_level(elevation: xr.DataArray, rule) -> xr.DataArray:
    """Compute the still-water level of each probe [m] by ``rule`` (see the module docstring).

    Parameters
    ----------
    elevation : Probe records [m], dims ("probe", "time").
    rule : "mean", "none", [start, end] [s], a level [m] or a mapping probe -> level [m].

    Returns
    -------
    xr.DataArray ``still_water_level`` (probe) [m], with the rule in ``attrs["rule"]``.
    """
    probes = [str(p) for p in elevation["probe"].values]
    if isinstance(rule, str) and rule == "mean":
        level = elevation.mean("time").values
        text = "record mean"
    elif isinstance(rule, str) and rule == "none":
        level = np.zeros(len(probes))
        text = "none"
    elif isinstance(rule, (list, tuple)):
        start, end = float(rule[0]), float(rule[1])
        t = elevation["time"].values
        sel = (t >= start) & (t <= end)
        if sel.sum() < 2:
            raise ValueError(f"the still segment [{start:g}, {end:g}] s holds fewer than two "
                             f"samples (record {t[0]:g}-{t[-1]:g} s)")
        level = elevation.isel(time=np.flatnonzero(sel)).mean("time").values
        text = f"mean of the still segment {start:g}-{end:g} s"
    elif isinstance(rule, dict):
        missing = [p for p in probes if p not in rule]
        if missing:
            raise ValueError(f"no still-water level given for probe(s) {missing}")
        level = np.array([float(rule[p]) for p in probes])
        text = "given per probe"
    elif isinstance(rule, (int, float)) and not isinstance(rule, bool):
        level = np.full(len(probes), float(rule))
        text = f"given: {float(rule):g} m"
    else:
        raise ValueError(f"unknown still-water rule {rule!r}")
    out = xr.DataArray(np.asarray(level, dtype=float), dims="probe",
                       coords={"probe": probes}, name="still_water_level",
                       attrs=conventions.attrs("still_water_level"))
    out.attrs["rule"] = text
    return out


def remove_still_water(elevation: xr.DataArray, rule) -> tuple[xr.DataArray, xr.DataArray]:
    """``eta`` = elevation - still-water level [m], and the level removed (per probe)."""
    level = still_water_level(elevation, rule)
    eta = (elevation - level).transpose("probe", "time").rename("eta")
    eta.attrs = conventions.attrs("eta")
    return eta, level
