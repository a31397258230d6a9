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


from flumekit.lazy import lazy_names

#: public name -> module of this package (imported on first use, so that importing the
#: package stays cheap)
_LAZY = {
    "hydro_dataset": "coefficients",
    "from_capytaine": "coefficients",
    "from_renzi_dias": "coefficients",
    "passivity_report": "coefficients",
    "infinite_frequency_inertia": "coefficients",
    "read_capytaine": "capytaine",
    "read_wamit": "wamit",
    "impulse_response": "radiation",
    "fit_state_space": "radiation",
    # the frequency-domain response itself is flumekit.hydro.response.response: a name of
    # the package equal to its submodule's would hide the submodule from `from ... import`
    "optimal_pto_damping": "response",
    "excitation_torque": "excitation",
    "simulate": "simulation",
    "with_infinite_frequency_inertia": "coefficients",
    "from_kernel": "coefficients",
    "split_complex": "coefficients",
    "merge_complex": "coefficients",
    "rigid_body_dataset": "rigid_body",
    "about_hinge": "rigid_body",
    "inertia_about_hinge": "rigid_body",
    "state_space_dataset": "radiation",
    "state_space_from_dataset": "radiation",
}

__all__ = sorted(_LAZY)


__getattr__, __dir__ = lazy_names(__name__, _LAZY, globals())
