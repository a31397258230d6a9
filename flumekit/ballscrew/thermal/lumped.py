"""Lumped-parameter thermal model of the PTO: generator, screw and nut, Eqs. (8)-(10).

Senatore & De Simone 2022, Sect. 2:

    (m c_p dT/dt)_gen = a1 (T_air,1 - T_gen) + b (T_scr - T_gen) + Q_el                      (8)
    (m c_p dT/dt)_scr = b (T_gen - T_scr) + a2 (T_air,2 - T_scr)
                        + p_scr-nut r Q_mecc + p_scr-bea (1 - r) Q_mecc                       (9)
    (m c_p dT/dt)_nut = a3 (T_air,2 - T_nut) + (1 - p_scr-nut) r Q_mecc                       (10)

A linear ODE system C dT/dt = -K T + s(t) + A T_air. For inputs constant over each time step
it is solved exactly (exact discretisation): with x = T - T_ref (T_ref the steady state with
no sources) and the symmetric form S = C^-1/2 K C^-1/2 = V Λ Vᵀ, each mode obeys
z' = -λ z + g, whose step update z_{n+1} = e^{-λΔt} z_n + (1 - e^{-λΔt})/λ g_n is applied to
the whole time series at once by a first-order recursive filter (scipy.signal.lfilter). Step
means of T are exact too, so the energy balance closes to round-off.

The fraction (1 - p_scr-bea)(1 - r) Q_mecc of the mechanical loss goes to the support
bearing, which is not a lump (Eq. (9) only gives the screw its share); it leaves the model.

Note on notation: the text calls the ball-system fraction r, Eq. (11) calls it γ (= 95 %).
"""

from __future__ import annotations

from dataclasses import asdict, dataclass

import numpy as np
import xarray as xr
from scipy import optimize, signal

from flumekit import conventions
from flumekit.signal import UNIFORM_RTOL, uniform_step

COMPONENTS = ("generator", "screw", "nut")


@dataclass(frozen=True)
class LumpedThermal:
    """Parameters of Eqs. (8)-(10).

    The paper's values came from UMBRA and a Simulink fit and are not published. Ours are
    plausible for the PTO of :mod:`flumekit.ballscrew.screw`, each with its source below, and
    the three that the paper's statements constrain were chosen to meet them (Senatore & De
    Simone 2022, §3.2; ``flumekit bench ballscrew`` prints the table): electrical losses four
    times the frictional ones (``generator_efficiency``), the nut warming "just above 40 °C"
    (``conductance_nut_air``), every lump at steady state by 100 min (heat capacities and
    conductances give time constants of at most 20 min). The abstract's "maximum temperature
    increase of 40 °C" contradicts the body text (the nut rises just above 40 °C and the screw
    and generator "experience a more noticeable" increase); we follow the body text.

    heat_capacity_generator : 18 kJ/K, EMRG stator, ≈ 36 kg of laminations and copper
        (c_p ≈ 500 J/kg/K), the mass of a permanent-magnet machine of ≈ 100 N m peak torque.
    heat_capacity_screw : 8 kJ/K, 17 kg steel shaft (Ø 80 mm x 0.45 m threaded length).
    heat_capacity_nut : 4.2 kJ/K, 9 kg steel ball nut with flange (c_p = 470 J/kg/K).
    conductance_generator_air : a1 = 17 W/K, natural convection h ≈ 25 W/m²/K on a finned
        casing of ≈ 0.7 m² (fin area ratio ≈ 2.5 over the 0.27 m² envelope of the FEM model).
    conductance_screw_air : a2 = 4.8 W/K, h ≈ 20 W/m²/K on ≈ 0.24 m² of rotating shaft.
    conductance_nut_air : a3 = 3.5 W/K, h ≈ 32 W/m²/K on ≈ 0.11 m² of nut (forced by its
        motion, textbook range 10-100 W/m²/K for forced convection in air).
    conductance_screw_generator : b = 6 W/K, shaft-rotor fit and bearings.
    partition_screw_nut, partition_screw_bearing : p = 50 % (Eq. (11)).
    ball_system_fraction : r = 95 % (Eq. (11), "γ").
    generator_efficiency : 74 %, the EMRG's cycle-average electrical efficiency. For a
        permanent-magnet generator on a resistive load the copper losses are the fraction
        R_s/(R_s + R_load) of the absorbed power, so η = R_load/(R_s + R_load): 50 % at the
        maximum-power match, ≈ 90 % at the rated point of catalogue machines, which a
        reciprocating duty with two speed reversals per wave does not reach. 74 %
        (R_load ≈ 2.8 R_s) makes the electrical losses four times the frictional ones, as the
        paper states (§3.2).
    initial_temperature, air temperatures : T_0 = 20 °C (Eq. (11)).
    """

    heat_capacity_generator: float = 18000.0
    heat_capacity_screw: float = 8000.0
    heat_capacity_nut: float = 4200.0
    conductance_generator_air: float = 17.0
    conductance_screw_air: float = 4.8
    conductance_nut_air: float = 3.5
    conductance_screw_generator: float = 6.0
    partition_screw_nut: float = 0.5
    partition_screw_bearing: float = 0.5
    ball_system_fraction: float = 0.95
    generator_efficiency: float = 0.74
    initial_temperature: float = 293.15
    air_temperature_generator: float = 293.15
    air_temperature_screw: float = 293.15

    def __post_init__(self):
        """Check that every capacity, conductance and temperature is positive."""
        for name in ("heat_capacity_generator", "heat_capacity_screw", "heat_capacity_nut",
                     "conductance_generator_air", "conductance_screw_air",
                     "conductance_nut_air", "initial_temperature",
                     "air_temperature_generator", "air_temperature_screw"):
            if not getattr(self, name) > 0:
                raise ValueError(f"lumped thermal model: {name} must be positive "
                                 f"(a lump without convection never reaches steady state), "
                                 f"got {getattr(self, name)}")
        if self.conductance_screw_generator < 0:
            raise ValueError("lumped thermal model: contact conductance b must be >= 0")
        for name in ("partition_screw_nut", "partition_screw_bearing", "ball_system_fraction",
                     "generator_efficiency"):
            if not 0 <= getattr(self, name) <= 1:
                raise ValueError(f"lumped thermal model: {name} must lie in [0, 1]")


def electrical_loss(generator_power, generator_efficiency: float) -> np.ndarray:
    """Electrical losses of the EMRG, Q_el = (1 - η_gen) P_gen [W].

    Parameters
    ----------
    generator_power : Mechanical power absorbed by the generator [W].
    generator_efficiency : η_gen [1] (:class:`LumpedThermal` explains the default).
    """
    if not 0 < generator_efficiency <= 1:
        raise ValueError(f"generator efficiency must lie in (0, 1], got {generator_efficiency}")
    return (1.0 - generator_efficiency) * np.abs(np.asarray(generator_power, float))


def heat_sources(mechanical_loss, electrical_loss_, params: LumpedThermal) -> dict[str, np.ndarray]:
    """Heat generated in each lump, the source terms of Eqs. (8)-(10) [W].

    Returns
    -------
    dict with 'generator' = Q_el, 'screw' = p_sn r Q_m + p_sb (1 - r) Q_m,
    'nut' = (1 - p_sn) r Q_m and 'bearing' = (1 - p_sb)(1 - r) Q_m (leaves the model).
    """
    qm = np.asarray(mechanical_loss, float)
    p, pb = params.partition_screw_nut, params.partition_screw_bearing
    r = params.ball_system_fraction
    return {"generator": np.asarray(electrical_loss_, float) + 0.0 * qm,
            "screw": p * r * qm + pb * (1 - r) * qm,   # Eq. (9)
            "nut": (1 - p) * r * qm,                  # Eq. (10)
            "bearing": (1 - pb) * (1 - r) * qm}


def system_matrices(params: LumpedThermal) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """C (heat capacities [J K-1]), K (conductance matrix [W K-1]) and A T_air [W] of Eqs. (8)-(10).

    C dT/dt = -K T + A T_air + s with T = (T_gen, T_scr, T_nut).
    """
    p = params
    a1, a2, a3, b = (p.conductance_generator_air, p.conductance_screw_air,
                     p.conductance_nut_air, p.conductance_screw_generator)
    c = np.array([p.heat_capacity_generator, p.heat_capacity_screw, p.heat_capacity_nut])
    k = np.array([[a1 + b, -b, 0.0], [-b, b + a2, 0.0], [0.0, 0.0, a3]])
    air = np.array([a1 * p.air_temperature_generator, a2 * p.air_temperature_screw,
                    a3 * p.air_temperature_screw])
    return c, k, air


def integrate(time_step: float, sources: np.ndarray, params: LumpedThermal,
              initial_temperature=None) -> tuple[np.ndarray, np.ndarray]:
    """Exact solution of Eqs. (8)-(10) for sources constant over each step.

    Parameters
    ----------
    time_step : Δt [s].
    sources : (n, 3) heat to generator, screw, nut over each step [W] (step means).
    params : Model parameters.
    initial_temperature : (3,) T at t = 0 [K]; default ``params.initial_temperature``.

    Returns
    -------
    (T, T_mean): T at the n + 1 step boundaries, shape (n + 1, 3) [K]; exact step means of T,
    shape (n, 3) [K].
    """
    s = np.asarray(sources, float)
    if s.ndim != 2 or s.shape[1] != 3 or not np.all(np.isfinite(s)):
        raise ValueError("sources must be a finite (n, 3) array (generator, screw, nut) [W]")
    if not time_step > 0:
        raise ValueError(f"time step must be positive, got {time_step}")
    c, k, air = system_matrices(params)
    t_ref = np.linalg.solve(k, air)  # steady state without sources
    t0 = (np.full(3, params.initial_temperature) if initial_temperature is None
          else np.asarray(initial_temperature, float))
    ch = 1.0 / np.sqrt(c)
    lam, vec = np.linalg.eigh(ch[:, None] * k * ch[None, :])
    if np.any(lam <= 0):
        raise ValueError("conductance matrix is not positive definite")
    to_modal = vec.T * ch[None, :]  # z = Vᵀ C^1/2 x  (x = T - T_ref);  g = Vᵀ C^-1/2 s
    from_modal = vec * ch[:, None]  # x = C^-1/2 V z
    z0 = vec.T @ (np.sqrt(c) * (t0 - t_ref))
    g = s @ to_modal.T  # (n, 3)
    decay = np.exp(-lam * time_step)
    gain = -np.expm1(-lam * time_step) / lam
    z = np.empty((s.shape[0] + 1, 3))
    z[0] = z0
    for j in range(3):  # three modes; the recursion over time runs inside lfilter
        z[1:, j], _ = signal.lfilter([gain[j]], [1.0, -decay[j]], g[:, j], zi=[decay[j] * z0[j]])
    frac = gain / time_step  # (1 - e^{-λΔt}) / (λΔt)
    z_mean = z[:-1] * frac + g / lam * (1.0 - frac)
    return z @ from_modal.T + t_ref, z_mean @ from_modal.T + t_ref


def step_means(time, values, period: float, edges) -> np.ndarray:
    """Means of a periodic, uniformly sampled signal over the intervals [edges_i, edges_i+1).

    Each sample stands for [t_i, t_i + dt) (rectangle rule, exact for the piecewise-constant
    reading), the record repeats with ``period``; the cumulative integral is interpolated, so
    the energy of the signal is conserved whatever the step.
    """
    t = np.asarray(time, float)
    x = np.asarray(values, float)
    dt = period / t.size
    if abs(uniform_step(t, "periodic signal") - dt) > UNIFORM_RTOL * dt:
        raise ValueError("periodic signal must be uniformly sampled over exactly one period "
                         "(time[-1] + dt = period)")
    cum = np.concatenate([[0.0], np.cumsum(x) * dt])
    grid = t[0] + np.arange(t.size + 1) * dt
    e = np.asarray(edges, float) - t[0]
    n_per, phase = np.divmod(e, period)
    big = n_per * cum[-1] + np.interp(phase + t[0], grid, cum)
    return np.diff(big) / np.diff(e)


def operating_cycle(eff: xr.Dataset, params: LumpedThermal = LumpedThermal(),
                    cycle_duration: float = 600.0, time_step: float = 1.0) -> xr.Dataset:
    """Build the heat sources of one WEC operating cycle (the role of the paper's Fig. 9).

    The paper uses UMBRA's measured losses of a 600 s cycle; we build them from the efficiency
    dataset (which must hold whole wave periods): mechanical losses Q_mecc = friction and
    viscous losses of the PTO, electrical losses Q_el = (1 - η_gen) x generator power, both
    repeated periodically and averaged over steps of ``time_step`` (energy-exact).

    Returns
    -------
    Dataset over ``time`` (step starts, 0 ... cycle_duration - Δt) with mechanical_power_loss,
    electrical_power_loss [W].
    """
    if not (cycle_duration > 0 and time_step > 0):
        raise ValueError("cycle duration and time step must be positive")
    n = int(round(cycle_duration / time_step))
    if abs(n * time_step - cycle_duration) > 1e-9 * cycle_duration:
        raise ValueError(f"time step {time_step} s must divide the cycle {cycle_duration} s")
    t = eff["time"].values
    period = float(t[-1] - t[0] + (t[1] - t[0]))
    wave = float(eff.attrs.get("wave_period", period))
    if abs(period / wave - round(period / wave)) > 1e-6 or round(period / wave) < 1:
        raise ValueError(f"the efficiency record ({period:.6g} s) must hold whole wave periods "
                         f"({wave:.6g} s) to be repeated over the operating cycle")
    edges = np.arange(n + 1) * time_step
    qm = step_means(t, eff["mechanical_power_loss"].values, period, edges)
    qe = step_means(t, electrical_loss(eff["generator_power"].values,
                                       params.generator_efficiency), period, edges)
    ds = xr.Dataset({"mechanical_power_loss": ("time", qm), "electrical_power_loss": ("time", qe)},
                    coords={"time": edges[:-1]})
    ds.attrs.update(cycle_duration=cycle_duration, time_step=time_step)
    return conventions.annotate(ds)


def fit_exponential(time, temperature, initial_temperature: float) -> tuple[float, float]:
    """Least-squares fit T(t) = T0 + ΔT (1 - e^(-t/τ)) (the solid lines of Fig. 16).

    Returns
    -------
    (ΔT [K], τ [s]).
    """
    t = np.asarray(time, float)
    y = np.asarray(temperature, float) - initial_temperature
    rise = float(y[-1])
    if abs(rise) < 1e-12:
        return 0.0, float("inf")
    i63 = int(np.argmax(np.abs(y) >= 0.632 * abs(rise)))
    guess = (rise, max(float(t[i63] - t[0]), float(t[1] - t[0])))
    (d, tau), _ = optimize.curve_fit(lambda tt, d, tau: d * (1 - np.exp(-(tt - t[0]) / tau)),
                                     t, y, p0=guess, maxfev=10000)
    return float(d), float(tau)


def thermal_lumped(eff: xr.Dataset, params: LumpedThermal = LumpedThermal(),
                   cycle_duration: float = 600.0, total_duration: float = 6000.0,
                   time_step: float = 1.0) -> xr.Dataset:
    """Scenario step 3: temperatures of generator, screw and nut over repeated cycles (Fig. 16).

    Parameters
    ----------
    eff : Output of :func:`flumekit.ballscrew.screw.efficiency`.
    params : Lumped model parameters.
    cycle_duration : Length of the operating cycle [s] (600 s in the paper).
    total_duration : Simulated time [s] (100 min in the paper), the cycle repeated.
    time_step : Output step and source-averaging step [s]; the solution is exact for the
        step-averaged sources.

    Returns
    -------
    Dataset over ``time`` and ``component`` (generator, screw, nut) with ``temperature`` [K],
    the heat ``heat_source`` per component and the cycle's mechanical/electrical losses (step
    means starting at each time), and the exponential fits ``temperature_rise_fit``,
    ``time_constant_fit`` per component.
    """
    if not total_duration >= cycle_duration:
        raise ValueError("total duration must cover at least one cycle")
    cyc = operating_cycle(eff, params, cycle_duration, time_step)
    n = int(round(total_duration / time_step))
    reps = int(np.ceil((n + 1) / cyc.sizes["time"]))
    qm = np.tile(cyc["mechanical_power_loss"].values, reps)[: n + 1]
    qe = np.tile(cyc["electrical_power_loss"].values, reps)[: n + 1]
    src = heat_sources(qm, qe, params)
    s = np.stack([src[c] for c in COMPONENTS], axis=1)
    temp, _ = integrate(time_step, s[:-1], params)
    t = np.arange(n + 1) * time_step
    fits = [fit_exponential(t, temp[:, j], params.initial_temperature) for j in range(3)]
    ds = xr.Dataset(
        {"temperature": (("time", "component"), temp),
         "heat_source": (("time", "component"), s),
         "mechanical_power_loss": ("time", qm), "electrical_power_loss": ("time", qe),
         "bearing_heat_loss": ("time", src["bearing"]),
         "temperature_rise_fit": ("component", [f[0] for f in fits]),
         "time_constant_fit": ("component", [f[1] for f in fits])},
        coords={"time": t, "component": list(COMPONENTS)},
        attrs=conventions.global_attrs("PTO lumped thermal model (Eqs. 8-10)",
                                       "flumekit.ballscrew.thermal.lumped.thermal_lumped",
                                       {**asdict(params), "cycle_duration": cycle_duration,
                                        "total_duration": total_duration,
                                        "time_step": time_step}))
    ds.attrs.update({k: float(v) for k, v in asdict(params).items()})
    ds.attrs.update(cycle_duration=cycle_duration, time_step=time_step)
    return conventions.annotate(ds)
