"""Transient axisymmetric (r-z) heat conduction in the PTO by finite elements (scikit-fem).

The two-dimensional axially symmetric model of Senatore & De Simone 2022 (Fig. 10): screw
shaft, EMRG rotor and stator, air gap and nut, adiabatic on the symmetry axis, convection to
the air on the outer surfaces, and the heat sources of the lumped model (Eqs. (8)-(10): the
electrical losses in the stator, the screw's and nut's shares of the mechanical losses).

Weak form (divided by 2π): find T with
    ∫ ρc ∂T/∂t v r dA + ∫ k ∇T·∇v r dA + ∫_Γ h T v r ds = ∫ q v r dA + ∫_Γ (h T_∞ + q_n) v r ds,
quadrilateral Q1 or Q2 elements on a tensor mesh whose lines follow the region boundaries.
Time stepping: BDF2 (L-stable, second order) started by one backward-Euler step; both system
matrices are factorised once, so each step is one sparse triangular solve. Heat sources enter
as step means (energy-exact for sources that fluctuate within a step, like the wave-by-wave
losses).

The nut moves ±0.24 m along the screw in the reference scenario; the model keeps it at its mean
position and spreads the screw's share of the ball-system heat over the screw length swept by
the nut.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass, field

import numpy as np
import xarray as xr
from scipy.sparse import linalg as spla
from skfem import (
    Basis,
    BilinearForm,
    ElementQuad1,
    ElementQuad2,
    FacetBasis,
    LinearForm,
    MeshQuad,
    asm,
    condense,
)
from skfem.helpers import dot, grad

from flumekit import conventions
from flumekit.errors import GeometryError

# --- generic axisymmetric conduction kernel -----------------------------------------------


@BilinearForm
def _conduction(u, v, w):
    return w.k * dot(grad(u), grad(v)) * w.x[0]


@BilinearForm
def _capacity(u, v, w):
    return w.rc * u * v * w.x[0]


@BilinearForm
def _robin(u, v, w):
    return w.h * u * v * w.x[0]


@LinearForm
def _weighted_load(v, w):
    return w.q * v * w.x[0]


def tensor_mesh(r_points, z_points) -> MeshQuad:
    """Quadrilateral mesh on the tensor grid of sorted radial and axial node coordinates [m]."""
    r = np.unique(np.asarray(r_points, float))
    z = np.unique(np.asarray(z_points, float))
    if r.size < 2 or z.size < 2 or r[0] < 0:
        raise GeometryError("axisymmetric mesh needs >= 2 radial and axial nodes and r >= 0")
    return MeshQuad.init_tensor(r, z)


def refine_points(breaks, cell_size: float) -> np.ndarray:
    """Node coordinates containing every break point, with intervals split to ≤ cell_size."""
    b = np.unique(np.asarray(breaks, float))
    if not cell_size > 0:
        raise ValueError(f"cell size must be positive, got {cell_size}")
    pts = [b[:1]]
    for lo, hi in zip(b[:-1], b[1:]):  # loop over a handful of region boundaries
        n = max(1, int(np.ceil((hi - lo) / cell_size - 1e-9)))
        pts.append(np.linspace(lo, hi, n + 1)[1:])
    return np.concatenate(pts)


def boundary_facets(mesh: MeshQuad, where=None) -> np.ndarray:
    """Return the boundary facets whose midpoint (r, z) satisfies ``where(r, z)`` (all if None)."""
    f = mesh.boundary_facets()
    mid = mesh.p[:, mesh.facets[:, f]].mean(axis=1)
    if where is None:
        return f
    return f[np.asarray(where(mid[0], mid[1]), bool)]


@dataclass
class AxisymmetricSystem:
    """Assembled axisymmetric conduction system (all integrals divided by 2π).

    capacity : M [J K-1 / 2π]; stiffness : conduction + Robin [W K-1 / 2π];
    load : constant right-hand side (h T_∞ and prescribed fluxes) [W / 2π];
    unit_loads : per named source, the load vector of 1 W spread uniformly over its cells.
    """

    basis: Basis
    capacity: object
    stiffness: object
    load: np.ndarray
    unit_loads: dict[str, np.ndarray] = field(default_factory=dict)


def _cell_field(basis: Basis, values: np.ndarray) -> np.ndarray:
    return np.repeat(np.asarray(values, float)[:, None], basis.X.shape[1], axis=1)


def assemble(mesh: MeshQuad, conductivity, heat_capacity, robin=(), flux=(), sources=None,
             order: int = 1) -> AxisymmetricSystem:
    """Assemble the axisymmetric heat equation on a quadrilateral r-z mesh.

    Parameters
    ----------
    mesh : Quadrilateral mesh, x = r ≥ 0 (the axis r = 0 is adiabatic by symmetry).
    conductivity : k per cell [W m-1 K-1].
    heat_capacity : ρ c_p per cell [J m-3 K-1] (zeros allowed for steady problems).
    robin : Iterable of (facet indices, h [W m-2 K-1], T_∞ [K]) convective boundaries.
    flux : Iterable of (facet indices, q_n [W m-2]) heat flux into the body.
    sources : {name: cell indices}: for each, a unit-power load vector (1 W total, uniform
        volumetric density over the cells, 2π r weighting).
    order : 1 (Q1) or 2 (Q2) elements.
    """
    if order not in (1, 2):
        raise ValueError(f"element order must be 1 or 2, got {order}")
    if np.any(mesh.p[0] < -1e-14):
        raise GeometryError("axisymmetric mesh has points with r < 0")
    k = np.asarray(conductivity, float)
    rc = np.asarray(heat_capacity, float)
    if k.shape != (mesh.nelements,) or rc.shape != (mesh.nelements,):
        raise ValueError("conductivity and heat capacity need one value per cell")
    if np.any(k <= 0) or np.any(rc < 0):
        raise ValueError("conductivity must be > 0 and heat capacity >= 0 in every cell")
    elem = ElementQuad1() if order == 1 else ElementQuad2()
    basis = Basis(mesh, elem, intorder=2 * order + 1)
    kk = asm(_conduction, basis, k=_cell_field(basis, k))
    mm = asm(_capacity, basis, rc=_cell_field(basis, rc))
    load = np.zeros(basis.N)
    for facets, h, t_inf in robin:
        if h < 0:
            raise ValueError("convection coefficient must be >= 0")
        fb = FacetBasis(mesh, elem, facets=np.asarray(facets), intorder=2 * order + 1)
        kk = kk + asm(_robin, fb, h=h)
        load += asm(_weighted_load, fb, q=h * t_inf)
    for facets, q in flux:
        fb = FacetBasis(mesh, elem, facets=np.asarray(facets), intorder=2 * order + 1)
        load += asm(_weighted_load, fb, q=q)
    unit = {}
    for name, cells in (sources or {}).items():
        cells = np.asarray(cells)
        if cells.size == 0:
            raise GeometryError(f"heat source '{name}' has no cells")
        sub = Basis(mesh, elem, elements=cells, intorder=2 * order + 1)
        vec = asm(_weighted_load, sub, q=1.0)
        unit[name] = vec / (2 * np.pi * vec.sum())  # 1 W in total (∫ r dA = sum of the vector)
    return AxisymmetricSystem(basis, mm.tocsc(), kk.tocsc(), load, unit)


def solve_steady(system: AxisymmetricSystem, powers: dict[str, float] | None = None,
                 dirichlet_dofs=None, dirichlet_value: float = 0.0) -> np.ndarray:
    """Steady temperature [K]: K T = load + Σ P_g unit_g, optional fixed temperatures."""
    rhs = system.load + sum(p * system.unit_loads[g] for g, p in (powers or {}).items())
    if dirichlet_dofs is None:
        return spla.spsolve(system.stiffness, rhs)
    x = np.zeros(system.basis.N)
    x[dirichlet_dofs] = dirichlet_value
    return condense_solve(system.stiffness, rhs, x, dirichlet_dofs)


def condense_solve(a, b, x, dofs) -> np.ndarray:
    """Solve A x = b with x prescribed on ``dofs`` (skfem.condense)."""
    out = x.copy()
    aa, bb, _, interior = condense(a, b, x=x, D=dofs)
    out[interior] = spla.spsolve(aa, bb)
    return out


def solve_transient(system: AxisymmetricSystem, time_step: float, initial, powers=None,
                    n_steps: int | None = None, probes=None, keep_steps=()):
    """Integrate M T' + K T = load + Σ_g P_g(t) unit_g with BDF2 (backward-Euler start).

    Parameters
    ----------
    time_step : Δt [s].
    initial : Initial temperature, scalar or nodal vector [K].
    powers : {source name: (n_steps,) step-mean power [W]}; steps are [nΔt, (n+1)Δt).
    n_steps : Number of steps (needed when there are no powers).
    probes : Sparse (n_points, N) interpolation matrix (``basis.probes``) for time series.
    keep_steps : Step indices (0 = initial state) whose full nodal field is returned.

    Returns
    -------
    (probe_values (n_steps + 1, n_points), {step: nodal field}).
    """
    if not time_step > 0:
        raise ValueError(f"time step must be positive, got {time_step}")
    powers = powers or {}
    lengths = {np.asarray(p).shape[0] for p in powers.values()}
    if n_steps is None:
        if len(lengths) != 1:
            raise ValueError("give n_steps or power series of one common length")
        n_steps = lengths.pop()
    elif lengths and lengths != {n_steps}:
        raise ValueError("power series must have n_steps values")
    names = list(powers)
    if names:
        unit = np.stack([system.unit_loads[g] for g in names], axis=1)
        pw = np.stack([np.asarray(powers[g], float) for g in names], axis=1)
        if not np.all(np.isfinite(pw)):
            raise ValueError("heat source powers must be finite")
    m, k = system.capacity, system.stiffness
    t = np.broadcast_to(np.asarray(initial, float), (system.basis.N,)).copy()
    lu_be = spla.splu((m / time_step + k).tocsc())
    lu_bdf2 = spla.splu((1.5 / time_step * m + k).tocsc())
    keep = set(int(s) for s in keep_steps)
    fields = {0: t.copy()} if 0 in keep else {}
    out = [] if probes is None else [probes @ t]
    t_prev = None
    for n in range(n_steps):  # time steps: one triangular solve each
        rhs = system.load + (unit @ pw[n] if names else 0.0)
        if t_prev is None:
            t_new = lu_be.solve(m @ t / time_step + rhs)
        else:
            t_new = lu_bdf2.solve(m @ (2.0 * t - 0.5 * t_prev) / time_step + rhs)
        t_prev, t = t, t_new
        if probes is not None:
            out.append(probes @ t)
        if n + 1 in keep:
            fields[n + 1] = t.copy()
    return (np.array(out) if probes is not None else None), fields


# --- the PTO model of Fig. 10 ------------------------------------------------------------------

@dataclass(frozen=True)
class Region:
    """A rectangular region of the r-z section [m], its material and convection."""

    name: str
    r0: float
    r1: float
    z0: float
    z1: float
    conductivity: float  # [W m-1 K-1]
    heat_capacity: float  # ρ c_p [J m-3 K-1]
    convection: float = 0.0  # h on its faces exposed to air [W m-2 K-1]
    source: str | None = None  # lumped heat source feeding it ('generator', 'screw', 'nut')


STEEL = (45.0, 3.6e6)
LAMINATION = (28.0, 3.7e6)  # laminated iron + magnets/copper, radial conductivity
# Air in the rotor-stator gap: a rotor at ≈ 1300 rpm drives Taylor-Couette flow whose Nusselt
# number (Becker & Kaye 1962 correlation) is ≈ 10, so the gap conducts like k_eff ≈ 10 k_air
AIR_GAP = (0.3, 1.2e3)
BALL_TRACK = (2.0, 2.5e6)  # balls in Hertz point contacts + grease, effective radial k
# Spoked aluminium hub between shaft and rotor ring: a quarter of the annulus is metal
# (k = 0.25 x 160, ρc = 0.25 x 2.4e6), the rest air
ROTOR_HUB = (40.0, 0.6e6)


def _default_regions() -> tuple[Region, ...]:
    # h on the screw shaft: a cylinder of Ø 80 mm spinning at up to 140 rad/s in still air,
    # Nu = 0.133 Re^(2/3) Pr^(1/3) (Anderson & Saunders' rotating-cylinder correlation) gives
    # h ≈ 55 W/m²/K at the peak speed and ≈ 40 W/m²/K over the wave cycle; the rotor's end
    # faces are rotating disks (laminar, Nu = 0.33 Re^(1/2)): h ≈ 26 W/m²/K.
    shaft, disk = 40.0, 26.0
    return (
        Region("bearing_seat", 0.0, 0.040, 0.00, 0.05, *STEEL, shaft, "bearing"),
        Region("screw_generator", 0.0, 0.040, 0.05, 0.30, *STEEL, 0.0),
        Region("screw_free", 0.0, 0.040, 0.30, 0.41, *STEEL, shaft),
        Region("screw_swept", 0.0, 0.040, 0.41, 0.55, *STEEL, shaft, "screw"),
        Region("screw_under_nut", 0.0, 0.034, 0.55, 0.75, *STEEL, shaft, "screw"),
        Region("screw_swept_end", 0.0, 0.040, 0.75, 0.89, *STEEL, shaft, "screw"),
        Region("rotor_hub", 0.040, 0.065, 0.05, 0.30, *ROTOR_HUB, disk),
        Region("rotor", 0.065, 0.080, 0.05, 0.30, *LAMINATION, disk),
        Region("air_gap", 0.080, 0.083, 0.05, 0.30, *AIR_GAP, disk),
        Region("stator", 0.083, 0.115, 0.05, 0.30, *LAMINATION, 64.0, "generator"),
        Region("ball_track", 0.034, 0.046, 0.55, 0.75, *BALL_TRACK, 40.0),
        Region("nut", 0.046, 0.062, 0.55, 0.75, *STEEL, 40.0, "nut"),
    )


@dataclass(frozen=True)
class PTOGeometry:
    """Axisymmetric PTO section (Fig. 10), materials, convection and control points.

    Plausible dimensions for the 80 mm ball screw of :mod:`flumekit.ballscrew.screw` and an EMRG
    of the lumped model's size (the stator's ρc V = 18 kJ/K is the lumped generator's heat
    capacity); convection coefficients as in
    :class:`flumekit.ballscrew.thermal.lumped.LumpedThermal`: 64 W/m²/K on the stator's
    envelope is the finned casing's h ≈ 25 W/m²/K times its fin area ratio ≈ 2.5, so the
    envelope (0.27 m²) conducts a1 = 17 W/K to the air; 20 on the shaft, 35 on the moving nut. The
    bearing seat at the screw end receives the screw's share of the bearing losses. Between
    screw core (r < 34 mm) and nut (r > 46 mm) lies the ball track, a layer of balls in Hertz
    point contacts and grease with an effective conductivity of 2 W/m/K.
    """

    regions: tuple[Region, ...] = field(default_factory=_default_regions)
    air_temperature: float = 293.15
    control_points: tuple[tuple[str, float, float], ...] = (
        ("stator", 0.099, 0.175), ("stator_bore", 0.0835, 0.175), ("stator_end", 0.099, 0.30),
        ("rotor", 0.0725, 0.175), ("screw_in_generator", 0.0, 0.175),
        ("screw_under_nut", 0.0, 0.65), ("nut", 0.054, 0.65))

    def __post_init__(self):
        """Check that every region has a positive extent."""
        for reg in self.regions:
            if not (0 <= reg.r0 < reg.r1 and reg.z0 < reg.z1):
                raise GeometryError(f"region '{reg.name}' has an empty or inverted extent")
            if reg.conductivity <= 0 or reg.heat_capacity <= 0 or reg.convection < 0:
                raise GeometryError(f"region '{reg.name}': k and ρc must be > 0, h >= 0")


def _region_of(geometry: PTOGeometry, r: float, z: float) -> str:
    """Name of the region holding the point (r, z) (the first one, on a shared boundary)."""
    for g in geometry.regions:
        if g.r0 <= r <= g.r1 and g.z0 <= z <= g.z1:
            return g.name
    raise GeometryError(f"control point (r = {r} m, z = {z} m) lies outside the PTO section")


def pto_mesh(geometry: PTOGeometry, radial_cell_size: float = 0.005,
             axial_cell_size: float = 0.02) -> tuple[MeshQuad, np.ndarray]:
    """Tensor mesh of the PTO regions; returns the mesh and the region index of each cell."""
    regs = geometry.regions
    r = refine_points([x for g in regs for x in (g.r0, g.r1)], radial_cell_size)
    z = refine_points([x for g in regs for x in (g.z0, g.z1)], axial_cell_size)
    mesh = tensor_mesh(r, z)
    mid = mesh.p[:, mesh.t].mean(axis=1)
    region = np.full(mesh.nelements, -1)
    for i, g in enumerate(regs):  # loop over the handful of regions
        inside = (mid[0] > g.r0) & (mid[0] < g.r1) & (mid[1] > g.z0) & (mid[1] < g.z1)
        if np.any(region[inside] >= 0):
            raise GeometryError(f"region '{g.name}' overlaps another region")
        region[inside] = i
    mesh = mesh.restrict(np.flatnonzero(region >= 0))
    return mesh, region[region >= 0]


def assemble_pto(geometry: PTOGeometry, radial_cell_size: float = 0.005,
                 axial_cell_size: float = 0.02, order: int = 1):
    """Mesh and assemble the PTO model. Returns (system, cell_region)."""
    mesh, region = pto_mesh(geometry, radial_cell_size, axial_cell_size)
    regs = geometry.regions
    k = np.array([regs[i].conductivity for i in region])
    rc = np.array([regs[i].heat_capacity for i in region])
    f = mesh.boundary_facets()
    owner = region[mesh.f2t[0, f]]
    mid = mesh.p[:, mesh.facets[:, f]].mean(axis=1)
    on_axis = mid[0] < 1e-12
    robin = []
    for i, g in enumerate(regs):
        sel = f[(owner == i) & ~on_axis]
        if g.convection > 0 and sel.size:
            robin.append((sel, g.convection, geometry.air_temperature))
    names = sorted({g.source for g in regs if g.source})
    sources = {s: np.flatnonzero(np.isin(region, [i for i, g in enumerate(regs) if g.source == s]))
               for s in names}
    return assemble(mesh, k, rc, robin, (), sources, order), region


def source_powers(th: xr.Dataset, factor: int) -> dict[str, np.ndarray]:
    """Split the powers [W] of the lumped dataset over the FEM source regions.

    Averaged over FEM steps of ``factor`` lumped steps.

    Eq. (9) gives the screw p_sn r Q_mecc (ball system: the swept screw length) plus
    p_sb (1 - r) Q_mecc (support bearing: the bearing seat); Eq. (10) the nut (1 - p_sn) r Q_mecc;
    Eq. (8) the generator Q_el (stator).
    """
    p = float(th.attrs["partition_screw_nut"])
    pb = float(th.attrs["partition_screw_bearing"])
    r = float(th.attrs["ball_system_fraction"])
    qm = th["mechanical_power_loss"].values[:-1]
    if qm.size % factor:
        raise ValueError(f"the FEM step ({factor} lumped steps) must divide the simulated "
                         f"time ({qm.size} lumped steps)")
    powers = {"generator": th["electrical_power_loss"].values[:-1],
              "screw": p * r * qm, "bearing": pb * (1 - r) * qm, "nut": (1 - p) * r * qm}
    return {g: x.reshape(x.size // factor, factor).mean(axis=1) for g, x in powers.items()}


def thermal_fem(lumped: xr.Dataset, geometry: PTOGeometry = PTOGeometry(),
                time_step: float = 10.0, radial_cell_size: float = 0.005,
                axial_cell_size: float = 0.02, order: int = 1,
                snapshot_times=(641.0, 1840.0, 3225.0, 6000.0)) -> xr.Dataset:
    """Scenario step 4: transient r-z temperature field of the PTO (Figs. 17-18).

    Parameters
    ----------
    lumped : Output of :func:`thermal_lumped.thermal_lumped` (its heat sources and time grid
        are reused: same sources as the lumped model, averaged over the FEM step).
    geometry : PTO section, materials and convection.
    time_step : FEM step [s], a multiple of the lumped dataset's step.
    radial_cell_size, axial_cell_size : Mesh size [m].
    order : Element order (1 or 2).
    snapshot_times : Times [s] of the stored temperature fields (Fig. 17: 641, 1840, 3225,
        6000 s), linearly interpolated between the bracketing FEM steps.

    Returns
    -------
    Dataset with ``control_temperature`` (time, control_point), ``temperature_field``
    (snapshot_time, node) at the mesh vertices, node coordinates, ``cell_nodes`` and
    ``cell_region`` for plotting.
    """
    lt = lumped["time"].values
    dt_l = float(lt[1] - lt[0])
    factor = int(round(time_step / dt_l))
    if factor < 1 or abs(factor * dt_l - time_step) > 1e-9 * time_step:
        raise ValueError(f"FEM step {time_step} s must be a multiple of the lumped step {dt_l} s")
    system, region = assemble_pto(geometry, radial_cell_size, axial_cell_size, order)
    powers = {g: p for g, p in source_powers(lumped, factor).items() if g in system.unit_loads}
    n = next(iter(powers.values())).size
    times = np.arange(n + 1) * time_step
    snap_t = np.asarray(snapshot_times, float)
    if np.any(snap_t < 0) or np.any(snap_t > times[-1]):
        raise ValueError(f"snapshot times must lie within 0..{times[-1]} s")
    lo = np.minimum(np.floor(snap_t / time_step + 1e-9).astype(int), n - 1)
    weight = snap_t / time_step - lo  # linear interpolation between the two bracketing steps
    pts = np.array([[p[1], p[2]] for p in geometry.control_points]).T
    probes = system.basis.probes(pts)
    t0 = float(lumped.attrs.get("initial_temperature", geometry.air_temperature))
    series, fields = solve_transient(system, time_step, t0, powers, probes=probes,
                                     keep_steps=np.concatenate([lo, lo + 1]))
    snapshots = np.array([(1 - w) * fields[i] + w * fields[i + 1] for i, w in zip(lo, weight)])
    mesh = system.basis.mesh
    vert = system.basis.nodal_dofs[0]
    ds = xr.Dataset(
        {"control_temperature": (("time", "control_point"), series),
         "temperature_field": (("snapshot_time", "node"), snapshots[:, vert]),
         "radial_coordinate": ("node", mesh.p[0]), "axial_coordinate": ("node", mesh.p[1]),
         "cell_nodes": (("cell", "corner"), mesh.t.T.astype(np.int32)),
         "cell_region": ("cell", region.astype(np.int32)),
         "control_radius": ("control_point", pts[0]), "control_axial": ("control_point", pts[1]),
         "control_region": ("control_point", [_region_of(geometry, r, z) for r, z in pts.T])},
        coords={"time": times, "snapshot_time": snap_t,
                "control_point": [p[0] for p in geometry.control_points],
                "region": [g.name for g in geometry.regions]},
        attrs=conventions.global_attrs(
            "PTO axisymmetric FEM thermal model", "flumekit.ballscrew.thermal.fem.thermal_fem",
            {"time_step": time_step, "radial_cell_size": radial_cell_size,
             "axial_cell_size": axial_cell_size, "order": order,
             "regions": [asdict(g) for g in geometry.regions]}))
    ds.attrs.update(time_step=time_step, radial_cell_size=radial_cell_size,
                    axial_cell_size=axial_cell_size, order=order, n_dofs=system.basis.N)
    return conventions.annotate(ds)
