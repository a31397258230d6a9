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
}

__all__ = sorted(_LAZY)


__getattr__, __dir__ = lazy_names(__name__, _LAZY, globals())
