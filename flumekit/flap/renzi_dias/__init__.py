"""The semi-analytic model of a bottom-hinged flap in a channel (Renzi & Dias 2012, 2013).

:mod:`~flumekit.flap.renzi_dias.model` solves the hypersingular integral equation and returns the
coefficients; :mod:`~flumekit.flap.renzi_dias.eigenmodes` and
:mod:`~flumekit.flap.renzi_dias.hypersingular` hold the channel eigenmodes and the kernels.
"""
