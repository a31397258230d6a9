"""Thermal models of the ball-screw power take-off.

Lumped (Senatore & De Simone 2022, Eqs. 8-10, :mod:`~flumekit.ballscrew.thermal.lumped`) and
axisymmetric finite elements (:mod:`~flumekit.ballscrew.thermal.fem`).
"""


from flumekit.lazy import lazy_names

#: public name -> module of this package (imported on first use, so that importing the
#: package stays cheap)
_LAZY = {
    "thermal_lumped": "lumped",
    "thermal_fem": "fem",
}

__all__ = sorted(_LAZY)


__getattr__, __dir__ = lazy_names(__name__, _LAZY, globals())
