"""The ball-screw wave energy converter of Senatore & De Simone (2022).

The buoy and its inverse dynamics (:mod:`~flumekit.ballscrew.buoy`), the ball screw and its
efficiency (:mod:`~flumekit.ballscrew.screw`), elastohydrodynamic lubrication of the ball
contacts (:mod:`~flumekit.ballscrew.ehl`) and the thermal models
(:mod:`~flumekit.ballscrew.thermal`).
"""
