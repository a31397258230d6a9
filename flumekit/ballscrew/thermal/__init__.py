"""Thermal models of the ball-screw power take-off: lumped (Eqs. 8-10,
:mod:`~flumekit.ballscrew.thermal.lumped`) and axisymmetric finite elements
(:mod:`~flumekit.ballscrew.thermal.fem`)."""


import importlib

#: public name -> module of this package (imported on first use, so that importing the
#: package stays cheap)
_LAZY = {
    "thermal_lumped": "lumped",
    "thermal_fem": "fem",
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
