"""The layout of a BEM result held as an xarray dataset, in Capytaine's conventions.

Capytaine (Ancellin & Dias 2019) writes its results with complex values split along a
``complex`` ("re", "im") dimension, one of several frequency dimensions that carry an ``omega``
coordinate [rad s-1], an optional ``wave_direction`` [rad], and the excitation either whole or
as diffraction plus Froude-Krylov force. These helpers undo that layout; both the six-dof reader
(:mod:`flumekit.hydro.capytaine`) and the one-dof container (:func:`flumekit.hydro.coefficients.
from_capytaine`) use them.

References
----------
Ancellin, M., Dias, F. (2019). Capytaine: a Python-based linear potential flow solver. J. Open
Source Softw. 4(36), 1341.
"""

from __future__ import annotations

import numpy as np
import xarray as xr

#: names of the frequency dimension in a Capytaine dataset (each with an ``omega`` coordinate)
FREQUENCY_DIMS = ("omega", "freq", "period", "wavenumber", "wavelength")


def merge_complex_dim(ds: xr.Dataset) -> xr.Dataset:
    """Join variables split along a ``complex`` ("re", "im") dimension into complex values.

    Parameters
    ----------
    ds : xarray.Dataset
        Capytaine dataset (units of its variables kept).

    Returns
    -------
    xarray.Dataset
        ``ds`` without the ``complex`` dimension (``ds`` itself if it has none).

    Examples
    --------
    >>> import xarray as xr
    >>> from flumekit.hydro.bem_layout import merge_complex_dim
    >>> ds = xr.Dataset({"f": ("complex", [1.0, 2.0])}, coords={"complex": ["re", "im"]})
    >>> complex(merge_complex_dim(ds)["f"])
    (1+2j)
    """
    if "complex" not in ds.dims:
        return ds
    ds = ds.copy()
    for name in [n for n in ds.data_vars if "complex" in ds[n].dims]:
        ds[name] = ds[name].sel(complex="re") + 1j * ds[name].sel(complex="im")
    return ds.drop_dims("complex", errors="ignore").drop_vars("complex", errors="ignore")


def frequency_dim(ds: xr.Dataset) -> str:
    """Return the name of Capytaine's frequency dimension, which must carry ``omega``.

    Parameters
    ----------
    ds : xarray.Dataset
        Capytaine dataset.

    Returns
    -------
    str
        The first of :data:`FREQUENCY_DIMS` among the dataset's dimensions.

    Raises
    ------
    ValueError
        No frequency dimension, or no ``omega`` coordinate [rad s-1].
    """
    fdim = next((d for d in FREQUENCY_DIMS if d in ds.dims), None)
    if fdim is None:
        raise ValueError(f"no frequency dimension among {list(ds.dims)}; Capytaine uses one "
                         f"of {list(FREQUENCY_DIMS)}")
    if "omega" not in ds.coords:
        raise ValueError(f"the dataset has frequency dim '{fdim}' but no 'omega' coordinate")
    return fdim


def select_direction(da: xr.DataArray, wave_direction: float) -> xr.DataArray:
    """Select the incident direction ``wave_direction`` (modulo 2π), if ``da`` has one.

    Parameters
    ----------
    da : xarray.DataArray
        A variable, possibly over ``wave_direction`` [rad].
    wave_direction : float
        The direction to keep [rad] (0: waves towards +x).

    Returns
    -------
    xarray.DataArray
        ``da`` at that direction (``da`` itself if it has no ``wave_direction`` dimension).

    Raises
    ------
    ValueError
        The direction was not computed (within 1e-6 rad).
    """
    if "wave_direction" not in da.dims:
        return da
    dirs = da["wave_direction"].values.astype(float)
    gap = np.abs(np.angle(np.exp(1j * (dirs - wave_direction))))
    if gap.min() > 1e-6:
        raise ValueError(f"wave direction {wave_direction} rad not computed; "
                         f"available: {dirs.tolist()}")
    return da.isel(wave_direction=int(np.argmin(gap)))


def excitation_of(ds: xr.Dataset) -> xr.DataArray:
    """Return ``excitation_force``, or ``diffraction_force`` + ``Froude_Krylov_force``.

    Parameters
    ----------
    ds : xarray.Dataset
        Capytaine dataset with complex values (:func:`merge_complex_dim`).

    Returns
    -------
    xarray.DataArray
        The excitation force per unit amplitude [N m-1, N m m-1].

    Raises
    ------
    ValueError
        Neither form is in the dataset.
    """
    if "excitation_force" in ds:
        return ds["excitation_force"]
    if "diffraction_force" in ds and "Froude_Krylov_force" in ds:
        return ds["diffraction_force"] + ds["Froude_Krylov_force"]
    raise ValueError("the Capytaine dataset has neither 'excitation_force' nor "
                     "'diffraction_force' + 'Froude_Krylov_force'")


__all__ = ["FREQUENCY_DIMS", "excitation_of", "frequency_dim", "merge_complex_dim",
           "select_direction"]
