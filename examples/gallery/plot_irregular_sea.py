"""
An irregular sea: spectrum, sea-state parameters and wave heights
=================================================================

A 20-minute record of a JONSWAP sea (Hm0 = 0.10 m, Tp = 2 s, γ = 3.3) in 0.5 m of water,
sampled at 25 Hz, is synthesised as linear random-phase waves
(:func:`flumekit.synth.waves.irregular_wave_field`). Its variance density is estimated by
Welch's method with a 90 % confidence interval (:func:`flumekit.waves.spectrum`) and reduced to
the sea-state parameters (:func:`flumekit.waves.spectral_parameters`) and the finite-depth
energy flux (:func:`flumekit.waves.spectral_energy_flux`); the zero up-crossing waves
(:func:`flumekit.waves.wave_statistics`) give H1/3, Hmax and the distribution of the heights,
drawn against the Rayleigh distribution of a narrow-band sea.
"""

import matplotlib.pyplot as plt
import numpy as np

import flumekit
from flumekit.synth import irregular_wave_field, jonswap

fs, duration, depth = 25.0, 1200.0, 0.5  # [Hz], [s], [m]
time = np.arange(int(duration * fs)) / fs
sea = irregular_wave_field(time, [0.0], hm0=0.10, peak_period=2.0, depth=depth, gamma=3.3,
                           reflection=0.0, rng=1)
eta = sea["eta"].isel(x=0)  # surface elevation [m] over time [s]

# %%
# Spectrum, parameters and zero-crossing statistics, with public names only:
spec = flumekit.waves.spectrum(eta, confidence=0.90)
params = flumekit.waves.spectral_parameters(spec.variance_density)
waves = flumekit.waves.wave_statistics(eta)
flux = flumekit.waves.spectral_energy_flux(spec.variance_density, depth)
print(f"Hm0 = {float(params.hm0):.4f} m, Tp = {float(params.tp):.2f} s "
      f"(smoothed {float(params.tp_smoothed):.2f} s), Te = {float(params.tm_10):.2f} s, "
      f"Tm02 = {float(params.tm02):.2f} s, Qp = {float(params.peakedness):.2f}")
print(f"{int(waves.number_of_waves)} waves: H1/3 = {float(waves.h1_3):.4f} m, "
      f"Hmax = {float(waves.hmax):.4f} m, Tz = {float(waves.tz):.2f} s; "
      f"J = {float(flux):.1f} W/m; ν = {spec.equivalent_degrees_of_freedom:.1f}")

# %%
# The estimate with its confidence band against the target spectrum, and the heights against
# Rayleigh, p(H) = 2H/Hrms² exp(-H²/Hrms²) with Hrms = sqrt(8 m0):
f = spec.frequency.values
target = jonswap(f, 0.10, 2.0, 3.3)
fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(7, 2.8), layout="constrained")
ax1.fill_between(f, spec.variance_density_lower, spec.variance_density_upper, color="0.8",
                 label="90 % interval")
ax1.plot(f, spec.variance_density, lw=1, label="Welch estimate")
ax1.plot(f, target, "k--", lw=1, label="target JONSWAP")
ax1.set_xlim(0, 1.5)
ax1.set_xlabel("frequency [Hz]")
ax1.set_ylabel("variance density [m² s]")
ax1.legend(fontsize=8)

hm0 = float(params.hm0)
h = waves.individual_wave_height.values / hm0
x = np.linspace(0, 2.2, 200)
hrms = np.sqrt(8 * float(params.m0)) / hm0
ax2.hist(h, bins=25, density=True, color="0.7", label="zero up-crossing waves")
ax2.plot(x, 2 * x / hrms**2 * np.exp(-(x / hrms) ** 2), "k", label="Rayleigh")
ax2.set_xlabel("wave height H / Hm0 [-]")
ax2.set_ylabel("probability density [-]")
ax2.legend(fontsize=8)
