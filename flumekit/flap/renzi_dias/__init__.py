"""The semi-analytic model of a bottom-hinged flap in a channel (Renzi & Dias 2012, 2013).

:mod:`~flumekit.flap.renzi_dias.model` solves the hypersingular integral equation and returns the
coefficients; :mod:`~flumekit.flap.renzi_dias.eigenmodes` and
:mod:`~flumekit.flap.renzi_dias.hypersingular` hold the channel eigenmodes and the kernels.
"""


from flumekit.lazy import lazy_names

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


__getattr__, __dir__ = lazy_names(__name__, _LAZY, globals())
