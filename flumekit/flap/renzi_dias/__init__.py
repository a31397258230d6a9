"""The semi-analytic model of a bottom-hinged flap in a channel (Renzi & Dias 2012, 2013).

:mod:`~flumekit.flap.renzi_dias.model` solves the hypersingular integral equation and returns the
coefficients; :mod:`~flumekit.flap.renzi_dias.eigenmodes` and
:mod:`~flumekit.flap.renzi_dias.hypersingular` hold the channel eigenmodes and the kernels.
"""


from flumekit.lazy import attach

# public names by the module that defines them, each imported on first use so that
# importing the package stays cheap
__getattr__, __dir__, __all__ = attach(
    __name__, globals(),
    model=["solve", "coefficients", "excitation", "reflection", "transmission",
           "sloshing_cutoff_periods", "two_dimensional"],
    eigenmodes=["vertical_modes"],
)
