"""Waves: linear theory, probe layout, incident/reflected separation and run statistics.

The names an analyst needs: :func:`separate` (incident and reflected waves from a probe array,
numpy, pandas or xarray), :func:`probe_record` (a record in the shape the wave functions use),
:func:`analyse_run` (quasi-steady window and separation of one regular-wave run), the linear
theory (:func:`wavenumber`, :func:`wavelength`, ...), the probe layout checks and
:mod:`~flumekit.waves.calibration` (probe calibration); the sea state of an irregular record:
:func:`spectrum` (Welch, with its confidence interval), :func:`spectral_parameters` (Hm0, Tp,
Tm01, Tm02, Te, ...), :func:`spectral_energy_flux` (:func:`flumekit.waves.spectra.energy_flux`,
the finite-depth flux of a spectrum) and :func:`wave_statistics` (zero-crossing waves).
"""

from flumekit.waves import calibration
from flumekit.waves.analysis import analyse_run
from flumekit.waves.irregular import LowFrequencyWarning, analyse_irregular_run
from flumekit.waves.layout import (
    MAX_CONDITION,
    check_layout,
    condition_number,
    probe_spacing,
)
from flumekit.waves.records import (
    REGULAR_FRACTION,
    harmonic_energy_fraction,
    probe_record,
    refine_frequency,
)
from flumekit.waves.separation import SeparationWarning, separate
from flumekit.waves.spectra import energy_flux as spectral_energy_flux
from flumekit.waves.spectra import jonswap, spectral_parameters, spectrum
from flumekit.waves.statistics import wave_statistics
from flumekit.waves.theory import (
    energy_flux,
    group_velocity,
    phase_velocity,
    stokes2_coefficient,
    wavelength,
    wavenumber,
)

__all__ = [
    "MAX_CONDITION", "REGULAR_FRACTION", "LowFrequencyWarning", "SeparationWarning",
    "analyse_irregular_run", "analyse_run", "calibration",
    "check_layout", "condition_number", "energy_flux", "group_velocity",
    "harmonic_energy_fraction", "phase_velocity", "probe_record", "probe_spacing",
    "refine_frequency", "separate", "stokes2_coefficient", "wavelength", "wavenumber",
    "spectral_energy_flux", "spectral_parameters", "spectrum", "wave_statistics", "jonswap",
]
