"""Ball-screw PTO: force Eq. (3), ball forces and efficiency Eqs. (4)-(6), coupled to the EHL.

The EHL model of the contacts is evaluated at every time step (the "simultaneous" scheme of
Fig. 6). Senatore & De Simone 2022, Sect. 2. Notation: α lead angle at the pitch radius r_m,
β contact angle, Q ball-groove normal load, f (= f_A) ball-nut and f_B ball-screw friction
coefficients, γ_B slip angle at the ball-screw contact, ρ rolling-friction angle (tan ρ =
rolling resistance coefficient; the paper takes it from Houpert and Balan, here it is a
parameter).

Two corrections to Eqs. (5)-(6) as printed, both needed for energy conservation:

1. Eq. (6) multiplies the lead angle α of the *pitch* radius by the lever arm of the contact
   point, r_m - r_b cos β. A force normal to the helicoid at radius r has tangential/axial ratio
   tan α_r = r_m tan α / r, so the torque/axial-force ratio is r_m tan α at every radius. With the
   printed form a frictionless screw would have η = 1 - r_b cos β / r_m ≈ 0.89: energy lost
   without friction. The lever arm here is r_m (equivalently r_B with α_B), which gives η = 1
   at zero friction.
2. The sign of the γ_B term in Eq. (6) depends on how γ_B is oriented. γ_B ≥ 0 is taken as the
   magnitude of the slip angle and every friction term is oriented against the motion, so
   friction only ever reduces the transmitted torque (dissipation ≥ 0) and η falls as friction
   rises.

In indirect (back-driving) mode, nut → screw::

    F_ball = Q {cos ρ [sin β cos α + f cos β cos α] + sin ρ sin α}                       (5)
    M_scr = r_m Q {cos ρ [sin β sin α - f_B (cos γ_B cos β sin α + sin γ_B cos α)]
                   - sin ρ cos α}                                                     (6)
    η = M_scr ω / (F_ball v) = M_scr / (F_ball r_m tan α)   (ω = v / (r_m tan α))       (4)

With β = 90°, f = f_B = 0 this is the classic tan(α - ρ)/tan α. In direct mode (screw → nut,
e.g. while the rotor's inertia drives the nut) all friction terms change sign and
η_d = F_ball r_m tan α / M_scr = tan α / tan(α + ρ) in the classic case.

Self-locking: when M_scr ≤ 0 (friction angle above the lead angle) the nut cannot back-drive
the screw. :func:`indirect_efficiency` then returns η = 0 (documented, vectorised) or raises
``ValueError`` with ``strict=True``.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass

import numpy as np
import xarray as xr

from flumekit import conventions
from flumekit.ballscrew import buoy, ehl
from flumekit.docstrings import filler
from flumekit.errors import GeometryError

#: docstring text that several functions of this module share
_doc = filler(
    friction_nut=("friction_nut : float or array_like\n"
                  "    Ball-nut friction coefficient f [-], finite and ≥ 0."),
    friction_screw=("friction_screw : float or array_like\n"
                    "    Ball-screw friction coefficient f_B [-], finite and ≥ 0."),
    lead_angle_=("lead_angle_ : float\n"
                 "    Lead angle α [rad]."),
    lubricant=("lubricant : Lubricant\n"
               "    The lubricant and friction law."),
    pto=("pto : PTOCoefficients\n"
         "    The coefficients of Eq. (3)."),
    friction_angle=("rho : float or array_like\n"
                    "    Rolling-friction angle ρ [rad], finite and ≥ 0."),
    screw=("screw : BallScrew\n"
           "    The ball screw."),
    slip_angle=("slip_angle : float\n"
                "    Slip angle γ_B [rad]."),
    # the ball contact of Eqs. (4)-(6), in the order of the functions' arguments
    ball_contact=("%(lead_angle_)s\n"
                  "%(contact_angle)s\n"
                  "%(friction_nut)s\n"
                  "%(friction_screw)s\n"
                  "%(friction_angle)s\n"
                  "%(slip_angle)s"))


@_doc
@dataclass(frozen=True)
class BallScrew:
    """Geometry, materials and surfaces of the recirculating ball screw.

    Defaults: a large ground ball screw (80 mm x 20 mm lead, 1/2" balls) in the size class of
    the UMBRA actuators; each parameter says its value's reason.

    Parameters
    ----------
    pitch_diameter : float
        Pitch (ball-centre) diameter d_m [m]; 0.080 m, with the 20 mm lead α = 4.55° and
        ω ≈ 140 rad/s at 0.45 m/s.
    lead : float
        Lead [m]; 0.020 m.
    ball_diameter : float
        Ball diameter [m]; 12.7 mm (1/2"), standard for an 80 mm screw.
    contact_angle : float
        Contact angle β [rad]; 45°, the usual gothic-arch groove.
    conformity_screw : float
        Groove radius / ball diameter of the screw [-]; 0.54 (0.52-0.56 usual).
    conformity_nut : float
        The same for the nut [-].
    loaded_balls : int
        Effective loaded balls [-]; 60 (3 circuits x 2.5 turns x ~19 balls/turn ≈ 140 balls,
        of which about half carry load in one direction of a preloaded double nut).
    preload_per_ball : float
        Preload per ball [N]; 50 N (about 2 % of the dynamic rating per ball), which also keeps
        the EHL load positive at the motion reversals.
    slip_angle : float
        Slip angle γ_B at the ball-screw contact [rad]; 1°, a small constant slip direction
        (the paper: "constant slip angle γ_B").
    rolling_resistance : float
        tan ρ [-]; 2e-4, rolling resistance of a hardened steel ball on a hardened raceway
        (textbook range 1e-4 to 5e-4 for hardened steel on steel); with the lubricant's
        friction law it sets the top of the efficiency range, 97 % in the paper (§3.1).
    roughness_ball : float
        RMS roughness of the balls [m]; 0.05 µm (grade G10).
    roughness_screw : float
        RMS roughness of the ground screw raceway [m]; 0.15 µm.
    roughness_nut : float
        RMS roughness of the ground nut raceway [m]; 0.15 µm.
    young_modulus : float
        Young's modulus [Pa]; bearing steel.
    poisson_ratio : float
        Poisson's ratio [-]; bearing steel.

    Raises
    ------
    flumekit.errors.GeometryError
        For a non-positive lead, a ball not smaller than the pitch diameter, a contact angle
        outside (0, 90°), no loaded ball, a non-positive preload, a slip angle outside [0, 90°)
        or a negative rolling resistance.

    %(references_senatore2022)s, Sect. 2 and §3.1.

    Examples
    --------
    >>> import numpy as np
    >>> from flumekit.ballscrew.screw import BallScrew
    >>> round(float(np.degrees(BallScrew().lead_angle)), 2)
    4.55
    """

    pitch_diameter: float = 0.080
    lead: float = 0.020
    ball_diameter: float = 0.0127
    contact_angle: float = float(np.radians(45.0))
    conformity_screw: float = 0.54
    conformity_nut: float = 0.54
    loaded_balls: int = 60
    preload_per_ball: float = 50.0
    slip_angle: float = float(np.radians(1.0))
    rolling_resistance: float = 2e-4
    roughness_ball: float = 0.05e-6
    roughness_screw: float = 0.15e-6
    roughness_nut: float = 0.15e-6
    young_modulus: float = 208e9
    poisson_ratio: float = 0.3

    def __post_init__(self):
        """Check the geometry (see the class's Raises)."""
        if not (self.lead > 0 and self.pitch_diameter > self.ball_diameter > 0):
            raise GeometryError("ball screw: need lead > 0 and pitch diameter > ball diameter > 0")
        if not 0 < self.contact_angle < np.pi / 2:
            raise GeometryError(f"ball screw: contact angle must lie in (0, 90°), got "
                                f"{np.degrees(self.contact_angle):.3g}°")
        if self.loaded_balls < 1 or self.preload_per_ball <= 0:
            raise GeometryError("ball screw: need >= 1 loaded ball and a positive preload "
                                "(the EHL film needs a positive contact load)")
        if not (0 <= self.slip_angle < np.pi / 2 and self.rolling_resistance >= 0):
            raise GeometryError("ball screw: slip angle in [0, 90°) and rolling resistance >= 0")

    @property
    def lead_angle(self) -> float:
        """Lead angle at the pitch radius [rad]."""
        return lead_angle(self.lead, self.pitch_diameter)

    @property
    def rho(self) -> float:
        """Rolling-friction angle ρ = atan(rolling resistance) [rad]."""
        return float(np.arctan(self.rolling_resistance))


@_doc
@dataclass(frozen=True)
class Lubricant:
    """Lubricant and friction law.

    With the default values the reference scenario gives η from 73 % to 97 % with the screw
    contact mixed 89 % of the time, the three statements of Senatore & De Simone (2022) §3.1
    (``flumekit bench ballscrew`` prints the table).

    Parameters
    ----------
    viscosity : float
        Dynamic viscosity at ambient pressure η0 [Pa s]; 0.07, the base oil of an ISO VG 100
        grease near 45 °C (the paper's nut runs up to ≈ 20 + 40 °C; the thermal model is
        standalone, as in the paper, so η0 is not updated). With the default surfaces λ peaks
        near 3 at full speed: mostly mixed.
    pressure_viscosity : float
        Pressure-viscosity coefficient α [Pa-1]; 2.0e-8, mineral oil.
    friction_boundary : float
        Friction coefficient of boundary lubrication [-]; 0.13, lubricated steel (textbook
        range 0.1-0.15); it sets the bottom of the efficiency range at the motion reversals,
        73 % in the paper (§3.1).
    friction_full_film : float
        EHL traction coefficient of a full film [-]; 0.002, at the small slide-to-roll ratios of
        a ball screw (measured traction curves start at 0.001-0.01 near pure rolling).

    Raises
    ------
    ValueError
        For a non-positive viscosity or pressure-viscosity coefficient, or unless
        0 ≤ ``friction_full_film`` ≤ ``friction_boundary``.

    %(references_senatore2022)s, Fig. 8 and §3.1.

    Examples
    --------
    The defaults, and the friction of the Stribeck curve where film and asperities carry half
    the load each (λ = √3): the mean of the boundary and full-film coefficients:

    >>> from flumekit.ballscrew.ehl import stribeck_friction
    >>> from flumekit.ballscrew.screw import Lubricant
    >>> oil = Lubricant()
    >>> oil.viscosity, oil.friction_boundary, oil.friction_full_film
    (0.07, 0.13, 0.002)
    >>> f = stribeck_friction(3 ** 0.5, oil.friction_boundary, oil.friction_full_film)
    >>> round(float(f), 6)  # (0.13 + 0.002) / 2
    0.066
    """

    viscosity: float = 0.07
    pressure_viscosity: float = 2.0e-8
    friction_boundary: float = 0.13
    friction_full_film: float = 0.002

    def __post_init__(self):
        """Check the values (see the class's Raises)."""
        if not (self.viscosity > 0 and self.pressure_viscosity > 0):
            raise ValueError("lubricant: viscosity and pressure-viscosity coefficient must be > 0")
        if not 0 <= self.friction_full_film <= self.friction_boundary:
            raise ValueError("lubricant: need 0 <= full-film friction <= boundary friction")


@_doc
@dataclass(frozen=True)
class PTOCoefficients:
    """Coefficients of Eq. (3) in physical form.

    Parameters
    ----------
    damping : float
        K_damp [N s m-1], the generator's electromagnetic damping reflected to the nut. 60 kN s/m
        gives a mean generator power of ≈ 4.6 kW in the reference scenario, the order of the
        wave energy brought to the 5 m float by T = 3.8 s, H ≈ 1.5 m waves (the energy balance
        algorithm gives h ≈ 1 m for H = 1.5 m with these defaults).
    viscous : float
        K_visc [N s m-1], viscous losses of seals and grease churning (≈ 1 % of K_damp).
    rotor_inertia : float
        J [kg m2] of the EMRG rotor and screw shaft; reflected to the nut as J (2π/lead)²
        (≈ 1000 kg for 0.01 kg m², lead 20 mm).
    nut_mass : float
        Mass of the nut and its carriage [kg].

    Raises
    ------
    ValueError
        For a negative coefficient (a damping, an inertia and a mass are all ≥ 0; zero
        leaves the term out).

    %(references_senatore2022)s, Eq. (3).

    Examples
    --------
    The force of Eq. (3) on a nut sliding at 0.1 m/s (damping and viscous losses, (60 000 +
    600) × 0.1 N), then starting from rest at 1 m/s² (the rotor reflected through the 20 mm
    lead, 0.01 (2π/0.02)² + 30 kg), without friction:

    >>> from flumekit.ballscrew.screw import PTOCoefficients, pto_force
    >>> pto = PTOCoefficients()
    >>> pto_force([0.1, 0.0], [0.0, 1.0], 0.0, pto.damping, pto.viscous,
    ...           pto.inertia(0.02)).round(1).tolist()
    [-6060.0, -1017.0]
    """

    damping: float = 6.0e4
    viscous: float = 600.0
    rotor_inertia: float = 0.01
    nut_mass: float = 30.0

    def __post_init__(self):
        """Check the coefficients (see the class's Raises)."""
        if min(self.damping, self.viscous, self.rotor_inertia, self.nut_mass) < 0:
            raise ValueError("PTO coefficients must be >= 0")

    @_doc
    def inertia(self, lead: float) -> float:
        """Return K_inert of Eq. (3), J (2π/lead)² + m_nut.

        Parameters
        ----------
        %(lead)s

        Returns
        -------
        float
            Equivalent inertia on the nut [kg].

        Examples
        --------
        >>> from flumekit.ballscrew.screw import PTOCoefficients
        >>> round(PTOCoefficients().inertia(0.02), 1)
        1017.0
        """
        return self.rotor_inertia * (2 * np.pi / lead) ** 2 + self.nut_mass


# --- geometry and kinematics -------------------------------------------------------------------

@_doc
def lead_angle(lead: float, pitch_diameter: float) -> float:
    """Return the lead angle α = atan(lead / (π d_m)) at the pitch diameter.

    Parameters
    ----------
    %(lead)s
    pitch_diameter : float
        Pitch diameter d_m [m].

    Returns
    -------
    float
        Lead angle [rad].

    Raises
    ------
    flumekit.errors.GeometryError
        For a non-positive lead or pitch diameter.

    Examples
    --------
    >>> from flumekit.ballscrew.screw import lead_angle
    >>> round(lead_angle(0.020, 0.080), 6)
    0.07941
    """
    if not (lead > 0 and pitch_diameter > 0):
        raise GeometryError(f"lead and pitch diameter must be positive, "
                            f"got {lead}, {pitch_diameter}")
    return float(np.arctan(lead / (np.pi * pitch_diameter)))


@_doc
def entrainment_speed(screw_speed, screw: BallScrew) -> np.ndarray:
    """Return the mean entrainment (rolling) speed of the ball-groove contacts.

    Ball-bearing kinematics with the screw as inner race turning at ω relative to the
    non-rotating nut: u = ``|ω|`` d_m/4 (1 - γ²), γ = d cos β / d_m, stretched by 1/cos α along the
    helical path. Pure rolling on the nut (the paper's assumption), so u is the same at both
    contacts.

    Parameters
    ----------
    screw_speed : float or array_like
        Screw angular speed ω [rad s-1].
    %(screw)s

    Returns
    -------
    numpy.ndarray
        Entrainment speed [m s-1].

    Examples
    --------
    >>> from flumekit.ballscrew.screw import BallScrew, entrainment_speed
    >>> round(float(entrainment_speed(100.0, BallScrew())), 4)
    1.981
    """
    gam = screw.ball_diameter * np.cos(screw.contact_angle) / screw.pitch_diameter
    return (np.abs(np.asarray(screw_speed, float)) * screw.pitch_diameter / 4.0
            * (1.0 - gam**2) / np.cos(screw.lead_angle))


# --- Eqs. (4)-(6) --------------------------------------------------------------------------

@_doc
def ball_forces(normal_load, lead_angle_: float, contact_angle: float, friction_nut,
                friction_screw, rho, slip_angle: float, pitch_radius: float,
                mode: str = "indirect") -> tuple[np.ndarray, np.ndarray]:
    """Return the axial force and screw torque of one loaded ball, Eqs. (5)-(6).

    As corrected in the module's description (lever arm r_m, friction against the motion).

    Parameters
    ----------
    normal_load : float or array_like
        Closing force Q = Q_A = Q_B [N].
    %(ball_contact)s
    pitch_radius : float
        Pitch radius r_m [m].
    mode : {"indirect", "direct"}
        'indirect' (nut drives the screw) or 'direct' (screw drives the nut).

    Returns
    -------
    force : numpy.ndarray
        Axial ball force F_ball [N].
    torque : numpy.ndarray
        Screw torque M_scr [N m].

    Raises
    ------
    flumekit.errors.GeometryError
        For a lead angle outside (0, 90°).
    ValueError
        For an unknown ``mode`` or a negative or non-finite friction coefficient or angle.

    %(references_senatore2022)s, Eqs. (5)-(6).

    Examples
    --------
    >>> import numpy as np
    >>> from flumekit.ballscrew.screw import ball_forces
    >>> f, m = ball_forces(100.0, 0.1, np.pi / 2, 0.0, 0.0, 0.0, 0.0, 0.04)
    >>> round(float(f), 4), round(float(m), 4)  # frictionless: Q cos α, r_m Q sin α
    (99.5004, 0.3993)
    """
    s = {"indirect": 1.0, "direct": -1.0}.get(mode)
    if s is None:
        raise ValueError(f"mode must be 'indirect' or 'direct', got {mode!r}")
    if not 0 < lead_angle_ < np.pi / 2:
        raise GeometryError(f"lead angle must lie in (0, 90°), got {lead_angle_}")
    q = np.asarray(normal_load, float)
    a, b, g = lead_angle_, contact_angle, slip_angle
    f, fb, r = (np.asarray(x, float) for x in (friction_nut, friction_screw, rho))
    for name, x in (("ball-nut friction coefficient", f), ("ball-screw friction coefficient", fb),
                    ("rolling-friction angle", r)):
        bad = np.ravel(x)[~(np.isfinite(np.ravel(x)) & (np.ravel(x) >= 0))]
        if bad.size:  # NaN would pass a plain x < 0 test and give a NaN efficiency
            raise ValueError(f"{name} must be finite and >= 0, got {bad[:3]}")
    cr, sr = np.cos(r), np.sin(r)
    # Eq. (5) in Senatore & De Simone 2022
    force = q * (cr * (np.sin(b) * np.cos(a) + s * f * np.cos(b) * np.cos(a)) + s * sr * np.sin(a))
    # Eq. (6) in Senatore & De Simone 2022, lever arm r_m and dissipative orientation (module doc)
    torque = pitch_radius * q * (
        cr * (np.sin(b) * np.sin(a)
              - s * fb * (np.cos(g) * np.cos(b) * np.sin(a) + np.sin(g) * np.cos(a)))
        - s * sr * np.cos(a))
    return force, torque


@_doc
def indirect_efficiency(lead_angle_: float, contact_angle: float, friction_nut, friction_screw,
                        rho=0.0, slip_angle: float = 0.0, strict: bool = False) -> np.ndarray:
    """Return the indirect (back-driving) efficiency η = M ω / (F v), Eqs. (4)-(6).

    Independent of Q and of the pitch radius. Where the ball screw is self-locking (M ≤ 0:
    the friction exceeds what the lead angle can overcome) η = 0, or ``ValueError`` if
    ``strict``.

    Parameters
    ----------
    %(ball_contact)s
    strict : bool
        Raise instead of returning 0 where the screw self-locks.

    Returns
    -------
    numpy.ndarray
        η [-].

    Raises
    ------
    flumekit.errors.GeometryError
        For a lead angle outside (0, 90°).
    ValueError
        With ``strict``, where the screw self-locks; for a negative or non-finite friction
        coefficient or angle.

    %(references_senatore2022)s, Eqs. (4)-(6).

    Examples
    --------
    Frictionless contact with a rolling-friction angle ρ: η = tan(α − ρ) / tan α, and 0 once
    ρ exceeds the lead angle α = 5° (tan ρ = 0.1):

    >>> import numpy as np
    >>> from flumekit.ballscrew.screw import indirect_efficiency
    >>> a = np.radians(5.0)
    >>> indirect_efficiency(a, np.pi / 2, 0.0, 0.0, np.arctan([0.01, 0.1])).round(6)
    array([0.884925, 0.      ])
    """
    f, m = ball_forces(1.0, lead_angle_, contact_angle, friction_nut, friction_screw, rho,
                       slip_angle, 1.0, "indirect")
    locked = m <= 0
    if strict and np.any(locked):
        raise ValueError("ball screw is self-locking (friction angle above the lead angle): "
                         "the nut cannot back-drive the screw")
    return np.where(locked, 0.0, m / (f * np.tan(lead_angle_)))


@_doc
def direct_efficiency(lead_angle_: float, contact_angle: float, friction_nut, friction_screw,
                      rho=0.0, slip_angle: float = 0.0) -> np.ndarray:
    """Return the direct efficiency η_d = F v / (M ω) (screw drives the nut), Eqs. (4)-(6) reversed.

    Parameters
    ----------
    %(ball_contact)s

    Returns
    -------
    numpy.ndarray
        η_d [-], clipped to [0, 1].

    Raises
    ------
    flumekit.errors.GeometryError
        For a lead angle outside (0, 90°).
    ValueError
        For a negative or non-finite friction coefficient or angle.

    %(references_senatore2022)s, Eqs. (4)-(6).

    Examples
    --------
    >>> import numpy as np
    >>> from flumekit.ballscrew.screw import direct_efficiency
    >>> a, rho = np.radians(5.0), np.arctan(0.01)
    >>> round(float(direct_efficiency(a, np.pi / 2, 0.0, 0.0, rho)), 6)  # tan α / tan(α + ρ)
    0.896639
    """
    f, m = ball_forces(1.0, lead_angle_, contact_angle, friction_nut, friction_screw, rho,
                       slip_angle, 1.0, "direct")
    return np.clip(f * np.tan(lead_angle_) / m, 0.0, 1.0)


# --- Eq. (3) ---------------------------------------------------------------------------------

@_doc
def pto_force(nut_velocity, nut_acceleration, friction_force, damping: float, viscous: float,
              inertia: float) -> np.ndarray:
    """Return the axial PTO force on the nut, Eq. (3) in Senatore & De Simone 2022.

    F_PTO = -K_damp v - F_friction sign(v) - K_visc v - K_inert a.

    Parameters
    ----------
    %(nut_velocity)s
    nut_acceleration : float or array_like
        Nut acceleration a [m s-2].
    friction_force : float or array_like
        Friction force magnitude F_friction ≥ 0 [N] (from the lubrication model).
    damping : float
        K_damp [N s m-1].
    viscous : float
        K_visc [N s m-1].
    inertia : float
        K_inert [kg].

    Returns
    -------
    numpy.ndarray
        F_PTO [N], positive extending the actuator.

    Raises
    ------
    ValueError
        For a negative or non-finite friction force.

    %(references_senatore2022)s, Eq. (3).

    Examples
    --------
    >>> from flumekit.ballscrew.screw import pto_force
    >>> pto_force([0.1, -0.1], [0.0, 0.0], 50.0, 1000.0, 10.0, 5.0).tolist()
    [-151.0, 151.0]
    """
    v = np.asarray(nut_velocity, float)
    fr = np.asarray(friction_force, float)
    if not np.all(np.isfinite(fr) & (fr >= 0)):
        raise ValueError("friction force magnitude must be finite and >= 0")
    return (-damping * v - fr * np.sign(v) - viscous * v
            - inertia * np.asarray(nut_acceleration, float))


# --- coupled multibody-EHL evaluation ----------------------------------------------------------

@dataclass(frozen=True)
class _Contacts:
    rx_screw: float
    ry_screw: float
    rx_nut: float
    ry_nut: float
    modulus: float
    sigma_screw: float
    sigma_nut: float


def _contacts(screw: BallScrew) -> _Contacts:
    d, dm, b = screw.ball_diameter, screw.pitch_diameter, screw.contact_angle
    rxs, rys = ehl.ball_groove_radii(d, dm, b, screw.conformity_screw, "inner")
    rxn, ryn = ehl.ball_groove_radii(d, dm, b, screw.conformity_nut, "outer")
    return _Contacts(rxs, rys, rxn, ryn,
                     ehl.reduced_modulus(screw.young_modulus, screw.poisson_ratio),
                     ehl.composite_roughness(screw.roughness_ball, screw.roughness_screw),
                     ehl.composite_roughness(screw.roughness_ball, screw.roughness_nut))


@_doc
def pto_state(nut_velocity, nut_acceleration, screw: BallScrew = BallScrew(),
              lubricant: Lubricant = Lubricant(), pto: PTOCoefficients = PTOCoefficients(),
              iterations: int = 8, tolerance: float = 1e-10) -> dict[str, np.ndarray]:
    """Compute the ball-screw state at every time step: EHL of both contacts, friction, efficiency.

    The load transmitted through the balls to the screw is F_t = K_damp v + J (2π/l)² a
    (generator and rotor inertia). When F_t v ≥ 0 the nut drives the screw (indirect mode) and
    the nut must push F_t/η: the friction force is F_fr = ``|F_t|`` (1/η - 1); otherwise the rotor
    drives the nut (direct mode) and F_fr = ``|F_t|`` (1 - η_d). The ball load
    Q = Q_preload + F_balls / (z sin β cos α) depends on η, so η, Q and the EHL state are
    iterated to a fixed point (a handful of vectorised iterations; η depends on Q only through
    the film thickness, W^-0.073).

    Parameters
    ----------
    nut_velocity : array_like
        Nut velocity v [m s-1].
    nut_acceleration : array_like
        Nut acceleration a [m s-2], of the shape of ``nut_velocity``.
    %(screw)s
    %(lubricant)s
    %(pto)s
    iterations : int
        Fixed-point iterations at most.
    tolerance : float
        Largest change of η that ends the iterations [-].

    Returns
    -------
    dict of str to numpy.ndarray
        screw_speed [rad s-1], entrainment_speed [m s-1], ball_load [N],
        min_film_thickness_{screw,nut} [m], film_parameter_{screw,nut} [-],
        lubrication_regime_{screw,nut}, friction_coefficient_{screw,nut} [-],
        ballscrew_efficiency (indirect, Fig. 15) [-], direct_efficiency [-],
        power_flow_direction (+1 indirect, -1 direct), friction_force [N], pto_force (Eq. 3)
        [N], screw_torque [N m], input_power, output_power, generator_power,
        mechanical_power_loss [W].

    Raises
    ------
    ValueError
        For velocity and acceleration not finite or of different shapes, or a motion in which
        the screw self-locks.

    %(references_senatore2022)s, Eqs. (3)-(7), Figs. 6 and 15.

    Examples
    --------
    >>> import numpy as np
    >>> from flumekit.ballscrew.screw import pto_state
    >>> s = pto_state(np.array([0.2, 0.4]), np.zeros(2))
    >>> s["ballscrew_efficiency"].round(4).tolist(), s["lubrication_regime_screw"].tolist()
    ([0.8962, 0.9674], [1, 2])
    """
    v = np.asarray(nut_velocity, float)
    a = np.asarray(nut_acceleration, float)
    if v.shape != a.shape or not (np.all(np.isfinite(v)) and np.all(np.isfinite(a))):
        raise ValueError("nut velocity and acceleration must be finite arrays of equal shape")
    c = _contacts(screw)
    al, be = screw.lead_angle, screw.contact_angle
    omega = buoy.screw_speed(v, screw.lead)
    u = entrainment_speed(omega, screw)
    k_rot = pto.rotor_inertia * (2 * np.pi / screw.lead) ** 2
    f_t = pto.damping * v + k_rot * a
    indirect = f_t * v >= 0
    per_ball = 1.0 / (screw.loaded_balls * np.sin(be) * np.cos(al))
    eta = np.ones_like(v)
    for _ in range(iterations):  # fixed-point iterations, vectorised over time
        f_balls = np.where(indirect, np.abs(f_t) / np.maximum(eta, 1e-6), np.abs(f_t))
        q = screw.preload_per_ball + f_balls * per_ball
        hs, _ = ehl.film_thickness(u, q, c.rx_screw, c.ry_screw, c.modulus,
                                   lubricant.viscosity, lubricant.pressure_viscosity)
        hn, _ = ehl.film_thickness(u, q, c.rx_nut, c.ry_nut, c.modulus,
                                   lubricant.viscosity, lubricant.pressure_viscosity)
        lam_s, lam_n = ehl.film_parameter(hs, c.sigma_screw), ehl.film_parameter(hn, c.sigma_nut)
        fs = ehl.stribeck_friction(lam_s, lubricant.friction_boundary, lubricant.friction_full_film)
        fn = ehl.stribeck_friction(lam_n, lubricant.friction_boundary, lubricant.friction_full_film)
        new = indirect_efficiency(al, be, fn, fs, screw.rho, screw.slip_angle)
        change = np.max(np.abs(new - eta))
        eta = new
        if change < tolerance:
            break
    if np.any(indirect & (eta <= 0) & (v != 0)):
        raise ValueError("ball screw self-locks in the requested motion: the nut cannot "
                         "back-drive the screw (lead angle below the friction angle)")
    eta_d = direct_efficiency(al, be, fn, fs, screw.rho, screw.slip_angle)
    with np.errstate(divide="ignore"):
        f_fr = np.where(indirect, np.abs(f_t) * (1.0 / np.where(eta > 0, eta, 1.0) - 1.0),
                        np.abs(f_t) * (1.0 - eta_d))
    f_pto = pto_force(v, a, f_fr, pto.damping, pto.viscous, pto.inertia(screw.lead))
    f_nut = f_t + f_fr * np.sign(v)
    return {
        "screw_speed": omega, "entrainment_speed": u, "ball_load": q,
        "min_film_thickness_screw": hs, "min_film_thickness_nut": hn,
        "film_parameter_screw": lam_s, "film_parameter_nut": lam_n,
        "lubrication_regime_screw": ehl.lubrication_regime(lam_s),
        "lubrication_regime_nut": ehl.lubrication_regime(lam_n),
        "friction_coefficient_screw": fs, "friction_coefficient_nut": fn,
        "ballscrew_efficiency": eta, "direct_efficiency": eta_d,
        "power_flow_direction": np.where(indirect, 1, -1).astype(np.int8),
        "friction_force": f_fr, "pto_force": f_pto,
        "screw_torque": f_t * screw.lead / (2 * np.pi),
        "input_power": f_nut * v, "output_power": f_t * v,
        "generator_power": pto.damping * v**2,
        "mechanical_power_loss": f_fr * np.abs(v) + pto.viscous * v**2,
    }


@_doc
def pto_force_function(screw: BallScrew = BallScrew(), lubricant: Lubricant = Lubricant(),
                       pto: PTOCoefficients = PTOCoefficients()):
    """Return the callable (v, a) -> F_PTO of the full model.

    For :func:`flumekit.ballscrew.buoy.lift_from_energy_balance`: :func:`pto_state`'s
    ``pto_force``.

    Parameters
    ----------
    %(screw)s
    %(lubricant)s
    %(pto)s

    Returns
    -------
    callable
        (nut velocity [m s-1], nut acceleration [m s-2]) -> F_PTO [N].

    Examples
    --------
    >>> import numpy as np
    >>> from flumekit.ballscrew.screw import pto_force_function
    >>> round(float(pto_force_function()(np.array([0.2]), np.zeros(1))[0]), 1)
    -13509.4
    """
    def force(v, a):
        return pto_state(v, a, screw, lubricant, pto)["pto_force"]
    return force


@_doc
def efficiency(kin: xr.Dataset, screw: BallScrew = BallScrew(), lubricant: Lubricant = Lubricant(),
               pto: PTOCoefficients = PTOCoefficients()) -> xr.Dataset:
    """Compute the PTO force, EHL state and ball-screw efficiency at every time step.

    Step 2 of the scenario: :func:`pto_state` on the nut motion of ``kin``, then the
    inverse dynamics of the buoy (:func:`flumekit.ballscrew.buoy.inverse_dynamics`). Cheap (no
    thermal model): the efficiency-only scene stops here.

    Parameters
    ----------
    kin : xarray.Dataset
        Output of :func:`flumekit.ballscrew.buoy.kinematics` (its lead must match ``screw``).
    %(screw)s
    %(lubricant)s
    %(pto)s

    Returns
    -------
    xarray.Dataset
        Over ``time``: the variables of :func:`pto_state`, nut_velocity, nut_acceleration, the
        inverse-dynamics ``wave_force`` and ``net_vertical_force`` [N]; attributes hold the
        parameters and ``wave_period``.

    Raises
    ------
    ValueError
        When ``kin`` was computed for another lead.

    %(references_senatore2022)s, Sect. 3.1 and Fig. 15.

    Examples
    --------
    >>> from flumekit.ballscrew import efficiency, kinematics
    >>> from flumekit.ballscrew.buoy import reference_motion
    >>> eta = efficiency(kinematics(reference_motion())).ballscrew_efficiency
    >>> round(float(eta.min()), 2), round(float(eta.max()), 2)  # the paper: 73 % to 97 %
    (0.73, 0.97)
    """
    if abs(float(kin.attrs.get("lead", screw.lead)) - screw.lead) > 1e-12:
        raise ValueError(f"kinematics were computed for lead {kin.attrs['lead']} m, the ball "
                         f"screw has lead {screw.lead} m")
    state = pto_state(kin["nut_velocity"].values, kin["nut_acceleration"].values, screw,
                      lubricant, pto)
    geometry = buoy.geometry_from_attrs(kin)
    dyn = buoy.inverse_dynamics(kin, state["pto_force"], geometry)
    params = {**{f"screw_{k}": v for k, v in asdict(screw).items()},
              **{f"lubricant_{k}": v for k, v in asdict(lubricant).items()},
              **{f"pto_{k}": v for k, v in asdict(pto).items()}}
    ds = xr.Dataset({name: ("time", val) for name, val in state.items()},
                    coords={"time": kin["time"].values},
                    attrs=conventions.global_attrs("ball-screw efficiency (multibody + EHL)",
                                                   "flumekit.ballscrew.screw.efficiency", params))
    ds["nut_velocity"] = kin["nut_velocity"]
    ds["nut_acceleration"] = kin["nut_acceleration"]
    ds["wave_force"] = dyn["wave_force"]
    ds["net_vertical_force"] = dyn["net_vertical_force"]
    ds.attrs.update({k: float(v) for k, v in params.items()})
    ds.attrs["pto_inertia_coefficient"] = pto.inertia(screw.lead)
    if "wave_period" in kin.attrs:
        ds.attrs["wave_period"] = kin.attrs["wave_period"]
    return conventions.annotate(ds)


@_doc
def sea_state_motion(wave_height: float, wave_period: float,
                     geometry: buoy.BuoyGeometry = buoy.BuoyGeometry(),
                     screw: BallScrew = BallScrew(), lubricant: Lubricant = Lubricant(),
                     pto: PTOCoefficients = PTOCoefficients(), n_periods: int = 1,
                     samples_per_period: int = 760) -> xr.Dataset:
    """Return the kinematic input z(t) = h sin(2π t/T) of a sea state (scenario step 0).

    The lift h comes from the energy balance algorithm (Fig. 4,
    :func:`flumekit.ballscrew.buoy.lift_from_energy_balance`) with the full PTO model of this
    module.

    Parameters
    ----------
    %(wave_height)s
    %(wave_period)s
    geometry : flumekit.ballscrew.buoy.BuoyGeometry
        The buoy.
    %(screw)s
    %(lubricant)s
    %(pto)s
    n_periods : int
        Periods of motion.
    samples_per_period : int
        Samples per period.

    Returns
    -------
    xarray.Dataset
        The :func:`flumekit.ballscrew.buoy.reference_motion` dataset with attributes
        ``wave_height`` [m] and ``lift`` [m].

    %(references_senatore2022)s, Eq. (2) and Fig. 4.

    Examples
    --------
    >>> from flumekit.ballscrew.screw import sea_state_motion
    >>> round(sea_state_motion(1.5, 3.8, samples_per_period=380).attrs["lift"], 2)
    1.0
    """
    h = buoy.lift_from_energy_balance(wave_height, wave_period, geometry,
                                      pto_force_function(screw, lubricant, pto), screw.lead)
    motion = buoy.reference_motion(h, wave_period, n_periods, samples_per_period)
    motion.attrs.update(wave_height=float(wave_height), lift=h)
    return motion
