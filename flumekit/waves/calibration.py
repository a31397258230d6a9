"""Wave-probe calibration from static submersions (Brito et al. 2020, §2.3).

A polynomial eta = sum_n c_n V^n (first order by default) is fitted by least squares to the
voltages recorded at known still-water levels, per probe; R² and residuals are reported, and
the fit is checked for monotonicity over the voltage range a run actually records.
"""

from __future__ import annotations

import warnings

import numpy as np
import xarray as xr

from flumekit import conventions
from flumekit.docstrings import filler

#: docstring text that several functions of this module share
_doc = filler(
    calibration=("calibration : xarray.Dataset\n"
                 "    Output of :func:`fit` holding every probe of ``voltage``."))

__all__ = ["R2_WARNING", "CalibrationWarning", "apply", "fit", "is_monotonic"]

R2_WARNING = 0.999


class CalibrationWarning(UserWarning):
    """A probe calibration is poor (R² below 0.999) or not monotonic where it is used."""


def fit(calibration, order: int = 1, *, levels=None) -> xr.Dataset:
    """Least-squares calibration polynomial per probe.

    Parameters
    ----------
    calibration : xarray.Dataset, pandas.DataFrame or array_like
        The static submersions: a Dataset from :func:`flumekit.io.read_calibration`, with
        ``calibration_voltage`` (sample, probe) [V] and coordinate ``level`` (sample) [m]; or
        the voltages [V] alone, one row per submersion, as an array of shape (sample,) (one
        probe) or (sample, probe) or a DataFrame with one column per probe, with ``levels``.
    order : int
        Polynomial order (1 = gain and offset, as in the paper).
    levels : array_like, optional
        Water level of each submersion relative to still water [m], shape (sample,); needed
        with voltages given as an array or a DataFrame.

    Returns
    -------
    xarray.Dataset
        ``calibration_coefficients`` (probe, polynomial_order) [m V^-n], ``gain`` [m V-1] and
        ``offset`` [m] (first-order terms), ``calibration_r2``, ``calibration_residual``
        (sample, probe) [m], ``calibration_rms_residual`` [m].

    Raises
    ------
    ValueError
        Too few distinct levels for the order, or voltages and levels that do not match.

    Examples
    --------
    >>> from flumekit.waves import calibration
    >>> cal = calibration.fit([1.0, 2.0, 3.0], levels=[-0.05, 0.0, 0.05])
    >>> round(float(cal.gain[0]), 9), round(float(cal.offset[0]), 9)
    (0.05, -0.1)
    """
    if not isinstance(calibration, xr.Dataset):
        calibration = _submersions(calibration, levels)
    elif levels is not None:
        raise ValueError("levels is only for voltages given as an array or a DataFrame; the "
                         "Dataset carries its own 'level' coordinate")
    v = calibration["calibration_voltage"].transpose("sample", "probe").values
    levels = calibration["level"].values
    n_levels = np.unique(levels).size
    if order < 1 or order >= n_levels:
        raise ValueError(f"calibration order {order} needs at least {order + 1} distinct levels; "
                         f"the calibration has {n_levels}")
    # Vandermonde per probe, solved in one batched least-squares call: (probe, sample, order+1)
    A = v.T[:, :, None] ** np.arange(order + 1)
    # scale columns for conditioning
    scale = np.max(np.abs(A), axis=1, keepdims=True)
    scale[scale == 0] = 1.0
    As = A / scale
    coef = np.stack([np.linalg.lstsq(As[p], levels, rcond=None)[0] for p in range(A.shape[0])])
    coef = coef / scale[:, 0, :]
    fitted = np.einsum("psk,pk->sp", A, coef)
    resid = levels[:, None] - fitted
    ss_tot = np.sum((levels - levels.mean()) ** 2)
    r2 = 1.0 - np.sum(resid**2, axis=0) / ss_tot
    probes = calibration["probe"].values
    ds = xr.Dataset(
        {
            "calibration_coefficients": (("probe", "polynomial_order"), coef),
            "gain": ("probe", coef[:, 1]),
            "offset": ("probe", coef[:, 0]),
            "calibration_r2": ("probe", r2),
            "calibration_residual": (("sample", "probe"), resid),
            "calibration_rms_residual": ("probe", np.sqrt(np.mean(resid**2, axis=0))),
        },
        coords={"probe": probes, "polynomial_order": np.arange(order + 1),
                "level": ("sample", levels)},
        attrs={"calibration_order": order},
    )
    for p, r in zip(probes, r2):
        if r < R2_WARNING:
            warnings.warn(f"probe {p}: calibration R² = {r:.5f} < {R2_WARNING}", CalibrationWarning,
                          stacklevel=2)
    return conventions.annotate(ds)


def _submersions(voltage, levels) -> xr.Dataset:
    """Voltages (array or DataFrame) and levels as the Dataset :func:`fit` reads."""
    if levels is None:
        raise ValueError("give the water level [m] of each submersion: fit(voltages, levels=...)")
    if hasattr(voltage, "columns") and hasattr(voltage, "to_numpy"):  # a pandas DataFrame
        probes = [str(c) for c in voltage.columns]
        v = voltage.to_numpy(dtype=float)
    else:
        v = np.asarray(voltage, dtype=float)
        if v.ndim == 1:
            v = v[:, None]
        probes = [str(i) for i in range(v.shape[1] if v.ndim == 2 else 0)]
    lev = np.asarray(levels, dtype=float)
    if v.ndim != 2 or lev.shape != (v.shape[0],):
        raise ValueError(f"voltages of shape {v.shape} (sample, probe) need one level per "
                         f"sample, got levels of shape {lev.shape}")
    return xr.Dataset({"calibration_voltage": (("sample", "probe"), v)},
                      coords={"level": ("sample", lev), "probe": probes})


def is_monotonic(coefficients: np.ndarray, v_min: float, v_max: float) -> bool:
    """Whether the calibration polynomial's derivative keeps one sign on [v_min, v_max].

    Parameters
    ----------
    coefficients : numpy.ndarray
        Polynomial coefficients c_0 ... c_n, lowest order first [m V^-n].
    v_min, v_max : float
        Voltage range [V].

    Returns
    -------
    bool
        True where a voltage in the range maps to a unique level.
    """
    deriv = np.polynomial.polynomial.polyder(coefficients)
    vv = np.linspace(v_min, v_max, 201)
    d = np.polynomial.polynomial.polyval(vv, deriv)
    return bool(np.all(d > 0) or np.all(d < 0))


@_doc
def non_monotonic(voltage: xr.DataArray,
                  calibration: xr.Dataset) -> list[tuple[str, float, float]]:
    """Probes whose calibration polynomial is not monotonic over the voltages of a record.

    Parameters
    ----------
    voltage : xarray.DataArray
        Probe voltages [V], dims ("probe", "time"); NaN (masked samples) ignored.
    %(calibration)s

    Returns
    -------
    list of (str, float, float)
        (probe, lowest, highest recorded voltage [V]) of every probe whose polynomial is not
        monotonic there, where a voltage no longer maps to a unique level.
    """
    coef = calibration["calibration_coefficients"].sel(probe=voltage["probe"])
    vmin, vmax = voltage.min("time").values, voltage.max("time").values
    return [(str(p), float(vmin[i]), float(vmax[i]))
            for i, p in enumerate(voltage["probe"].values)
            if not is_monotonic(coef.sel(probe=p).values, float(vmin[i]), float(vmax[i]))]


@_doc
def apply(voltage: xr.DataArray, calibration: xr.Dataset) -> xr.DataArray:
    """Surface elevation [m] from probe voltages [V] with each probe's calibration polynomial.

    Parameters
    ----------
    voltage : xarray.DataArray
        Probe voltages [V], dims ("probe", "time").
    %(calibration)s

    Returns
    -------
    xarray.DataArray
        ``eta`` [m], dims ("probe", "time").

    Warns
    -----
    CalibrationWarning
        When a polynomial is not monotonic over the voltage range the record spans, where a
        voltage no longer maps to a unique level (:func:`non_monotonic`).
    """
    coef = calibration["calibration_coefficients"].sel(probe=voltage["probe"])
    powers = calibration["polynomial_order"]
    eta = (coef * voltage ** powers).sum("polynomial_order", skipna=False)
    for p, lo, hi in non_monotonic(voltage, calibration):
        warnings.warn(f"probe {p}: calibration polynomial is not monotonic over the recorded "
                      f"voltages [{lo:.4g}, {hi:.4g}] V", CalibrationWarning, stacklevel=2)
    eta = eta.transpose("probe", "time").rename("eta")
    eta.attrs = conventions.attrs("eta")
    return eta
