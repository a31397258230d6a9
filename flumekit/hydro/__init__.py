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


from flumekit.lazy import attach

# public names by the module that defines them, each imported on first use so that
# importing the package stays cheap
__getattr__, __dir__, __all__ = attach(
    __name__, globals(),
    coefficients=["hydro_dataset", "from_capytaine", "from_renzi_dias", "passivity_report",
                  "infinite_frequency_inertia", "with_infinite_frequency_inertia", "from_kernel",
                  "split_complex", "merge_complex"],
    capytaine=["read_capytaine"],
    wamit=["read_wamit"],
    radiation=["impulse_response", "fit_state_space", "state_space_dataset",
               "state_space_from_dataset"],
    # the frequency-domain response itself is flumekit.hydro.response.response: a name of
    # the package equal to its submodule's would hide the submodule from `from ... import`
    response=["optimal_pto_damping"],
    excitation=["excitation_torque"],
    simulation=["simulate"],
    rigid_body=["rigid_body_dataset", "about_hinge", "inertia_about_hinge"],
)
