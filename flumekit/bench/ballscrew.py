"""Accuracy versus run time of the coupled multibody-EHL efficiency step (one wave period).

Knobs: samples per wave period of the kinematic input, and the number of fixed-point
iterations between efficiency, ball load and film thickness. Errors of the cycle-mean loss
power and of the cycle-mean efficiency against a fine, fully converged reference (16384 samples,
iterated to 1e-12). Also the lumped thermal model: exact discretisation vs explicit Euler.

Last, the paper's stated results for its reference scenario against flumekit's
(:mod:`flumekit.ballscrew.scenario`), with how close the FEM field is to its steady state at
100 min (the paper says steady; the FEM's slowest mode, rotor and shaft, has τ ≈ 38 min).

Run: ``flumekit bench ballscrew`` (``--quick`` for a short table).
"""

from __future__ import annotations

import numpy as np

from flumekit.ballscrew import buoy, scenario
from flumekit.ballscrew import screw as ballscrew
from flumekit.ballscrew.thermal import fem
from flumekit.ballscrew.thermal import lumped as thermal_lumped
from flumekit.bench import best_time


def _state(samples: int, iterations: int):
    kin = buoy.kinematics(buoy.reference_motion(1.0, 3.8, 1, samples))
    return ballscrew.pto_state(kin["nut_velocity"].values, kin["nut_acceleration"].values,
                               iterations=iterations, tolerance=0.0 if iterations < 50 else 1e-12)



def run(quick: bool = False) -> str:
    """Run the benchmark and return its tables as text.

    Parameters
    ----------
    quick : bool
        Three sample counts, three iteration counts and two time steps instead of seven, five
        and four.

    Returns
    -------
    str
        The printed tables: loss and efficiency errors against samples and iterations, the
        lumped thermal model's error against the time step, the paper's stated results and
        the FEM's share of its steady rise.
    """
    ref = _state(16384, 100)
    loss_ref = ref["mechanical_power_loss"].mean()
    eta_ref = ref["ballscrew_efficiency"].mean()
    rows = ["efficiency step, reference motion (A = 1 m, T = 3.8 s), one period",
            f"reference: 16384 samples, converged: mean loss {loss_ref:.3f} W, "
            f"mean efficiency {eta_ref:.6f}",
            f"{'samples':>7} {'iter':>4} {'loss error [%]':>14} {'eta_mean error':>14} "
            f"{'time [ms]':>9}"]
    samples = [64, 256, 1024] if quick else [32, 64, 128, 256, 512, 1024, 4096]
    iterations = [1, 2, 4] if quick else [1, 2, 3, 4, 8]
    for n in samples:
        for it in iterations:
            sec, st = best_time(lambda n=n, it=it: _state(n, it))
            err_l = 100 * abs(st["mechanical_power_loss"].mean() / loss_ref - 1)
            err_e = abs(st["ballscrew_efficiency"].mean() - eta_ref)
            rows.append(f"{n:>7} {it:>4} {err_l:>14.4f} {err_e:>14.2e} {sec * 1e3:>9.2f}")
    # lumped thermal model: exact discretisation vs explicit Euler, 6000 s of constant sources
    p = thermal_lumped.LumpedThermal()
    src = np.array([600.0, 170.0, 160.0])
    c, k, air = thermal_lumped.system_matrices(p)
    rows += ["", "lumped model, 6000 s, constant sources: exact (any step) vs explicit Euler",
             f"{'dt [s]':>7} {'exact err [K]':>13} {'Euler err [K]':>13} {'exact [ms]':>10}"]
    fine, _ = thermal_lumped.integrate(0.01, np.tile(src, (600000, 1)), p)
    for dt in ([60.0, 10.0] if quick else [600.0, 60.0, 10.0, 1.0]):
        n = int(6000 / dt)
        sec, (temp, _) = best_time(
            lambda dt=dt, n=n: thermal_lumped.integrate(dt, np.tile(src, (n, 1)), p))
        x = np.full(3, p.initial_temperature)
        for _ in range(n):  # the explicit scheme, for comparison only
            x = x + dt * (src + air - k @ x) / c
        rows.append(f"{dt:>7.0f} {np.max(np.abs(temp[-1] - fine[-1])):>13.2e} "
                    f"{np.max(np.abs(x - fine[-1])):>13.2e} {sec * 1e3:>10.3f}")
    eff, th, fem_ds = scenario.reference_scenario()
    rows += ["", "Senatore & De Simone (2022), reference scenario: stated results",
             scenario.table(scenario.stated_results(eff, th, fem_ds)), "",
             "FEM at 100 min, share of the steady rise (mean of the last cycle) per control point"]
    system, _ = fem.assemble_pto(fem.PTOGeometry())
    sources = fem.source_powers(th, th.sizes["time"] - 1)  # one step: the mean over the run
    steady = fem.solve_steady(system, {g: float(p[0]) for g, p in sources.items()
                                       if g in system.unit_loads})
    pts = np.stack([fem_ds["control_radius"].values, fem_ds["control_axial"].values])
    t0 = float(th.attrs["initial_temperature"])
    rise_ss = system.basis.probes(pts) @ steady - t0
    last = fem_ds["control_temperature"].sel(time=slice(5400.0, 6000.0)).mean("time").values
    for name, a, b in zip(fem_ds["control_point"].values, last - t0, rise_ss):
        rows.append(f"  {name:<20} {a:6.1f} K of {b:6.1f} K  ({100 * a / b:5.1f} %)")
    return "\n".join(rows)


if __name__ == "__main__":
    print(run())
