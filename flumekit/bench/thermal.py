"""Accuracy versus run time of the PTO thermal FEM (mesh size, element order, time step).

The 600 s operating cycle of the reference scenario (sinusoidal z(t), A = 1 m, T = 3.8 s) is
solved on a range of meshes and steps; the error is the largest deviation of the control-point
temperatures from a fine reference (Q2, 1.25 mm x 5 mm, Δt = 1 s; 2.5 x 10 mm when quick),
every 60 s, relative to the largest temperature rise of the reference. Target: 1 % error in
≤ 1 s; the error floor (a few hundredths of a per cent) comes from the step-mean source
timing.

A second table shows the effect of factorising the system matrix once (splu, one triangular
solve per step) against a sparse direct solve at every step.

Run: ``python -m flumekit.bench.thermal`` (``run(quick=True)`` for a short table).
"""

from __future__ import annotations

import numpy as np
from scipy.sparse import linalg as spla

from flumekit.ballscrew import buoy
from flumekit.ballscrew import screw as ballscrew
from flumekit.ballscrew.thermal import fem as thermal_fem
from flumekit.ballscrew.thermal import lumped as thermal_lumped
from flumekit.bench import best_time


def _scenario():
    kin = buoy.kinematics(buoy.reference_motion(1.0, 3.8, 1, 760))
    eff = ballscrew.efficiency(kin)
    return thermal_lumped.thermal_lumped(eff, total_duration=600.0, time_step=1.0)



def _error(fe, ref, t0: float) -> float:
    times = np.arange(60.0, 600.0 + 1e-9, 60.0)
    a = fe["control_temperature"].sel(time=times).values
    b = ref["control_temperature"].sel(time=times).values
    return float(np.max(np.abs(a - b)) / np.max(b - t0))


def _naive(lumped, time_step, cell_r, cell_z):
    """Run BDF2 with a sparse direct solve at every step (the comparison for the factorisation)."""
    system, _ = thermal_fem.assemble_pto(thermal_fem.PTOGeometry(), cell_r, cell_z, 1)
    factor = int(round(time_step))
    powers = thermal_fem.source_powers(lumped, factor)
    m, k = system.capacity, system.stiffness
    a = (1.5 / time_step * m + k).tocsc()
    t = np.full(system.basis.N, 293.15)
    t_prev = t.copy()
    for n in range(next(iter(powers.values())).size):
        rhs = system.load + sum(p[n] * system.unit_loads[g] for g, p in powers.items())
        t, t_prev = spla.spsolve(a, m @ (2 * t - 0.5 * t_prev) / time_step + rhs), t
    return t


def run(quick: bool = False) -> str:
    """Run the benchmark and return its tables as text.

    Parameters
    ----------
    quick : bool
        A coarser reference (2.5 x 10 mm), two meshes, three steps and first order only.

    Returns
    -------
    str
        The printed tables: error and time per element order, mesh and time step, then one
        factorisation against a solve at every step.
    """
    lumped = _scenario()
    t0 = float(lumped.attrs["initial_temperature"])
    ref_cell = (0.0025, 0.01) if quick else (0.00125, 0.005)
    ref_t, ref = best_time(lambda: thermal_fem.thermal_fem(
        lumped, time_step=1.0, radial_cell_size=ref_cell[0], axial_cell_size=ref_cell[1],
        order=2, snapshot_times=(600.0,)), 1)
    meshes = [(0.01, 0.04), (0.005, 0.02)] if quick else [(0.01, 0.04), (0.005, 0.02),
                                                          (0.0025, 0.01)]
    steps = [60.0, 20.0, 5.0] if quick else [60.0, 30.0, 20.0, 10.0, 5.0, 2.0]
    orders = [1] if quick else [1, 2]
    rows = [f"reference: Q2, {ref_cell[0] * 1e3:g} x {ref_cell[1] * 1e3:g} mm, dt = 1 s, "
            f"{ref.attrs['n_dofs']} dofs, {ref_t:.2f} s",
            f"{'order':>5} {'dr [mm]':>7} {'dz [mm]':>7} {'dofs':>6} {'dt [s]':>6} "
            f"{'error [%]':>9} {'time [s]':>8} {'target':>6}"]
    for order in orders:
        for cr, cz in meshes:
            for dt in steps:
                sec, fe = best_time(
                    lambda dt=dt, cr=cr, cz=cz, order=order: thermal_fem.thermal_fem(
                        lumped, time_step=dt, radial_cell_size=cr, axial_cell_size=cz,
                        order=order, snapshot_times=(600.0,)),
                    1 if quick else 2)
                err = 100 * _error(fe, ref, t0)
                ok = "yes" if (err <= 1.0 and sec <= 1.0) else ""
                rows.append(f"{order:>5} {cr * 1e3:>7.2f} {cz * 1e3:>7.1f} {fe.attrs['n_dofs']:>6} "
                            f"{dt:>6.0f} {err:>9.3f} {sec:>8.3f} {ok:>6}")
    rows.append("")
    rows.append("factorise once vs solve every step (Q1, 2.5 x 10 mm, dt = 2 s, 300 steps):")
    sec_fast, _ = best_time(lambda: thermal_fem.thermal_fem(
        lumped, time_step=2.0, radial_cell_size=0.0025, axial_cell_size=0.01, order=1,
        snapshot_times=(600.0,)), 2)
    sec_slow, _ = best_time(lambda: _naive(lumped, 2.0, 0.0025, 0.01), 1)
    rows.append(f"  splu once + triangular solves: {sec_fast:.3f} s;  spsolve per step: "
                f"{sec_slow:.3f} s  (x{sec_slow / sec_fast:.1f})")
    return "\n".join(rows)


if __name__ == "__main__":
    print(run())
