"""The models stage's parameters and the choices of ``linear_pto_damping``.

Kept apart from :mod:`flumekit.stages.models`, which wires the rules.
"""

from __future__ import annotations

DEFAULTS = {"coefficients": "renzi_dias", "omega_min": 0.4, "omega_max": 25.0, "n_omega": 400,
            "bem_omega_min": 1.0, "bem_omega_max": 12.0, "bem_n_omega": 40,
            "bem_panel_size": 0.05, "dt": 0.04, "simulator": True, "friction": True,
            "spin_up_periods": 20, "irf_duration": 30.0,
            "linear_pto_damping": "energy_equivalent"}
DOCS = {
    "coefficients": "hydrodynamic coefficients: 'renzi_dias' (thin plate in the channel) or "
                    "'bem' (Capytaine, thick flap, open water)",
    "omega_min": "Renzi-Dias frequency grid: lowest angular frequency [rad s-1]",
    "omega_max": "Renzi-Dias frequency grid: highest angular frequency [rad s-1]",
    "n_omega": "Renzi-Dias frequency grid: number of frequencies [-]",
    "bem_omega_min": "BEM frequency grid: lowest angular frequency [rad s-1]",
    "bem_omega_max": "BEM frequency grid: highest angular frequency [rad s-1]",
    "bem_n_omega": "BEM frequency grid: number of frequencies [-]",
    "bem_panel_size": "BEM panel size [m]",
    "dt": "time step of the time-domain simulator [s]",
    "simulator": "run the time-domain simulator beside the linear model",
    "friction": "include the campaign's LuGre PTO friction in the simulator",
    "spin_up_periods": "periods of the incident wave the simulator runs before the compared "
                       "window [-]",
    "irf_duration": "length of the radiation impulse response K(t) of the simulator [s]",
    "linear_pto_damping": "PTO damping of the linear model (Eq. A1): 'energy_equivalent' "
                          "(measured mean power / mean(theta_dot^2)) or 'optimal' (maximum "
                          "power at the run's period, Renzi & Dias 2012 Eq. 2.40)",
}


#: the choices of ``linear_pto_damping``, :data:`flumekit.flap.comparison.LINEAR_PTO_DAMPING`
#: repeated (tests/stages checks they agree): planning imports no flumekit.flap (numpy, scipy)
LINEAR_PTO_DAMPING = ("energy_equivalent", "optimal")
