"""The ball-screw wave energy converter of Senatore & De Simone (2022).

The buoy and its inverse dynamics (:mod:`~flumekit.ballscrew.buoy`), the ball screw and its
efficiency (:mod:`~flumekit.ballscrew.screw`), elastohydrodynamic lubrication of the ball
contacts (:mod:`~flumekit.ballscrew.ehl`) and the thermal models
(:mod:`~flumekit.ballscrew.thermal`).
"""


from flumekit.lazy import attach

# public names by the module that defines them, each imported on first use so that
# importing the package stays cheap
__getattr__, __dir__, __all__ = attach(
    __name__, globals(),
    buoy=["kinematics", "inverse_dynamics", "BuoyGeometry", "reference_motion", "forward_dynamics",
          "lift_from_energy_balance"],
    screw=["efficiency", "BallScrew", "Lubricant", "PTOCoefficients", "pto_state",
           "indirect_efficiency", "sea_state_motion"],
    ehl=["hertz_contact", "film_thickness", "stribeck_friction"],
    scenario=["reference_scenario", "stated_results"],
)
