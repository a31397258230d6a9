"""Thermal models of the ball-screw power take-off: lumped (Eqs. 8-10,
:mod:`~flumekit.ballscrew.thermal.lumped`) and axisymmetric finite elements
(:mod:`~flumekit.ballscrew.thermal.fem`)."""
