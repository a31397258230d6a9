"""Units a raw file may declare, with their physical quantity and factor to SI.

One table for every reader (CSV headers, dialect declarations, TDMS ``unit_string`` and
HDF5/netCDF ``units`` attributes) and for the campaign's validation.
"""

from __future__ import annotations

#: unit -> (quantity, factor to SI)
UNITS: dict[str, tuple[str, float]] = {
    "s": ("time", 1.0), "ms": ("time", 1e-3),
    "V": ("voltage", 1.0), "mV": ("voltage", 1e-3),
    "Pa": ("pressure", 1.0), "kPa": ("pressure", 1e3), "bar": ("pressure", 1e5),
    "mbar": ("pressure", 1e2),
    "m": ("length", 1.0), "cm": ("length", 1e-2), "mm": ("length", 1e-3),
    "counts": ("count", 1.0), "1": ("count", 1.0),
}


def quantity(unit: str) -> str:
    """Return the physical quantity of a unit a raw file may declare.

    Parameters
    ----------
    unit : str
        A unit of :data:`UNITS`.

    Returns
    -------
    str
        ``"time"``, ``"voltage"``, ``"pressure"``, ``"length"`` or ``"count"``.

    Raises
    ------
    KeyError
        For a unit not in :data:`UNITS`.

    Examples
    --------
    >>> quantity("mbar"), UNITS["mbar"][1]
    ('pressure', 100.0)
    """
    return UNITS[unit][0]
