"""Thermal models of the PTO: lumped Eqs. (8)-(10) (exact discretisation) and the axisymmetric
FEM, against the matrix exponential, energy conservation, the Bessel series of a convectively
cooled cylinder and the NAFEMS axisymmetric steady benchmark."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy import linalg, optimize, special

from flumekit import conventions
from flumekit.ballscrew import buoy
from flumekit.ballscrew import screw as ballscrew
from flumekit.ballscrew.thermal import fem as thermal_fem
from flumekit.ballscrew.thermal import lumped as thermal_lumped

P = thermal_lumped.LumpedThermal()


# --- lumped model ---------------------------------------------------------------------------

@settings(max_examples=25, deadline=None)
@given(st.floats(0.0, 2000.0), st.floats(0.0, 500.0), st.floats(0.0, 300.0),
       st.floats(0.5, 50.0), st.integers(1, 400))
def test_lumped_matches_matrix_exponential(q_gen, q_scr, q_nut, dt, n):
    src = np.tile([q_gen, q_scr, q_nut], (n, 1))
    temp, _ = thermal_lumped.integrate(dt, src, P)
    c, k, air = thermal_lumped.system_matrices(P)
    a = -k / c[:, None]
    b = (np.array([q_gen, q_scr, q_nut]) + air) / c
    t = n * dt
    # T(t) = e^{At} T0 + A^-1 (e^{At} - I) b, augmented-matrix form [[A, b], [0, 0]]
    aug = np.zeros((4, 4))
    aug[:3, :3], aug[:3, 3] = a, b
    expected = (linalg.expm(aug * t) @ np.append(np.full(3, P.initial_temperature), 1.0))[:3]
    assert temp[-1] == pytest.approx(expected, rel=1e-11, abs=1e-9)


def test_lumped_energy_conservation_over_a_cycle():
    rng = np.random.default_rng(3)
    n, dt = 600, 1.0  # one 600 s cycle, piecewise-constant random sources
    src = rng.uniform(0, 1, (n, 3)) * [900.0, 300.0, 200.0]
    temp, mean = thermal_lumped.integrate(dt, src, P)
    c, _, _ = thermal_lumped.system_matrices(P)
    stored = np.sum(c * (temp[-1] - temp[0]))
    t_air = np.array([P.air_temperature_generator, P.air_temperature_screw,
                      P.air_temperature_screw])
    conv = np.array([P.conductance_generator_air, P.conductance_screw_air, P.conductance_nut_air])
    to_air = dt * np.sum(conv * (mean - t_air))  # exact step means; the b-exchange cancels
    assert src.sum() * dt == pytest.approx(stored + to_air, rel=1e-12)


def test_lumped_steady_state_and_partition():
    q = thermal_lumped.heat_sources(np.array([1000.0]), np.array([0.0]), P)
    # Eqs. (9)-(10): 0.5 * 0.95 to the nut, 0.5*0.95 + 0.5*0.05 to the screw, 2.5 % to the bearing
    assert [q["screw"][0], q["nut"][0], q["bearing"][0]] == pytest.approx([500.0, 475.0, 25.0])
    src = np.tile([600.0, 170.0, 160.0], (50, 1))
    temp, _ = thermal_lumped.integrate(1e4, src, P)  # 50 x 1e4 s: far beyond all time constants
    c, k, air = thermal_lumped.system_matrices(P)
    assert temp[-1] == pytest.approx(np.linalg.solve(k, src[0] + air), rel=1e-12)


@pytest.fixture(scope="module")
def scenario():
    kin = buoy.kinematics(buoy.reference_motion(1.0, 3.8, 1, 760))
    eff = ballscrew.efficiency(kin)
    return eff, thermal_lumped.thermal_lumped(eff)


def test_operating_cycle_conserves_the_loss_energy(scenario):
    eff, _ = scenario
    cyc = thermal_lumped.operating_cycle(eff, P, 600.0, 7.5)
    dt = 3.8 / 760  # the efficiency record: one wave period, 760 samples
    n_full, rest = 157, int(round((600.0 - 157 * 3.8) / dt))  # 600 s = 157 periods + 3.4 s
    for name, x in (("mechanical_power_loss", eff["mechanical_power_loss"].values),
                    ("electrical_power_loss",
                         (1 - P.generator_efficiency) * eff["generator_power"].values)):
        energy = (n_full * x.sum() + x[:rest].sum()) * dt
        assert cyc[name].values.sum() * 7.5 == pytest.approx(energy, rel=1e-10)


def test_bad_thermal_inputs_raise(scenario):
    eff, _ = scenario
    with pytest.raises(ValueError, match="whole wave periods"):
        thermal_lumped.operating_cycle(eff.isel(time=slice(0, 500)))
    with pytest.raises(ValueError, match="divide"):
        thermal_lumped.operating_cycle(eff, P, 600.0, 7.0)
    with pytest.raises(ValueError, match="must be positive"):
        thermal_lumped.LumpedThermal(conductance_nut_air=0.0)
    with pytest.raises(ValueError, match="finite"):
        thermal_lumped.integrate(1.0, np.full((3, 3), np.nan), P)


def test_reference_nut_warms_by_about_40_degrees(scenario):
    _, th = scenario
    rise = th["temperature"].isel(time=-1) - P.initial_temperature
    nut = float(rise.sel(component="nut"))
    assert 30.0 < nut < 50.0  # paper: "a uniform temperature increase just above 40 °C"
    # 100 min reach steady state: the last 10 min change the nut by < 2 % of its rise
    last = th["temperature"].sel(component="nut")
    assert float(last.isel(time=-1) - last.sel(time=5400.0)) < 0.02 * nut
    # the exponential fit T0 + ΔT(1 - e^-t/τ) of Fig. 16 describes the nut within 1 K
    d, tau = float(th["temperature_rise_fit"].sel(component="nut")), float(
        th["time_constant_fit"].sel(component="nut"))
    t = th["time"].values
    fit = P.initial_temperature + d * (1 - np.exp(-t / tau))
    assert np.max(np.abs(fit - last.values)) < 1.0
    conventions.check(th)


# --- FEM: Bessel series of an infinite cylinder cooled by convection ---------------------------

def _bessel_cylinder(r, fourier, biot, n_terms=60):
    """θ/θ_i = Σ C_n exp(-ζ_n² Fo) J0(ζ_n r/R), ζ J1(ζ) = Bi J0(ζ) (Carslaw & Jaeger §7.7)."""
    f = lambda z: z * special.j1(z) - biot * special.j0(z)  # noqa: E731
    roots = []
    for j in range(n_terms):  # one root in each (jπ, (j+1)π) bracket of J0's zeros
        lo = special.jn_zeros(0, j)[-1] if j else 1e-12
        hi = special.jn_zeros(0, j + 1)[-1]
        roots.append(optimize.brentq(f, lo + 1e-12, hi - 1e-12))
    z = np.array(roots)
    c = 2 * special.j1(z) / (z * (special.j0(z) ** 2 + special.j1(z) ** 2))
    return (c * np.exp(-(z**2) * fourier) * special.j0(np.outer(r, z))).sum(axis=1)


def test_fem_cylinder_cooling_matches_bessel_series():
    biot, radius = 1.0, 1.0  # k = ρc = 1, h = Bi: Fo = t
    mesh = thermal_fem.tensor_mesh(np.linspace(0, radius, 21), [0.0, 0.05])  # insulated ends
    robin = [(thermal_fem.boundary_facets(mesh, lambda r, z: np.isclose(r, radius)), biot, 0.0)]
    system = thermal_fem.assemble(mesh, np.ones(mesh.nelements), np.ones(mesh.nelements),
                                  robin, order=2)
    pts = np.array([np.linspace(0, radius, 11), np.full(11, 0.025)])
    dt = 1e-3
    series, _ = thermal_fem.solve_transient(system, dt, 1.0, n_steps=1000,
                                            probes=system.basis.probes(pts))
    for fo in (0.05, 0.1, 0.3, 1.0):
        exact = _bessel_cylinder(pts[0], fo, biot)
        assert series[int(round(fo / dt))] == pytest.approx(exact, abs=1e-3)  # ≤ 0.1 % of θ_i


def test_fem_lumped_limit_of_a_conducting_cylinder():
    # k → ∞ (Bi = 1e-5): FEM must follow T0 + P/(hA) (1 - e^{-t hA/C}) with all 2π factors right
    r0, length, h, rc, power = 0.05, 0.2, 20.0, 3.6e6, 150.0
    mesh = thermal_fem.tensor_mesh(np.linspace(0, r0, 6), np.linspace(0, length, 9))
    robin = [(thermal_fem.boundary_facets(mesh, lambda r, z: r > 1e-12), h, 293.15)]
    cells = np.arange(mesh.nelements)
    system = thermal_fem.assemble(mesh, np.full(mesh.nelements, 1e5), np.full(mesh.nelements, rc),
                                  robin, sources={"heater": cells})
    area = 2 * np.pi * r0 * length + 2 * np.pi * r0**2
    cap = rc * np.pi * r0**2 * length
    dt, n = 5.0, 800
    series, _ = thermal_fem.solve_transient(system, dt, 293.15, {"heater": np.full(n, power)},
                                            probes=system.basis.probes(np.array([[0.0], [0.1]])))
    t = np.arange(n + 1) * dt
    exact = 293.15 + power / (h * area) * (1 - np.exp(-t * h * area / cap))
    assert series[:, 0] == pytest.approx(exact, abs=1e-3 * power / (h * area))


# --- FEM: NAFEMS axisymmetric steady benchmark ------------------------------------------------
# r in [0.02, 0.1] m, z in [0, 0.14] m, k = 52 W/m/K; T = 273.15 K on z = 0, z = 0.14, r = 0.1;
# heat flux 5e5 W/m² into the body on r = 0.02 for 0.04 < z < 0.10, insulated elsewhere.
# Reference T(r = 0.04, z = 0.04) = 332.97 K (NAFEMS, Cameron, Casey & Simpson, Benchmark Tests
# for Thermal Analysis; as in Mathematica's HeatTransfer-FEM-Stationary-2DAxisym-Single-0002
# and cpmech/pmsim examples/heat_mathematica_axisym_nafems.rs).

def _nafems(cell, order):
    r = thermal_fem.refine_points([0.02, 0.04, 0.1], cell)
    z = thermal_fem.refine_points([0.0, 0.04, 0.10, 0.14], cell)
    mesh = thermal_fem.tensor_mesh(r, z)
    flux = [(thermal_fem.boundary_facets(
        mesh, lambda rr, zz: np.isclose(rr, 0.02) & (zz > 0.04) & (zz < 0.10)), 5e5)]
    system = thermal_fem.assemble(mesh, np.full(mesh.nelements, 52.0), np.zeros(mesh.nelements),
                                  flux=flux, order=order)
    fixed = system.basis.get_dofs(lambda x: np.isclose(x[0], 0.1) | np.isclose(x[1], 0.0)
                                  | np.isclose(x[1], 0.14)).all()
    temp = thermal_fem.solve_steady(system, dirichlet_dofs=fixed, dirichlet_value=273.15)
    return float((system.basis.probes(np.array([[0.04], [0.04]])) @ temp)[0])


def test_nafems_axisymmetric_benchmark_and_convergence_order():
    q1 = [_nafems(h, 1) for h in (0.01, 0.005, 0.0025)]
    q2 = [_nafems(h, 2) for h in (0.02, 0.01, 0.005)]
    order_q1 = np.log2((q1[0] - q1[1]) / (q1[1] - q1[2]))
    order_q2 = np.log2((q2[0] - q2[1]) / (q2[1] - q2[2]))
    assert 1.8 < order_q1 < 2.3  # Q1: second order at a point away from the singular corners
    assert order_q2 > 3.0  # Q2: at least third order (observed ≈ 4, nodal superconvergence)
    assert q1[-1] == pytest.approx(332.97, abs=0.02)  # 2.5 mm Q1 mesh
    assert q2[-1] == pytest.approx(332.97, abs=0.005)  # reference given to 0.01 K


@pytest.fixture(scope="module")
def fem(scenario):
    _, th = scenario
    return thermal_fem.thermal_fem(th, time_step=20.0, radial_cell_size=0.01,
                                   axial_cell_size=0.04, snapshot_times=(641.0, 6000.0))


def test_fem_scenario_dataset(scenario, fem):
    _, th = scenario
    fe = fem
    conventions.check(fe)
    rise = fe["control_temperature"].isel(time=-1) - 293.15
    assert 25.0 < float(rise.sel(control_point="nut")) < 60.0  # order of 40 °C, as the lumped
    assert fe["temperature_field"].sizes == {"snapshot_time": 2, "node": fe.sizes["node"]}
    assert np.all(fe["temperature_field"].values >= 293.15 - 1e-6)  # heating only
    with pytest.raises(ValueError, match="multiple"):
        thermal_fem.thermal_fem(th, time_step=2.5)


def test_fem_snapshot_is_interpolated_between_steps(scenario):
    # 641 s lies between the 640 s and 660 s steps: its field is their linear blend
    _, th = scenario
    fe = thermal_fem.thermal_fem(th, time_step=20.0, radial_cell_size=0.01, axial_cell_size=0.04,
                                 snapshot_times=(640.0, 660.0, 641.0))
    f = fe["temperature_field"].values
    assert f[2] == pytest.approx(0.95 * f[0] + 0.05 * f[1], rel=1e-12)
    assert np.max(f[1] - f[0]) > 0.1  # the blend is not trivially equal


def test_figures_9_10_and_16_to_18(scenario, fem):
    from matplotlib.figure import Figure

    from flumekit.figures import ballscrew as figures

    _, th = scenario
    for number, ds in ((9, th), (10, fem), (16, th), (17, fem), (18, fem)):
        fig = figures.FIGURES[number](ds)
        assert isinstance(fig, Figure) and len(fig.axes) >= 1
