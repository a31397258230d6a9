"""Capture width and capture width ratio of a wave energy converter.

The capture width (capture length) is the width of incident wave front whose energy flux
equals the absorbed power, L = P̄ / J; the capture width ratio divides it by a characteristic
width of the device, CWR = P̄ / (J w) (Babarit 2015). In regular waves J is E c_g
(:func:`flumekit.waves.theory.energy_flux`); in irregular seas the spectral flux
J = ρ g ∫ S(f) c_g(f, h) df of the incident spectrum.
"""

from __future__ import annotations

import numpy as np

from flumekit.docstrings import filler

#: docstring text that several functions of this module share
_doc = filler(
    energy_flux=("energy_flux : array_like\n"
                 "    Incident energy flux per unit crest width J [W m-1], > 0."))


def _positive(name: str, value) -> np.ndarray:
    arr = np.asarray(value, dtype=float)
    if np.any(~(arr > 0)) or np.any(~np.isfinite(arr)):
        raise ValueError(f"{name} must be finite and > 0, got {value}")
    return arr


@_doc
def capture_width(mean_power, energy_flux) -> np.ndarray:
    """Capture width (capture length) L = P̄ / J [m].

    Parameters
    ----------
    mean_power : array_like
        Mean absorbed power P̄ over the analysed record [W].
    %(energy_flux)s

    Returns
    -------
    numpy.ndarray
        Capture width [m].

    Raises
    ------
    ValueError
        A flux that is not finite and positive (no incident wave: no capture width).

    References
    ----------
    IEC TS 62600-100:2012, Marine energy - Wave, tidal and other water current converters -
    Part 100: Electricity producing wave energy converters - Power performance assessment
    (capture length).
    ITTC (2021). Recommended procedure 7.5-02-07-03.7, Wave energy converter model test
    experiments (capture width).

    Examples
    --------
    >>> float(capture_width(12.0, 48.0))
    0.25
    """
    return np.asarray(mean_power, dtype=float) / _positive("energy flux", energy_flux)


@_doc
def capture_width_ratio(mean_power, energy_flux, width) -> np.ndarray:
    """Capture width ratio CWR = P̄ / (J w) [-].

    Parameters
    ----------
    mean_power : array_like
        Mean absorbed power P̄ [W].
    %(energy_flux)s
    width : array_like
        Characteristic width of the device w [m], > 0 (the flap width for a flap, the
        diameter for a point absorber).

    Returns
    -------
    numpy.ndarray
        Capture width ratio [-]. For a flap in regular waves it is the capture factor C_f of
        Brito et al. (2020, Eq. A2).

    References
    ----------
    Babarit, A. (2015). A database of capture width ratio of wave energy converters.
    Renewable Energy 80, 610-628.
    IEC TS 62600-103:2018, Marine energy - Part 103: Guidelines for the early stage
    development of wave energy converters - Best practices and recommended procedures for the
    testing of pre-prototype devices.

    Examples
    --------
    >>> float(capture_width_ratio(12.0, 48.0, 0.5))
    0.5
    """
    return capture_width(mean_power, energy_flux) / _positive("device width", width)
