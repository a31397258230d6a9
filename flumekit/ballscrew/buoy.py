"""The onshore buoy WEC of Senatore & De Simone (2022): a float on holding arms, one DOF.

The float is carried by an arm hinged on the onshore frame; the ball-screw PTO (an actuator of
variable length s) joins a frame anchor to an anchor on the arm. The buoy's vertical motion z(t)
(of its centre of gravity, from the static equilibrium) fixes the arm angle θ, the actuator
length s(θ) and hence nut travel, nut velocity and screw speed ω = 2π v / lead.

Two ways in, as in the paper's multibody model (Sect. 2):

- kinematic input z(t) → :func:`kinematics` → (PTO force from :mod:`ballscrew`) →
  :func:`inverse_dynamics`: the wave force the sea must supply;
- force input F_z(t) → :func:`forward_dynamics` (ODE integration of the arm).

The energy balance algorithm (Fig. 4) gives the lift h for a sea state {H, T}:
:func:`lift_from_energy_balance`.

The paper gives no dimensions of the UMBRA device; :class:`BuoyGeometry` documents ours.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import asdict, dataclass

import numpy as np
import xarray as xr
from scipy import integrate, optimize

from flumekit import conventions
from flumekit.docstrings import filler
from flumekit.errors import GeometryError

#: docstring text that several functions of this module share
_doc = filler(
    parameters_float=("Parameters\n"
                      "----------\n"
                      "%(draft)s\n"
                      "%(radius)s"),
    draft=("draft : float or array_like\n"
           "    Draft d of the float [m]."),
    geometry=("geometry : BuoyGeometry\n"
              "    The geometry."),
    motion_period=("period : float\n"
                   "    Period T [s]."),
    radius=("radius : float\n"
            "    Float radius R [m]."))

WATER_DENSITY = 1025.0  # [kg m-3] sea water
GRAVITY = 9.81  # [m s-2]


@_doc
@dataclass(frozen=True)
class BuoyGeometry:
    """Geometry and mass of the buoy, arm and PTO linkage (hinge at the origin).

    The defaults are a plausible near-shore device of the size the paper's Fig. 1 suggests
    (the paper gives no numbers); each parameter says its choice and the reason. The float
    CoG is at the sphere centre and its mass is the displaced water at the static draft (no
    PTO force at rest: the ball screw back-drives).

    Parameters
    ----------
    float_radius : float
        Radius of the hemispherical float [m]; 2.5 m: a Wavestar-like bowl, deck at the sphere
        centre, whose waterplane area (about 15-20 m²) catches a few kW in T = 3.8 s waves.
    static_draft : float
        Draft at static equilibrium [m]; 1.25 m = R/2 leaves ±1.25 m of heave before the float
        leaves the water or the deck submerges, enough for the reference motion A = 1 m.
    arm_length : float
        Distance from the hinge to the float CoG [m]; 6.0 m keeps the arm angle within ±10° for
        A = 1 m, so the float stays nearly level.
    rest_angle : float
        Arm angle at static equilibrium [rad]; 0: the arm horizontal.
    pto_arm_anchor : float
        Distance of the PTO's arm anchor from the hinge along the arm [m].
    pto_frame_anchor : tuple of float
        (x, z) of the PTO's frame anchor [m]; (0, -2.0), 2 m below the hinge: with the arm
        anchor this gives a linkage ratio ds/dz ≈ 0.24, a nut stroke of about ±0.24 m for
        A = 1 m and, with a 20 mm lead, screw speeds above 1000 rpm ("high-speed rotary
        motion").
    arm_inertia : float
        Moment of inertia of the two steel arms about the hinge [kg m2]; 2.0e4 (about 1.7 t at
        6 m, m L²/3).
    water_density : float
        Density of the water [kg m-3].
    gravity : float
        Acceleration of gravity [m s-2].

    Raises
    ------
    flumekit.errors.GeometryError
        For a non-positive length, density or gravity, a static draft not below the float
        radius, a rest angle of ±90° or a negative arm inertia.

    %(references_senatore2022)s

    Examples
    --------
    >>> from flumekit.ballscrew.buoy import BuoyGeometry
    >>> g = BuoyGeometry()
    >>> round(g.mass, 1), round(g.inertia)
    (10482.2, 397359)
    """

    float_radius: float = 2.5
    static_draft: float = 1.25
    arm_length: float = 6.0
    rest_angle: float = 0.0
    pto_arm_anchor: float = 2.0
    pto_frame_anchor: tuple[float, float] = (0.0, -2.0)
    arm_inertia: float = 2.0e4
    water_density: float = WATER_DENSITY
    gravity: float = GRAVITY

    def __post_init__(self):
        """Check the geometry (see the class's Raises)."""
        for name in ("float_radius", "static_draft", "arm_length", "pto_arm_anchor",
                     "water_density", "gravity"):
            if not getattr(self, name) > 0:
                raise GeometryError(f"buoy geometry: {name} must be positive, got "
                                    f"{getattr(self, name)}")
        if self.static_draft >= self.float_radius:
            raise GeometryError("buoy geometry: static draft must be below the float radius "
                                "(deck above water at rest)")
        if abs(np.sin(self.rest_angle)) >= 1 or self.arm_inertia < 0:
            raise GeometryError("buoy geometry: bad rest angle or negative arm inertia")

    @property
    def mass(self) -> float:
        """Float mass [kg], equal to the displaced water at the static draft."""
        return float(self.water_density * displaced_volume(self.static_draft, self.float_radius))

    @property
    def inertia(self) -> float:
        """Moment of inertia of float (point mass) and arms about the hinge [kg m2]."""
        return self.mass * self.arm_length**2 + self.arm_inertia


# --- hydrostatics (Fig. 3) ---------------------------------------------------------------------

@_doc
def displaced_volume(draft, radius: float) -> np.ndarray:
    """Return the volume of water displaced by a hemispherical float (Fig. 3).

    A spherical cap V = π d² (3R - d)/3 for 0 ≤ d ≤ R; 0 out of the water (d < 0) and the full
    hemisphere 2πR³/3 once the deck is awash (d > R, green water on deck not counted).

    %(parameters_float)s

    Returns
    -------
    numpy.ndarray
        Displaced volume [m3].

    %(references_senatore2022)s, Fig. 3.

    Examples
    --------
    >>> from flumekit.ballscrew.buoy import displaced_volume
    >>> displaced_volume([-0.1, 0.5, 1.0, 2.0], 1.0).round(4).tolist()
    [0.0, 0.6545, 2.0944, 2.0944]
    """
    d = np.clip(np.asarray(draft, float), 0.0, radius)
    return np.pi * d**2 * (3 * radius - d) / 3.0


@_doc
def waterplane_area(draft, radius: float) -> np.ndarray:
    """Return the waterplane area of the hemispherical float, π(2Rd - d²).

    %(parameters_float)s

    Returns
    -------
    numpy.ndarray
        Waterplane area [m2], 0 outside 0 < d < R.

    Examples
    --------
    >>> from flumekit.ballscrew.buoy import waterplane_area
    >>> waterplane_area([0.5, 1.0], 1.0).round(4).tolist()
    [2.3562, 0.0]
    """
    d = np.asarray(draft, float)
    inside = (d > 0) & (d < radius)
    dc = np.clip(d, 0.0, radius)
    return np.where(inside, np.pi * (2 * radius * dc - dc**2), 0.0)


# --- linkage ---------------------------------------------------------------------------------

def arm_angle(heave, geometry: BuoyGeometry) -> np.ndarray:
    """Return the arm angle θ from the heave z of the float CoG (z = 0 at static equilibrium).

    sin θ = sin θ_rest + z / L.

    Parameters
    ----------
    heave : float or array_like
        Heave z [m].
    geometry : BuoyGeometry
        The geometry (arm length L, rest angle).

    Returns
    -------
    numpy.ndarray
        Arm angle [rad].

    Raises
    ------
    flumekit.errors.GeometryError
        Where |sin θ_rest + z / L| ≥ 1: the heave is out of the arm's reach.

    Examples
    --------
    >>> from flumekit.ballscrew.buoy import BuoyGeometry, arm_angle
    >>> round(float(arm_angle(1.0, BuoyGeometry())), 4)
    0.1674
    """
    g = geometry
    s = np.sin(g.rest_angle) + np.asarray(heave, float) / g.arm_length
    if np.any(np.abs(s) >= 1):
        raise GeometryError(f"heave out of reach of the arm: |z_rest + z| must stay below the "
                            f"arm length {g.arm_length} m "
                            f"(max {np.max(np.abs(s)) * g.arm_length:.3g} m)")
    return np.arcsin(s)


def actuator_length(theta, geometry: BuoyGeometry) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Return the actuator (PTO) length s(θ) and its derivatives s'(θ), s''(θ).

    s² = (d cos θ - p_x)² + (d sin θ - p_z)² with d the arm anchor distance and (p_x, p_z) the
    frame anchor; s s' = d (p_x sin θ - p_z cos θ); s'² + s s'' = d (p_x cos θ + p_z sin θ).

    Parameters
    ----------
    theta : float or array_like
        Arm angle θ [rad].
    geometry : BuoyGeometry
        The linkage geometry.

    Returns
    -------
    s : numpy.ndarray
        Actuator length [m].
    ds : numpy.ndarray
        s'(θ) [m rad-1].
    dds : numpy.ndarray
        s''(θ) [m rad-2].

    Raises
    ------
    flumekit.errors.GeometryError
        When the anchors coincide (zero length).

    Examples
    --------
    >>> from flumekit.ballscrew.buoy import BuoyGeometry, actuator_length
    >>> [round(float(v), 4) for v in actuator_length(0.0, BuoyGeometry())]
    [2.8284, 1.4142, -0.7071]
    """
    d = geometry.pto_arm_anchor
    px, pz = geometry.pto_frame_anchor
    th = np.asarray(theta, float)
    s = np.hypot(d * np.cos(th) - px, d * np.sin(th) - pz)
    if np.any(s <= 1e-9):
        raise GeometryError("PTO anchors coincide: actuator length is zero")
    ds = d * (px * np.sin(th) - pz * np.cos(th)) / s
    dds = (d * (px * np.cos(th) + pz * np.sin(th)) - ds**2) / s
    return s, ds, dds


@_doc
def screw_speed(nut_velocity, lead: float) -> np.ndarray:
    """Return the screw angular speed ω = 2π v / lead.

    Parameters
    ----------
    %(nut_velocity)s
    %(lead)s

    Returns
    -------
    numpy.ndarray
        Screw speed [rad s-1].

    Raises
    ------
    flumekit.errors.GeometryError
        For a non-positive lead.

    Examples
    --------
    >>> from flumekit.ballscrew.buoy import screw_speed
    >>> round(float(screw_speed(0.1, 0.02)), 4)
    31.4159
    """
    if not lead > 0:
        raise GeometryError(f"screw lead must be positive, got {lead}")
    return 2.0 * np.pi * np.asarray(nut_velocity, float) / lead


# --- scenario: kinematics --------------------------------------------------------------------

@_doc
def reference_motion(amplitude: float = 1.0, period: float = 3.8, n_periods: int = 1,
                     samples_per_period: int = 380) -> xr.Dataset:
    """Return the sinusoidal heave z(t) = A sin(2π t/T) of the buoy CoG and its exact derivatives.

    The reference scenario of Senatore & De Simone 2022, Sect. 3.1 (A = 1 m, T = 3.8 s).

    Parameters
    ----------
    amplitude : float
        Heave amplitude A [m].
    %(motion_period)s
    n_periods : int
        Number of periods.
    samples_per_period : int
        Samples per period (at least 8).

    Returns
    -------
    xarray.Dataset
        ``buoy_heave`` [m], ``buoy_heave_velocity`` [m s-1] and ``buoy_heave_acceleration``
        [m s-2] over ``time`` [s]; attribute ``wave_period`` [s].

    Raises
    ------
    ValueError
        For a negative amplitude, a non-positive period, fewer than one period or fewer than 8
        samples per period.

    %(references_senatore2022)s, Sect. 3.1.

    Examples
    --------
    >>> from flumekit.ballscrew.buoy import reference_motion
    >>> m = reference_motion()
    >>> m.sizes["time"], float(m.buoy_heave.max())
    (380, 1.0)
    """
    if not (amplitude >= 0 and period > 0 and n_periods >= 1 and samples_per_period >= 8):
        raise ValueError("reference motion needs amplitude >= 0, period > 0, n_periods >= 1, "
                         "samples_per_period >= 8")
    w = 2 * np.pi / period
    t = np.arange(n_periods * samples_per_period) * (period / samples_per_period)
    ds = xr.Dataset(
        {"buoy_heave": ("time", amplitude * np.sin(w * t)),
         "buoy_heave_velocity": ("time", amplitude * w * np.cos(w * t)),
         "buoy_heave_acceleration": ("time", -amplitude * w**2 * np.sin(w * t))},
        coords={"time": t},
        attrs=conventions.global_attrs("reference buoy motion", "flumekit.ballscrew.buoy",
                                       {"amplitude": amplitude, "period": period,
                                        "n_periods": n_periods}))
    ds.attrs["wave_period"] = period
    return conventions.annotate(ds)


def _derivative(x: np.ndarray, t: np.ndarray) -> np.ndarray:
    return np.gradient(x, t, edge_order=2)


@_doc
def kinematics(motion: xr.Dataset, geometry: BuoyGeometry = BuoyGeometry(),
               lead: float = 0.02, water_elevation: xr.DataArray | None = None) -> xr.Dataset:
    """Compute the linkage kinematics and hydrostatics of the buoy for a kinematic input z(t).

    Parameters
    ----------
    motion : xarray.Dataset
        ``buoy_heave`` z(t) [m] over ``time`` [s]; ``buoy_heave_velocity`` [m s-1] and
        ``buoy_heave_acceleration`` [m s-2] are used when present (else second-order
        differences).
    geometry : BuoyGeometry
        Buoy, arm and linkage geometry.
    lead : float
        Lead of the ball screw [m] (screw speed ω = 2π v / lead).
    water_elevation : xarray.DataArray, optional
        Free-surface elevation at the float [m] over ``time``; default still water (the
        displaced volume of Fig. 3 as a function of the arm angle).

    Returns
    -------
    xarray.Dataset
        Over ``time``: buoy_heave(_velocity, _acceleration), arm_angle, arm_angular_velocity,
        arm_angular_acceleration, nut_travel [m], nut_velocity [m s-1], nut_acceleration
        [m s-2], screw_speed [rad s-1], linkage_ratio (ds/dz) [-], buoy_draft [m],
        displaced_volume [m3], waterplane_area [m2], buoyancy_force [N]; attributes carry the
        geometry (:func:`geometry_from_attrs`) and the lead.

    Raises
    ------
    ValueError
        Without ``buoy_heave``, with fewer than 3 samples or a time axis that does not
        increase, or with non-finite heave.
    flumekit.errors.GeometryError
        When the heave is out of reach of the arm.

    %(references_senatore2022)s, Sect. 2 (multibody model) and Fig. 3.

    Examples
    --------
    >>> from flumekit.ballscrew.buoy import kinematics, reference_motion
    >>> k = kinematics(reference_motion(), lead=0.02)
    >>> round(float(k.linkage_ratio[0]), 4), round(float(k.nut_travel.max()), 4)
    (0.2357, 0.2266)
    """
    if "buoy_heave" not in motion:
        raise ValueError("motion dataset needs a 'buoy_heave' variable (z of the buoy CoG)")
    t = np.asarray(motion["time"].values, float)
    if t.size < 3 or np.any(np.diff(t) <= 0):
        raise ValueError("motion time must be strictly increasing with at least 3 samples")
    z = np.asarray(motion["buoy_heave"].values, float)
    if not np.all(np.isfinite(z)):
        raise ValueError("buoy_heave contains non-finite values")
    zd = (motion["buoy_heave_velocity"].values if "buoy_heave_velocity" in motion
          else _derivative(z, t))
    zdd = (motion["buoy_heave_acceleration"].values if "buoy_heave_acceleration" in motion
           else _derivative(np.asarray(zd, float), t))
    g = geometry
    th = arm_angle(z, g)
    c = np.cos(th)
    thd = zd / (g.arm_length * c)
    thdd = (zdd + g.arm_length * np.sin(th) * thd**2) / (g.arm_length * c)
    s, ds, dds = actuator_length(th, g)
    s0, _, _ = actuator_length(g.rest_angle, g)
    v = ds * thd
    a = dds * thd**2 + ds * thdd
    eta_w = 0.0 if water_elevation is None else np.asarray(water_elevation.values, float)
    draft = g.static_draft + eta_w - z
    vol = displaced_volume(draft, g.float_radius)
    ds_out = xr.Dataset(
        {"buoy_heave": ("time", z), "buoy_heave_velocity": ("time", np.asarray(zd, float)),
         "buoy_heave_acceleration": ("time", np.asarray(zdd, float)),
         "arm_angle": ("time", th), "arm_angular_velocity": ("time", thd),
         "arm_angular_acceleration": ("time", thdd),
         "nut_travel": ("time", s - s0), "nut_velocity": ("time", v),
         "nut_acceleration": ("time", a), "screw_speed": ("time", screw_speed(v, lead)),
         "linkage_ratio": ("time", ds / (g.arm_length * c)),
         "buoy_draft": ("time", draft), "displaced_volume": ("time", vol),
         "waterplane_area": ("time", waterplane_area(draft, g.float_radius)),
         "buoyancy_force": ("time", g.water_density * g.gravity * vol)},
        coords={"time": t},
        attrs=conventions.global_attrs("buoy WEC kinematics", "flumekit.ballscrew.buoy.kinematics",
                                       {**asdict(g), "lead": lead}))
    ds_out.attrs.update(lead=lead, **{f"geometry_{k}": np.asarray(v_, float)
                                      for k, v_ in asdict(g).items()})
    if "wave_period" in motion.attrs:
        ds_out.attrs["wave_period"] = motion.attrs["wave_period"]
    return conventions.annotate(ds_out)


def geometry_from_attrs(ds: xr.Dataset) -> BuoyGeometry:
    """Return the :class:`BuoyGeometry` stored in the attributes of a :func:`kinematics` dataset.

    Parameters
    ----------
    ds : xarray.Dataset
        A dataset written by :func:`kinematics` (attributes ``geometry_<field>``).

    Returns
    -------
    BuoyGeometry
        The geometry.

    Examples
    --------
    >>> from flumekit.ballscrew.buoy import (BuoyGeometry, geometry_from_attrs, kinematics,
    ...                                      reference_motion)
    >>> geometry_from_attrs(kinematics(reference_motion())) == BuoyGeometry()
    True
    """
    kw = {}
    for name in BuoyGeometry.__dataclass_fields__:
        val = np.asarray(ds.attrs[f"geometry_{name}"])
        kw[name] = tuple(float(x) for x in val) if val.ndim else float(val)
    return BuoyGeometry(**kw)


# --- dynamics --------------------------------------------------------------------------------

@_doc
def inverse_dynamics(kin: xr.Dataset, pto_force, geometry: BuoyGeometry) -> xr.Dataset:
    """Compute the wave (hydrodynamic) force that realises the kinematic input.

    Moment balance about the hinge (rigid arm, float CoG at distance L)::

        I θ'' = L cos θ (F_hs + F_hd - m g) + F_PTO s'(θ),

    with F_PTO the axial PTO force on the nut (Eq. (3), positive extending the actuator) and
    s'(θ) its lever (virtual work). Solved for F_hd.

    Parameters
    ----------
    kin : xarray.Dataset
        Output of :func:`kinematics`.
    pto_force : array_like
        PTO force F_PTO [N] over time (same length as ``kin.time``).
    geometry : BuoyGeometry
        The geometry used for ``kin``.

    Returns
    -------
    xarray.Dataset
        ``wave_force`` F_hd [N] and ``net_vertical_force`` F_z = F_hs + F_hd - m g [N] over
        ``time``.

    %(references_senatore2022)s, Sect. 2 and Eq. (3).

    Examples
    --------
    >>> import numpy as np
    >>> from flumekit.ballscrew.buoy import (BuoyGeometry, inverse_dynamics, kinematics,
    ...                                      reference_motion)
    >>> g = BuoyGeometry()
    >>> k = kinematics(reference_motion(amplitude=0.0), g)
    >>> float(abs(inverse_dynamics(k, np.zeros(k.sizes["time"]), g).wave_force).max()) < 1e-6
    True
    """
    g = geometry
    th = kin["arm_angle"].values
    _, ds, _ = actuator_length(th, g)
    f = np.asarray(pto_force, float)
    lever = g.arm_length * np.cos(th)
    fz = (g.inertia * kin["arm_angular_acceleration"].values - f * ds) / lever
    fhd = fz - kin["buoyancy_force"].values + g.mass * g.gravity
    return xr.Dataset({"wave_force": ("time", fhd), "net_vertical_force": ("time", fz)},
                      coords={"time": kin["time"].values})


@_doc
def forward_dynamics(time, net_vertical_force, geometry: BuoyGeometry, damping: float,
                     inertia: float = 0.0, friction_force: float = 0.0,
                     friction_velocity: float = 1e-3, initial_heave: float = 0.0,
                     initial_velocity: float = 0.0, rtol: float = 1e-8) -> xr.Dataset:
    """Compute the buoy motion for a force input F_z(t) (forward dynamics of the arm).

    (I + K_inert s'²) θ'' = L cos θ F_z - s' (K v + F_fr tanh(v/v_ε) + K_inert s'' θ'²),
    v = s' θ', with F_z the net non-PTO vertical force on the float (buoyancy + waves - weight)
    linearly interpolated in time, K the total viscous PTO coefficient (K_damp + K_visc of
    Eq. (3)) and F_fr a Coulomb friction regularised by tanh (v_ε small). Integrated with the
    implicit Radau method (the regularised friction is stiff).

    Parameters
    ----------
    time : array_like
        Times [s], increasing.
    net_vertical_force : array_like
        F_z at those times [N].
    %(geometry)s
    damping : float
        Viscous PTO coefficient K on the nut [N s m-1].
    inertia : float
        Equivalent inertia of the PTO on the nut K_inert [kg].
    friction_force : float
        Coulomb friction force on the nut F_fr [N].
    friction_velocity : float
        Regularisation velocity v_ε [m s-1].
    initial_heave : float
        Heave at ``time[0]`` [m].
    initial_velocity : float
        Heave velocity at ``time[0]`` [m s-1].
    rtol : float
        Relative tolerance of the integrator [-].

    Returns
    -------
    xarray.Dataset
        ``buoy_heave`` [m], ``buoy_heave_velocity`` [m s-1] and ``nut_velocity`` [m s-1] over
        ``time``.

    Raises
    ------
    ValueError
        When ``time`` does not increase or does not match the force samples.
    RuntimeError
        When the integration fails.

    %(references_senatore2022)s, Sect. 2 and Eq. (3).

    Examples
    --------
    The inverse of :func:`inverse_dynamics`: the force that makes the buoy heave 0.5 m against
    a viscous PTO of 4e4 N s/m (F_PTO = −K v), fed back here with that damping, gives back
    the heave it was computed from:

    >>> from flumekit.ballscrew.buoy import (BuoyGeometry, forward_dynamics, inverse_dynamics,
    ...                                      kinematics, reference_motion)
    >>> geometry = BuoyGeometry()
    >>> kin = kinematics(reference_motion(amplitude=0.5, samples_per_period=200), geometry)
    >>> force = inverse_dynamics(kin, -4.0e4 * kin.nut_velocity.values, geometry)
    >>> motion = forward_dynamics(kin.time.values, force.net_vertical_force.values, geometry,
    ...                           damping=4.0e4, rtol=1e-6,
    ...                           initial_velocity=float(kin.buoy_heave_velocity[0]))
    >>> round(float(motion.buoy_heave.max()), 3)
    0.5
    >>> float(abs(motion.buoy_heave - kin.buoy_heave).max()) < 1e-3  # [m]
    True
    """
    t = np.asarray(time, float)
    fz = np.asarray(net_vertical_force, float)
    if t.shape != fz.shape or t.size < 2 or np.any(np.diff(t) <= 0):
        raise ValueError("time must be increasing and match the force samples")
    g = geometry
    L = g.arm_length

    def rhs(tt, y):
        th, thd = y
        _, ds, dds = actuator_length(th, g)
        v = ds * thd
        f = np.interp(tt, t, fz)
        fpto = -(damping * v + friction_force * np.tanh(v / friction_velocity)
                 + inertia * dds * thd**2)
        thdd = (L * np.cos(th) * f + fpto * ds) / (g.inertia + inertia * ds**2)
        return [thd, thdd]

    th0 = float(arm_angle(initial_heave, g))
    thd0 = initial_velocity / (L * np.cos(th0))
    sol = integrate.solve_ivp(rhs, (t[0], t[-1]), [th0, thd0], method="Radau", t_eval=t,
                              rtol=rtol, atol=1e-10)
    if not sol.success:
        raise RuntimeError(f"forward dynamics failed: {sol.message}")
    th, thd = sol.y
    z = L * (np.sin(th) - np.sin(g.rest_angle))
    _, ds, _ = actuator_length(th, g)
    return xr.Dataset({"buoy_heave": ("time", z),
                       "buoy_heave_velocity": ("time", L * np.cos(th) * thd),
                       "nut_velocity": ("time", ds * thd)}, coords={"time": t})


# --- energy balance algorithm (Fig. 4) ---------------------------------------------------------

@_doc
def wave_energy_density(wave_height, water_density: float = WATER_DENSITY,
                        gravity: float = GRAVITY) -> np.ndarray:
    """Return the energy per unit horizontal area of a linear wave, E = ρ g H² / 16.

    Eq. (2) in Senatore & De Simone 2022 (Airy theory, independent of depth).

    Parameters
    ----------
    wave_height : float or array_like
        Wave height H [m].
    water_density : float
        Water density ρ [kg m-3].
    gravity : float
        Acceleration of gravity g [m s-2].

    Returns
    -------
    numpy.ndarray
        Energy density [J m-2].

    Raises
    ------
    ValueError
        For a negative height.

    %(references_senatore2022)s, Eq. (2).

    Examples
    --------
    >>> from flumekit.ballscrew.buoy import wave_energy_density
    >>> float(wave_energy_density(1.0))
    628.453125
    """
    h = np.asarray(wave_height, float)
    if np.any(h < 0):
        raise ValueError("wave height must be >= 0")
    return water_density * gravity * h**2 / 16.0


@_doc
def nut_work(lift: float, period: float, geometry: BuoyGeometry,
             pto_force: Callable[[np.ndarray, np.ndarray], np.ndarray],
             samples: int = 256, lead: float = 0.02) -> tuple[float, float]:
    """Return the work absorbed by the nut over one cycle of z = h sin(2π t/T), and the waterplane.

    Parameters
    ----------
    lift : float
        Heave amplitude h [m].
    %(motion_period)s
    %(geometry)s
    pto_force : callable
        (nut velocity [m s-1], nut acceleration [m s-2]) -> F_PTO [N].
    samples : int
        Samples of the cycle (the rectangle rule on a periodic integrand is spectrally
        accurate).
    %(lead)s

    Returns
    -------
    work : float
        W = -∮ F_PTO v dt [J] (positive for a resisting PTO).
    area : float
        Time-mean waterplane area S_avg [m2] in still water.

    Examples
    --------
    >>> from flumekit.ballscrew.buoy import BuoyGeometry, nut_work
    >>> w, s = nut_work(1.0, 3.8, BuoyGeometry(), lambda v, a: -1e5 * v)
    >>> round(w), round(s, 3)
    (29062, 13.155)
    """
    motion = reference_motion(lift, period, 1, samples)
    kin = kinematics(motion, geometry, lead)
    v = kin["nut_velocity"].values
    f = np.asarray(pto_force(v, kin["nut_acceleration"].values), float)
    dt = period / samples
    work = -float(np.sum(f * v) * dt)  # periodic: rectangle rule is spectrally accurate
    return work, float(kin["waterplane_area"].mean())


@_doc
def lift_from_energy_balance(wave_height: float, wave_period: float, geometry: BuoyGeometry,
                             pto_force: Callable[[np.ndarray, np.ndarray], np.ndarray],
                             lead: float = 0.02, samples: int = 256) -> float:
    """Return the lift h of the buoy for a sea state {H, T} by the energy balance algorithm.

    The energy brought by one wave to the float, E S_avg with E = ρ g H²/16 (Eq. (2)) and S_avg
    the mean waterplane area during the motion, equals the work of the nut against the PTO over
    one cycle of the kinematic input z(t) = h sin(2π t/T) (Fig. 4). The paper iterates; here
    E S_avg(h) = W(h) is solved with Brent's method (W grows with h, so the root is unique).

    Parameters
    ----------
    %(wave_height)s
    %(wave_period)s
    geometry : BuoyGeometry
        Buoy geometry (limits h below the static draft and the arm reach).
    pto_force : callable
        (nut velocity [m s-1], nut acceleration [m s-2]) -> F_PTO [N], e.g.
        :func:`flumekit.ballscrew.screw.pto_force_function`.
    %(lead)s
    samples : int
        Samples per cycle of the work integral.

    Returns
    -------
    float
        Lift h [m] (amplitude of z from the static equilibrium); 0 when the PTO's friction
        exceeds the wave's energy.

    Raises
    ------
    ValueError
        For H or T not positive, or a sea state carrying more energy than the PTO absorbs
        within the float's range of motion.

    %(references_senatore2022)s, Eq. (2) and Fig. 4.

    Examples
    --------
    >>> from flumekit.ballscrew.buoy import BuoyGeometry, lift_from_energy_balance
    >>> round(lift_from_energy_balance(1.0, 3.8, BuoyGeometry(), lambda v, a: -1e5 * v), 4)
    0.5563
    """
    if not (wave_height > 0 and wave_period > 0):
        raise ValueError("sea state needs H > 0 and T > 0")
    e = float(wave_energy_density(wave_height, geometry.water_density, geometry.gravity))

    def balance(h):
        w, s_avg = nut_work(h, wave_period, geometry, pto_force, samples, lead)
        return w - e * s_avg

    h_max = 0.999 * min(geometry.static_draft, geometry.float_radius - geometry.static_draft,
                        geometry.arm_length * (1 - abs(np.sin(geometry.rest_angle))))
    h_min = 1e-6 * h_max
    if balance(h_max) < 0:
        raise ValueError(f"sea state H={wave_height} m, T={wave_period} s carries more energy "
                         f"than the PTO absorbs within the float's range of motion "
                         f"(h < {h_max:.3g} m)")
    if balance(h_min) > 0:
        return 0.0  # the PTO friction exceeds the wave energy: the buoy does not move
    return float(optimize.brentq(balance, h_min, h_max, xtol=1e-10, rtol=1e-10))
