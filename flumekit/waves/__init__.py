"""Waves: linear theory, probe layout, incident/reflected separation and run statistics."""

from flumekit.waves.analysis import analyse_run  # noqa: F401
from flumekit.waves.layout import (  # noqa: F401
    MAX_CONDITION,
    check_layout,
    condition_number,
    probe_spacing,
)
from flumekit.waves.separation import SeparationWarning, separate  # noqa: F401
from flumekit.waves.theory import (  # noqa: F401
    energy_flux,
    group_velocity,
    phase_velocity,
    stokes2_coefficient,
    wavelength,
    wavenumber,
)
