"""The ball-screw wave energy converter of Senatore & De Simone (2022).

The buoy and its inverse dynamics (:mod:`~flumekit.ballscrew.buoy`), the ball screw and its
efficiency (:mod:`~flumekit.ballscrew.screw`), elastohydrodynamic lubrication of the ball
contacts (:mod:`~flumekit.ballscrew.ehl`) and the thermal models
(:mod:`~flumekit.ballscrew.thermal`).
"""


import importlib

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


def __getattr__(name: str):
    if name not in _LAZY:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    value = getattr(importlib.import_module(f"{__name__}.{_LAZY[name]}"), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__))
