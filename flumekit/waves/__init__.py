"""Waves: linear theory, probe calibration and incident/reflected separation."""

from flumekit.waves.theory import wavelength, wavenumber  # noqa: F401
