"""Device-agnostic one-degree-of-freedom hydrodynamics.

The coefficient container (added inertia, radiation damping, excitation, passivity, Ogilvie's
infinite-frequency inertia) in :mod:`~flumekit.hydro.coefficients`; six-dof rigid-body BEM
results and their rotation about a hinge in :mod:`~flumekit.hydro.rigid_body`, read from
Capytaine (:mod:`~flumekit.hydro.capytaine`) or WAMIT (:mod:`~flumekit.hydro.wamit`) files; the
radiation impulse response and its state-space approximation in :mod:`~flumekit.hydro.radiation`;
the excitation filter in :mod:`~flumekit.hydro.excitation`; the frequency-domain response in
:mod:`~flumekit.hydro.response`. Usable for a pitching flap and a heaving buoy alike: nothing here
knows about a particular device.
"""
