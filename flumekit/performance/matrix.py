"""The power matrix: statistics of runs binned by their sea state (Hm0, Te).

IEC TS 62600-100 reports a wave energy converter's performance as matrices over the
significant wave height Hm0 and the energy period Te: in each cell the number of records, the
mean and the standard deviation of the mean power (and of the capture length), the standard
deviation over the N records of the cell (ddof = 0). The same binning serves any per-run
quantity (mean power, capture width ratio, ...) and several sources at once (the experiment
beside its models).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np
import xarray as xr

from flumekit import conventions


def _edges(name: str, edges) -> np.ndarray:
    e = np.asarray(edges, dtype=float)
    if e.ndim != 1 or e.size < 2 or not np.all(np.isfinite(e)) or np.any(np.diff(e) <= 0):
        raise ValueError(f"{name} edges must be at least two finite, strictly increasing "
                         f"values, got {edges}")
    return e


def _bin(x: np.ndarray, edges: np.ndarray) -> np.ndarray:
    """Half-open bin index [e_i, e_{i+1}) of each value, -1 outside the edges (or NaN)."""
    i = np.searchsorted(edges, x, side="right") - 1
    return np.where(np.isfinite(x) & (i >= 0) & (i < edges.size - 1), i, -1)


def power_matrix(hm0, te, values: Mapping[str, object], hm0_edges, te_edges, *,
                 sources: Sequence[str] | None = None) -> xr.Dataset:
    """Count, mean and standard deviation (ddof = 0) of per-run quantities binned by Hm0 and Te.

    Parameters
    ----------
    hm0 : array_like
        Incident significant wave height Hm0 of each run [m], shape (n,).
    te : array_like
        Incident energy period Te = Tm-1,0 of each run [s], shape (n,).
    values : mapping of str to array_like
        The quantities to bin, each of shape (n,) or (n, len(sources)) (e.g. ``mean_power``
        [W], ``capture_width_ratio`` [-] over the experiment and its models). A DataArray over
        (``run``, ``source``) gives ``sources`` from its coordinate.
    hm0_edges : array_like
        Bin edges of Hm0 [m], strictly increasing; bins are half-open [e_i, e_i+1).
    te_edges : array_like
        Bin edges of Te [s], strictly increasing, half-open bins.
    sources : sequence of str, optional
        Names along the second axis of the 2-D ``values`` (the ``source`` dimension).

    Returns
    -------
    xarray.Dataset
        Over ``hm0_bin`` and ``te_bin`` (the bin centres, with CF ``bounds`` variables
        ``hm0_bin_bounds`` and ``te_bin_bounds`` over ``nv``) and ``source`` when given:
        ``run_count`` (runs in the cell), and for each quantity ``<name>`` (the cell mean) and
        ``<name>_std`` (the population standard deviation, ddof = 0; 0 for a single run). An
        empty cell has count 0 and NaN statistics. ``runs_outside`` counts the runs whose Hm0
        or Te falls outside the edges (or is NaN): they are in no cell.

    Raises
    ------
    ValueError
        Edges not strictly increasing, or values whose shape does not match the runs.

    References
    ----------
    IEC TS 62600-100:2012, Marine energy - Wave, tidal and other water current converters -
    Part 100: Electricity producing wave energy converters - Power performance assessment
    (the power matrix and the capture length matrix over Hm0 and Te, with per-bin mean,
    standard deviation, count, minimum and maximum).
    IEC TS 62600-103:2018, Guidelines for the early stage development of wave energy
    converters.

    Examples
    --------
    >>> ds = power_matrix([0.05, 0.07, 0.12], [1.5, 1.6, 2.4],
    ...                   {"mean_power": [1.0, 3.0, 5.0]}, [0.0, 0.1, 0.2], [1.0, 2.0, 3.0])
    >>> ds.run_count.values.tolist()
    [[2, 0], [0, 1]]
    >>> ds.mean_power.values[0, 0], ds.mean_power_std.values[0, 0]
    (np.float64(2.0), np.float64(1.0))
    """
    h = np.asarray(hm0, dtype=float).ravel()
    t = np.asarray(te, dtype=float).ravel()
    if h.shape != t.shape:
        raise ValueError(f"hm0 {h.shape} and te {t.shape} must have one value per run")
    he, tb = _edges("hm0", hm0_edges), _edges("te", te_edges)
    nh, nt = he.size - 1, tb.size - 1
    ih, it = _bin(h, he), _bin(t, tb)
    inside = (ih >= 0) & (it >= 0)
    cell = np.where(inside, ih * nt + it, 0)
    count = np.bincount(cell[inside], minlength=nh * nt)
    with np.errstate(invalid="ignore", divide="ignore"):
        denom = np.where(count > 0, count, np.nan)

    for v in values.values():
        if sources is None and isinstance(v, xr.DataArray) and "source" in v.dims:
            sources = [str(s) for s in v["source"].values]
    data = {"run_count": (("hm0_bin", "te_bin"), count.reshape(nh, nt))}
    for name, v in values.items():
        if isinstance(v, xr.DataArray) and "source" in v.dims:
            v = v.transpose(..., "source")
        x = np.asarray(v, dtype=float)
        two_d = x.ndim == 2
        if x.shape[0] != h.size or x.ndim > 2 or (two_d and (sources is None
                                                              or x.shape[1] != len(sources))):
            raise ValueError(f"power matrix: {name} has shape {x.shape}, expected ({h.size},)"
                             + (f" or ({h.size}, {len(sources)})" if sources else ""))
        x2 = x.reshape(h.size, -1)[inside]
        c = cell[inside]
        k = x2.shape[1]
        # sums per (cell, column) by one bincount over the flattened pairs
        flat = (c[:, None] * k + np.arange(k)).ravel()
        sums = np.bincount(flat, weights=x2.ravel(), minlength=nh * nt * k).reshape(nh * nt, k)
        mean = sums / denom[:, None]
        dev2 = (x2 - mean[c]) ** 2  # two-pass variance: no cancellation of large means
        var = np.bincount(flat, weights=dev2.ravel(), minlength=nh * nt * k).reshape(nh * nt, k)
        std = np.sqrt(var / denom[:, None])
        dims = ("hm0_bin", "te_bin", "source") if two_d else ("hm0_bin", "te_bin")
        shape = (nh, nt, k) if two_d else (nh, nt)
        data[name] = (dims, mean.reshape(shape))
        data[f"{name}_std"] = (dims, std.reshape(shape))
    coords = {"hm0_bin": 0.5 * (he[1:] + he[:-1]), "te_bin": 0.5 * (tb[1:] + tb[:-1]),
              "hm0_bin_bounds": (("hm0_bin", "nv"), np.stack([he[:-1], he[1:]], axis=1)),
              "te_bin_bounds": (("te_bin", "nv"), np.stack([tb[:-1], tb[1:]], axis=1))}
    if sources is not None and any(np.ndim(v) == 2 for v in values.values()):
        coords["source"] = list(sources)
    ds = xr.Dataset(data, coords=coords)
    ds["runs_outside"] = int((~inside).sum())
    ds = conventions.annotate(ds)
    ds["hm0_bin"].attrs["bounds"] = "hm0_bin_bounds"
    ds["te_bin"].attrs["bounds"] = "te_bin_bounds"
    for name in values:
        base = conventions.VARIABLES.get(name)
        ds[name].attrs["cell_methods"] = "hm0_bin: te_bin: mean"
        ds[f"{name}_std"].attrs["cell_methods"] = "hm0_bin: te_bin: standard_deviation"
        ds[name].attrs["long_name"] = f"mean of {name} over the runs of the cell"
        ds[f"{name}_std"].attrs["long_name"] = (f"standard deviation (ddof = 0) of {name} over "
                                                "the runs of the cell")
        if base is not None:  # the units of the quantity binned
            ds[name].attrs["units"] = ds[f"{name}_std"].attrs["units"] = base.units
    return ds


def target_te(target: dict) -> float:
    """Return the energy period of a target sea state.

    Parameters
    ----------
    target : dict
        ``te`` [s] when declared, else ``tp`` [s] and ``gamma`` [-] (default 3.3) of a
        JONSWAP spectrum.

    Returns
    -------
    float
        Te = m₋₁ / m₀ [s], the declared one or that of the JONSWAP spectrum (integrated
        to 20 fp).

    References
    ----------
    IEC TS 62600-100:2012, Marine energy - Wave, tidal and other water current converters -
    Part 100: Electricity producing wave energy converters - Power performance assessment.

    Examples
    --------
    >>> target_te({"te": 2.5})
    2.5
    >>> round(target_te({"tp": 2.0, "gamma": 3.3}) / 2.0, 2)
    0.9
    """
    import numpy as np

    from flumekit.waves.spectra import jonswap

    if target.get("te"):
        return float(target["te"])
    tp = float(target["tp"])
    f = np.linspace(0.0, 20.0 / tp, 20001)[1:]  # to 20 fp: the f^-5 tail beyond is < 1e-5
    s = jonswap(f, 1.0, tp, target.get("gamma") or 3.3)
    return float(np.trapezoid(s / f, f) / np.trapezoid(s, f))


def edges_around(values) -> list[float]:
    """Return bin edges that give each distinct value its own bin.

    Inner edges lie halfway between neighbours, the outer edges as far out as the nearest
    inner one (±10 % around a lone value).

    Parameters
    ----------
    values : array_like
        The values (e.g. target Hm0 [m] or Te [s]); equal to 9 decimals counts as one.

    Returns
    -------
    list of float
        Increasing edges, one more than the distinct values.

    Examples
    --------
    >>> edges_around([1.0, 2.0, 2.0, 4.0])
    [0.5, 1.5, 3.0, 5.0]
    >>> edges_around([2.0])
    [1.8, 2.2]
    """
    import numpy as np

    v = np.unique(np.round(np.asarray(values, dtype=float), 9))
    if v.size == 1:
        return [float(v[0] * 0.9), float(v[0] * 1.1)]
    mid = 0.5 * (v[1:] + v[:-1])
    return [float(2 * v[0] - mid[0]), *map(float, mid), float(2 * v[-1] - mid[-1])]
