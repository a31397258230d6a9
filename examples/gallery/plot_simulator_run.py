"""
A simulator run: free decay of a flap
=====================================

:func:`flumekit.flap.simulator.simulate` integrates the flap's equation of motion (Cummins'
equation with a power take-off) in the time domain. Without excitation and radiation memory,
with a linear restoring torque and a linear damper, the flap released from θ0 is a damped
oscillator whose exact solution is known; the simulated decay follows it.
"""

import matplotlib.pyplot as plt
import numpy as np

from flumekit.flap.simulator import FlapDynamics, LinearDamper, simulate

inertia, stiffness, damping, theta0 = 2.0, 60.0, 1.5, 0.1  # [kg m2], [N m/rad], [N m s], [rad]
run = simulate(None, FlapDynamics(inertia=inertia, added_inertia_infinite=0.5,
                                  hydrostatic_stiffness=stiffness),
               None, LinearDamper(damping=damping), dt=0.01, duration=20.0, theta0=theta0)

# %%
# The exact damped oscillation θ(t) = θ0 e^(-ζωt) (cos ω_d t + ζω/ω_d sin ω_d t):
t = run["time"].values
omega = np.sqrt(stiffness / (inertia + 0.5))
zeta = damping / (2 * (inertia + 0.5) * omega)
omega_d = omega * np.sqrt(1 - zeta**2)
exact = theta0 * np.exp(-zeta * omega * t) * (np.cos(omega_d * t)
                                              + zeta * omega / omega_d * np.sin(omega_d * t))
error = np.max(np.abs(run["theta"].values - exact))
print(f"largest difference from the exact solution: {error:.2e} rad")

fig, ax = plt.subplots(figsize=(7, 2.6), layout="constrained")
ax.plot(t, run["theta"].values, label="simulated")
ax.plot(t, exact, "--", label="exact")
ax.set_xlabel("time [s]")
ax.set_ylabel("flap angle θ [rad]")
ax.legend()
