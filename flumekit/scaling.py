"""Froude similitude: model-scale datasets to full (prototype) scale and back.

A model test at geometric scale 1:λ with the same gravity keeps the Froude number
U / sqrt(g L) (ITTC 7.5-02-07-03.7, §2; Chakrabarti 1994, ch. 9): lengths scale by λ, times by
λ^½ and masses by (ρ_p/ρ_m) λ³. Every other quantity follows from its dimensions, so the factor
of each variable is derived from its units in the registry (:data:`flumekit.conventions.
VARIABLES`): a quantity with dimensions m^a s^b kg^c scales by

    λ^(a + b/2 + 3c) (ρ_p / ρ_m)^c,

e.g. velocity λ^½, force λ³, torque λ⁴, power λ^3.5, energy flux per metre of crest λ^2.5.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

import numpy as np
import xarray as xr

#: UDUNITS symbol -> powers of (m, s, kg); angles and counts are dimensionless
BASE_UNITS: dict[str, tuple[float, float, float]] = {
    "m": (1, 0, 0), "s": (0, 1, 0), "kg": (0, 0, 1), "1": (0, 0, 0),
    "rad": (0, 0, 0), "degree": (0, 0, 0), "percent": (0, 0, 0), "Hz": (0, -1, 0),
    "N": (1, -2, 1), "Pa": (-1, -2, 1), "J": (2, -2, 1), "W": (2, -3, 1),
}
_TOKEN = re.compile(r"^([A-Za-z]+|1)\^?(-?\d+)?$")

#: the attribute a scaled dataset carries: "prototype" or "model"
SCALED_TO = "froude_scaled_to"


@dataclass(frozen=True)
class Dimensions:
    """Powers of length (m), time (s) and mass (kg) of a unit."""

    length: float
    time: float
    mass: float

    @property
    def froude_exponent(self) -> float:
        """Power of the geometric scale λ by which the quantity scales [-]."""
        return self.length + 0.5 * self.time + 3.0 * self.mass


def dimensions(units: str) -> Dimensions:
    """Return the powers of m, s and kg of a UDUNITS unit string.

    Parameters
    ----------
    units : str
        Space-separated (or ``.``-separated) symbols with optional integer powers, as the
        registry writes them: ``"m s-1"``, ``"N m"``, ``"Pa s2 rad-2"``, ``"W m-1"``.

    Returns
    -------
    Dimensions
        Powers of length, time and mass.

    Raises
    ------
    ValueError
        A symbol outside :data:`BASE_UNITS` (e.g. ``V``, ``K``: no Froude law scales them).

    Examples
    --------
    >>> dimensions("N m").froude_exponent
    4.0
    """
    a = np.zeros(3)
    for tok in units.replace(".", " ").split():
        m = _TOKEN.match(tok)
        if not m or m.group(1) not in BASE_UNITS:
            raise ValueError(f"unit {units!r}: {tok!r} is not a unit Froude similitude scales "
                             f"(known: {' '.join(BASE_UNITS)})")
        a += np.asarray(BASE_UNITS[m.group(1)], float) * int(m.group(2) or 1)
    return Dimensions(*(float(v) for v in a))


def froude_factor(units: str, scale: float, density_ratio: float = 1.0) -> float:
    """Return the model-to-prototype factor of a quantity: λ^(a + b/2 + 3c) (ρ_p/ρ_m)^c.

    Parameters
    ----------
    units : str
        UDUNITS unit string (see :func:`dimensions`).
    scale : float
        Geometric scale λ = L_prototype / L_model [-].
    density_ratio : float
        ρ_prototype / ρ_model [-].

    Returns
    -------
    float
        The factor [-].

    Raises
    ------
    ValueError
        For units no Froude law scales (:func:`dimensions`).

    References
    ----------
    ITTC (2021) Recommended procedure 7.5-02-07-03.7, Wave energy converter model test
    experiments, §2.1 (Froude scaling).

    Examples
    --------
    >>> round(froude_factor("W", 10.0), 3)  # power: 10^3.5
    3162.278
    """
    d = dimensions(units)
    return float(scale ** d.froude_exponent * density_ratio ** d.mass)


def scale(ds: xr.Dataset, scale: float, model_density: float = 1000.0,
          prototype_density: float = 1025.0, to: str = "prototype") -> xr.Dataset:
    """Return a dataset at full (``to="prototype"``) or model scale by Froude similitude.

    Each numeric variable and coordinate is multiplied by its factor (:func:`froude_factor`)
    derived from its units in :data:`flumekit.conventions.VARIABLES`; labels are kept.

    Parameters
    ----------
    ds : xarray.Dataset
        Dataset with registered variable names; times as numbers of seconds (open with
        ``decode_times=False``).
    scale : float or flumekit.campaign.Scale
        Geometric scale λ = L_prototype / L_model [-] (Brito et al. 2020: 10); a campaign's
        ``Scale`` also gives the densities.
    model_density, prototype_density : float
        Water densities of the model test and of the sea [kg m-3].
    to : {"prototype", "model"}
        Direction: model values to prototype (multiply) or prototype values to model (divide).

    Returns
    -------
    xarray.Dataset
        The scaled dataset; attributes ``froude_scaled_to``, ``froude_scale`` and the densities.

    Raises
    ------
    ValueError
        A variable not in the registry, or whose units no Froude law scales (the message names
        it); a time axis decoded to dates; a dataset already at the requested scale.

    References
    ----------
    ITTC (2021) Recommended procedure 7.5-02-07-03.7, Wave energy converter model test
    experiments, §2.1 (Froude scaling). Brito et al. (2020), §2.1 (model scale 1:10).

    Examples
    --------
    >>> import xarray as xr
    >>> ds = xr.Dataset({"mean_power": ((), 20.0), "measured_period": ((), 2.0)})
    >>> full = scale(ds, 10.0, prototype_density=1000.0)
    >>> round(float(full.mean_power)), round(float(full.measured_period), 3)
    (63246, 6.325)
    """
    from flumekit.conventions import VARIABLES

    if hasattr(scale, "factor"):  # a campaign's [scale] table
        model_density, prototype_density = scale.model_density, scale.prototype_density
        scale = scale.factor
    if to not in ("prototype", "model"):
        raise ValueError(f"to must be 'prototype' or 'model', got {to!r}")
    if not (np.isfinite(scale) and scale > 0 and model_density > 0 and prototype_density > 0):
        raise ValueError(f"scale {scale} and densities {model_density}, {prototype_density} "
                         "must be positive")
    if ds.attrs.get(SCALED_TO) == to:
        raise ValueError(f"the dataset is already at {to} scale ({SCALED_TO} = {to!r})")
    ratio = prototype_density / model_density
    sign = 1.0 if to == "prototype" else -1.0
    out = ds.copy()
    factors = {}
    for name in [*ds.coords, *ds.data_vars]:
        var = ds[name]
        if var.dtype.kind in "OSUb":  # labels and flags
            continue
        if var.dtype.kind in "mM":
            raise ValueError(f"variable {name!r} holds dates: open the dataset with "
                             "decode_times=False to scale its times in seconds")
        reg = VARIABLES.get(str(name))
        if reg is None:
            raise ValueError(f"variable {name!r} is not in flumekit.conventions.VARIABLES: "
                             "its Froude factor is unknown")
        try:
            f = froude_factor(reg.units, scale, ratio) ** sign
        except ValueError as e:
            raise ValueError(f"variable {name!r}: {e}") from None
        factors[name] = f
    scaled = {k: ds[k].variable * f for k, f in factors.items() if f != 1.0}
    for k, v in scaled.items():
        v.attrs = dict(ds[k].attrs)
    coords = {k: v for k, v in scaled.items() if k in ds.coords}
    out = out.assign_coords({k: (ds[k].dims, v.data, v.attrs) for k, v in coords.items()})
    for k, v in scaled.items():
        if k not in ds.coords:
            out[k] = v
    if to == "model":
        for k in (SCALED_TO, "froude_scale", "model_density", "prototype_density"):
            out.attrs.pop(k, None)
        out.attrs[SCALED_TO] = "model"
    else:
        out.attrs.update({SCALED_TO: "prototype", "froude_scale": float(scale),
                          "model_density": float(model_density),
                          "prototype_density": float(prototype_density)})
    return out
