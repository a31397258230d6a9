"""The flap: encoder angle, PTO geometry, pressure and friction models, torque balance, power.

Brito et al. (2020), §2.2-2.3, §3.1-3.3 and Appendices A-B. Conventions: x towards the beach,
z up from the hinge axis, θ > 0 leaning to the beach; T_h positive towards the beach, the
gravity and PTO torques of Eq. (11) as resisting torques.
"""

from flumekit.flap.analysis import DEFAULT_CUTOFF, analyse_irregular_run, analyse_run
from flumekit.flap.comparison import compare_irregular_run, compare_run
from flumekit.flap.encoder import (
    WireAngle,
    angle_from_wire,
    counts_from_wire,
    wire_from_counts,
    wire_length,
)
from flumekit.flap.friction import (
    FrictionState,
    LuGre,
    film_steady_state,
    friction_advance,
    friction_force,
    friction_series,
    friction_step,
    steady_friction,
    stribeck,
)
from flumekit.flap.geometry import (
    RodKinematics,
    angle_from_rod_length,
    check_anchors,
    flap_point,
    rod_kinematics,
    rod_length_limits,
)
from flumekit.flap.power import capture_factor, flow_rate, incident_power, pto_power, window_mean
from flumekit.flap.pressure import (
    PressureFit,
    chamber_pressure_model,
    fit_pressure_model,
    pressure_force,
    thoma_coefficient,
)
from flumekit.flap.summary import steady_window, summarise_run
from flumekit.flap.torque import (
    friction_torque,
    gravity_torque,
    hydrodynamic_torque,
    inertia_torque,
    pressure_torque,
)

__all__ = [
    "DEFAULT_CUTOFF", "analyse_run", "analyse_irregular_run",
    "WireAngle", "angle_from_wire", "counts_from_wire", "wire_from_counts", "wire_length",
    "FrictionState", "LuGre", "film_steady_state", "friction_advance", "friction_force",
    "friction_series",
    "friction_step", "steady_friction", "stribeck",
    "RodKinematics", "angle_from_rod_length", "check_anchors", "flap_point", "rod_kinematics",
    "rod_length_limits",
    "capture_factor", "flow_rate", "incident_power", "pto_power", "window_mean",
    "PressureFit", "chamber_pressure_model", "fit_pressure_model", "pressure_force",
    "thoma_coefficient",
    "friction_torque", "gravity_torque", "hydrodynamic_torque", "inertia_torque",
    "pressure_torque",
    "compare_run", "compare_irregular_run", "steady_window", "summarise_run",
]
