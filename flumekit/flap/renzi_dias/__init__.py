"""The semi-analytic model of a bottom-hinged flap in a channel (Renzi & Dias 2012, 2013).

:mod:`~flumekit.flap.renzi_dias.model` solves the hypersingular integral equation and returns the
coefficients; :mod:`~flumekit.flap.renzi_dias.eigenmodes` and
:mod:`~flumekit.flap.renzi_dias.hypersingular` hold the channel eigenmodes and the kernels.
"""


import importlib

#: public name -> module of this package (imported on first use, so that importing the
#: package stays cheap)
_LAZY = {
    "solve": "model",
    "coefficients": "model",
    "excitation": "model",
    "reflection": "model",
    "transmission": "model",
    "sloshing_cutoff_periods": "model",
    "two_dimensional": "model",
    "vertical_modes": "eigenmodes",
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
