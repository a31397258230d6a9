"""The ball-screw wave energy converter of Senatore & De Simone (2022).

The buoy and its inverse dynamics (:mod:`~flumekit.ballscrew.buoy`), the ball screw and its
efficiency (:mod:`~flumekit.ballscrew.screw`), elastohydrodynamic lubrication of the ball
contacts (:mod:`~flumekit.ballscrew.ehl`) and the thermal models
(:mod:`~flumekit.ballscrew.thermal`).
"""


from flumekit.lazy import lazy_names

#: public name -> module of this package (imported on first use, so that importing the
#: package stays cheap)
_LAZY = {
    "kinematics": "buoy",
    "inverse_dynamics": "buoy",
    "efficiency": "screw",
    "hertz_contact": "ehl",
    "film_thickness": "ehl",
    "reference_scenario": "scenario",
    "BuoyGeometry": "buoy",
    "reference_motion": "buoy",
    "forward_dynamics": "buoy",
    "lift_from_energy_balance": "buoy",
    "BallScrew": "screw",
    "Lubricant": "screw",
    "PTOCoefficients": "screw",
    "pto_state": "screw",
    "indirect_efficiency": "screw",
    "sea_state_motion": "screw",
    "stribeck_friction": "ehl",
    "stated_results": "scenario",
}

__all__ = sorted(_LAZY)


__getattr__, __dir__ = lazy_names(__name__, _LAZY, globals())
