"""UVP: beam geometry, per-run phase averaging, decomposition into ⟨u⟩, ⟨w⟩, turbulence, field.

Pipeline shape: per run, :func:`phase_average_beams` (raw beam records -> small dataset over
(beam, channel, phase)); per campaign, :func:`velocity_field` (all runs -> (phase, z, x)).
"""

from flumekit.uvp.decomposition import combine_ci, least_squares_velocity, paired_velocity
from flumekit.uvp.field import beam_to_grid, combine_repeats, default_grid, velocity_field
from flumekit.uvp.geometry import (
                                   beam_geometry,
                                   channel_distances,
                                   channel_positions,
                                   flap_face_x,
                                   inside_flap,
)
from flumekit.uvp.phase import phase_average_beams
from flumekit.uvp.turbulence import reynolds_stresses, turbulent_kinetic_energy

__all__ = [
    "beam_geometry", "beam_to_grid", "channel_distances", "channel_positions", "combine_ci",
    "combine_repeats", "default_grid", "flap_face_x", "inside_flap", "least_squares_velocity",
    "paired_velocity", "phase_average_beams", "reynolds_stresses", "turbulent_kinetic_energy",
    "velocity_field",
]
