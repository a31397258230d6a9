"""The ball-screw stage's parameters: the scenario, the numerics and the models' knobs.

Kept apart from :mod:`flumekit.stages.ballscrew`, which wires the rules.
"""

from __future__ import annotations

#: Model knobs that a pipeline may set, ``<part>_<field>`` for a field of the model's parameter
#: dataclass: ``screw`` -> :class:`flumekit.ballscrew.screw.BallScrew`, ``lubricant`` ->
#: ``Lubricant``, ``pto`` -> ``PTOCoefficients``, ``thermal`` ->
#: :class:`flumekit.ballscrew.thermal.lumped.LumpedThermal`. Unset (None) means the model's
#: documented default; the values and their sources live in those dataclasses only (planning
#: must not import numpy, so they are not copied here).
MODEL_KNOBS = {
    "efficiency": {
        "screw": ("pitch_diameter", "ball_diameter", "contact_angle", "conformity_screw",
                  "conformity_nut", "loaded_balls", "preload_per_ball", "slip_angle",
                  "rolling_resistance", "roughness_ball", "roughness_screw", "roughness_nut",
                  "young_modulus", "poisson_ratio"),
        "lubricant": ("viscosity", "pressure_viscosity", "friction_boundary",
                      "friction_full_film"),
        "pto": ("damping", "viscous", "rotor_inertia", "nut_mass")},
    "thermal_lumped": {
        "thermal": ("heat_capacity_generator", "heat_capacity_screw", "heat_capacity_nut",
                    "conductance_generator_air", "conductance_screw_air",
                    "conductance_nut_air", "conductance_screw_generator",
                    "partition_screw_nut", "partition_screw_bearing", "ball_system_fraction",
                    "generator_efficiency", "initial_temperature",
                    "air_temperature_generator", "air_temperature_screw")},
}
DEFAULTS = {"amplitude": 1.0, "period": 3.8, "samples_per_period": 380, "lead": 0.02,
            "cycle_duration": 600.0, "total_duration": 6000.0, "lumped_time_step": 1.0,
            "fem_time_step": 10.0, "radial_cell_size": 0.005, "axial_cell_size": 0.02,
            "fem_order": 1,
            **{f"{part}_{name}": None for parts in MODEL_KNOBS.values()
               for part, names in parts.items() for name in names}}
_KNOB_OWNER = {"screw": "BallScrew", "lubricant": "Lubricant", "pto": "PTOCoefficients",
               "thermal": "LumpedThermal"}
DOCS = {
    "amplitude": "heave amplitude of the buoy's reference motion [m]",
    "period": "period of the reference motion [s]",
    "samples_per_period": "samples per period of the reference motion [-]",
    "lead": "ball-screw lead [m]",
    "cycle_duration": "thermal models: duration of one operating cycle [s]",
    "total_duration": "thermal models: simulated duration [s]",
    "lumped_time_step": "lumped thermal model time step [s]",
    "fem_time_step": "finite-element thermal model time step [s]",
    "radial_cell_size": "finite-element mesh: radial cell size [m]",
    "axial_cell_size": "finite-element mesh: axial cell size [m]",
    "fem_order": "finite-element order [-]",
    **{f"{part}_{name}": f"model knob: field '{name}' of {_KNOB_OWNER[part]} ({step} step; "
       "unit and source in that dataclass); none: its documented default"
       for step, parts in MODEL_KNOBS.items() for part, names in parts.items()
       for name in names},
}
