"""Six-degree-of-freedom BEM results of one rigid body, and their rotation about a hinge.

BEM codes (Capytaine, WAMIT, NEMOH) and WEC-Sim store a rigid body's coefficients for its six
rigid modes about one *reference point* r₀ of the body (Capytaine's ``rotation_center``,
WAMIT's body origin): translations of r₀ (surge, sway, heave) and rotations about axes through
r₀ (roll, pitch, yaw). A flap, though, turns about its hinge. This module holds the six-dof
result as data (:func:`rigid_body_dataset`, written by :mod:`flumekit.hydro.capytaine` and
:mod:`flumekit.hydro.wamit`) and reduces it to the one-dof container of
:mod:`flumekit.hydro.coefficients` for a rotation about a given axis (:func:`about_hinge`).

Rotation about a hinge (Newman 1977, §7.1; Falnes 2002, §5.7 for generalised modes)
---------------------------------------------------------------------------------
A rotation θ about the axis through the point H with unit direction u moves the body point P
by θ u × (P − H) to first order. The body's motion is therefore the six-vector of modes

    ξ = T θ,   T = [u × d ; u],   d = r₀ − H,

(translation of r₀, then rotation). For the OSWEC (u = +y, r₀ five metres above the hinge,
d = (0, 0, 5) m): T = (5, 0, 0, 0, 1, 0), i.e. *pitch about the hinge = pitch about r₀ plus
5 m × surge*. The generalised coefficients of the mode (virtual work of the six-dof loads on
the mode shape) are

    A_h(ω) = Tᵀ A(ω) T,   B_h(ω) = Tᵀ B(ω) T,   F_h(ω) = Tᵀ F(ω),

which for the OSWEC reads A_h = A₅₅ + 5 (A₁₅ + A₅₁) + 25 A₁₁ (the coupled terms included) and
F_h = F₅ + 5 F₁, the moment about the hinge.

Hydrostatic stiffness. The linear restoring matrix C about r₀ is not a tensor: it is the
Hessian of the potential energy of gravity and buoyancy, and a finite rotation about the hinge
also moves r₀ by the second-order displacement ½ θ² u × (u × d). With the body out of static
balance (a hinged flap is held by its hinge: net static force F_s = (ρ g V − m g) e_z ≠ 0) that
displacement does work, so

    C_h = Tᵀ C T + F_s · d − (F_s · u)(u · d).

For u = +y and d vertical this is C_h = C₅₅ + |d| (ρ g V − m g) (+ the surge terms, zero
here), the familiar ρ g V (z_B − z_H) − m g (z_G − z_H) + ρ g I_wp of a bottom-hinged flap.
C about r₀ must be the *whole* restoring matrix (buoyancy and the body's true weight); when r₀
is the centre of gravity, as in WEC-Sim's files, the weight adds nothing to the rotational
terms about r₀ and a buoyancy-only matrix (Capytaine's) is complete.

Checks: the result goes through :func:`flumekit.hydro.coefficients.hydro_dataset` (finite
values, C > 0) and :func:`~flumekit.hydro.coefficients.check_passive` unless a passivity fix is
asked for explicitly (``passivity="clip"``).

Failed frequencies: BEM runs that fail at some frequencies (Capytaine's finite-depth Green
function below kh ≈ 0.15, irregular frequencies, ...) store NaN there. :func:`drop_failed`
removes every frequency where any coefficient is not finite, with a warning naming them.

References
----------
Newman, J. N. (1977). Marine Hydrodynamics. MIT Press.
Falnes, J. (2002). Ocean Waves and Oscillating Systems. Cambridge University Press.
"""

from __future__ import annotations

import warnings

import numpy as np
import xarray as xr

from flumekit import conventions
from flumekit.docstrings import filler
from flumekit.hydro.coefficients import (
    DIM,
    FailedFrequencyWarning,
    HydroError,
    check_passive,
    hydro_dataset,
    make_passive,
)

#: docstring text that several functions of this module share
_doc = filler(
    ds=("ds : xarray.Dataset\n"
        "    Six-dof dataset of :func:`rigid_body_dataset`."),
    hinge_point=("hinge_point : sequence of float\n"
                 "    A point H (x, y, z) [m] on the hinge axis."))

DOFS = ("Surge", "Sway", "Heave", "Roll", "Pitch", "Yaw")


def rigid_body_dataset(angular_frequency, added_mass, radiation_damping, excitation_force,
                       hydrostatic_stiffness, *, reference_point=None, rho: float = 1000.0,
                       g: float = 9.81, water_depth: float = np.inf, wave_direction: float = 0.0,
                       added_mass_infinite=None, source: str = "") -> xr.Dataset:
    """Build the dataset of six-dof coefficients of one rigid body about a reference point.

    Parameters
    ----------
    angular_frequency : array_like
        ω [rad s-1], shape (n,), > 0 (NaN coefficients allowed: see :func:`drop_failed`).
    added_mass : array_like
        A(ω) [kg, kg m, kg m2], shape (n, 6, 6), indexed (radiating, influenced).
    radiation_damping : array_like
        B(ω) [N s m-1 ... N m s], shape (n, 6, 6).
    excitation_force : array_like of complex
        F(ω) per unit incident amplitude [N m-1, N m m-1], shape (n, 6), time factor
        e^{-iωt}, referenced to the incident wave at the origin of the BEM frame.
    hydrostatic_stiffness : array_like
        C [N m-1 ... N m rad-1], shape (6, 6), about the reference point.
    reference_point : sequence of float, optional
        (x, y, z) [m] about which the rotations are taken, or None if unknown.
    rho : float, optional
        Water density of the BEM run [kg m-3].
    g : float, optional
        Gravitational acceleration of the BEM run [m s-2].
    water_depth : float, optional
        Water depth of the BEM run [m] (``inf`` for deep water).
    wave_direction : float, optional
        Incident wave direction of ``excitation_force`` [rad] (0: towards +x).
    added_mass_infinite : array_like, optional
        A∞ [kg, kg m, kg m2], shape (6, 6), if the BEM run has it.
    source : str, optional
        Where the data come from (kept in ``attrs``).

    Returns
    -------
    xarray.Dataset
        ``added_mass``, ``radiation_damping``, ``excitation_force`` over ascending
        ``angular_frequency`` and the dofs (Surge ... Yaw), ``hydrostatic_stiffness``; the run's
        constants in ``attrs``.

    Raises
    ------
    HydroError
        An array of the wrong shape, frequencies not finite or not positive, or a non-finite
        stiffness matrix.

    Examples
    --------
    A sphere of radius 1 m deep below the surface, about its centre: added mass ½ ρ V in each
    translation, as in unbounded fluid, and none in rotation; frequencies in any order:

    >>> import numpy as np
    >>> from flumekit.hydro.rigid_body import rigid_body_dataset
    >>> a = np.diag([1.0, 1.0, 1.0, 0.0, 0.0, 0.0]) * 1000.0 * 2 / 3 * np.pi  # ½ ρ (4/3 π R³)
    >>> sphere = rigid_body_dataset([2.0, 1.0], [a, a], np.zeros((2, 6, 6)), np.zeros((2, 6)),
    ...                             np.zeros((6, 6)), reference_point=(0.0, 0.0, -10.0))
    >>> sphere["added_mass"].dims, sphere["angular_frequency"].values.tolist()
    (('angular_frequency', 'radiating_dof', 'influenced_dof'), [1.0, 2.0])
    >>> heave = sphere["added_mass"].sel(radiating_dof="Heave", influenced_dof="Heave")
    >>> np.round(heave.values, 1).tolist(), sphere.attrs["reference_point"]
    ([2094.4, 2094.4], [0.0, 0.0, -10.0])
    """
    w = np.asarray(angular_frequency, dtype=float).ravel()
    a = np.asarray(added_mass, dtype=float)
    b = np.asarray(radiation_damping, dtype=float)
    f = np.asarray(excitation_force, dtype=complex)
    c = np.asarray(hydrostatic_stiffness, dtype=float)
    n = w.size
    for name, arr, shape in (("added_mass", a, (n, 6, 6)), ("radiation_damping", b, (n, 6, 6)),
                             ("excitation_force", f, (n, 6)), ("hydrostatic_stiffness", c, (6, 6))):
        if arr.shape != shape:
            raise HydroError(f"{name} has shape {arr.shape}, expected {shape}")
    if not np.all(np.isfinite(w)) or np.any(w <= 0):
        raise HydroError("angular frequencies must be finite and > 0")
    if not np.all(np.isfinite(c)):
        raise HydroError("the hydrostatic stiffness matrix has non-finite entries")
    order = np.argsort(w)
    rad, inf = ("radiating_dof", "influenced_dof")
    ds = xr.Dataset(
        {"added_mass": ((DIM, rad, inf), a[order]),
         "radiation_damping": ((DIM, rad, inf), b[order]),
         "excitation_force": ((DIM, inf), f[order]),
         "hydrostatic_stiffness": ((inf, rad), c)},
        coords={DIM: w[order], rad: list(DOFS), inf: list(DOFS)})
    if added_mass_infinite is not None:
        ds["added_mass_infinite"] = ((rad, inf), np.asarray(added_mass_infinite, dtype=float))
    ds.attrs.update(source=source, rho=float(rho), g=float(g), water_depth=float(water_depth),
                    wave_direction=float(wave_direction), time_convention="exp(-i omega t)")
    if reference_point is not None:
        ds.attrs["reference_point"] = [float(v) for v in reference_point]
    return ds


@_doc
def failed_frequencies(ds: xr.Dataset) -> np.ndarray:
    """Return the angular frequencies [rad s-1] at which any coefficient is not finite.

    A frequency fails where the added mass, the radiation damping or the excitation force
    holds a non-finite value in any mode: a BEM solver writes NaN where it did not converge.

    Parameters
    ----------
    %(ds)s

    Returns
    -------
    numpy.ndarray
        The failed frequencies [rad s-1], ascending (empty if none).
    """
    bad = np.zeros(ds.sizes[DIM], dtype=bool)
    for name in ("added_mass", "radiation_damping", "excitation_force"):
        v = ds[name].values
        bad |= ~np.isfinite(v).reshape(v.shape[0], -1).all(axis=1)
    return ds[DIM].values[bad]


@_doc
def drop_failed(ds: xr.Dataset, failed: str = "drop") -> xr.Dataset:
    """Remove the frequencies with non-finite coefficients, or raise naming them.

    Parameters
    ----------
    %(ds)s
    failed : {"drop", "raise"}, optional
        Drop them with a :class:`~flumekit.hydro.coefficients.FailedFrequencyWarning` naming
        them (their list kept in ``attrs["dropped_frequencies"]`` [rad s-1]), or raise.

    Returns
    -------
    xarray.Dataset
        ``ds`` without the failed frequencies (``ds`` itself if none failed).

    Raises
    ------
    HydroError
        Failed frequencies with ``failed="raise"``, or every frequency failed.
    ValueError
        ``failed`` is neither "drop" nor "raise".
    """
    bad = failed_frequencies(ds)
    if bad.size == 0:
        return ds
    listed = ", ".join(f"{w:.4g}" for w in bad[:12]) + (" ..." if bad.size > 12 else "")
    if failed == "raise":
        raise HydroError(f"the BEM result has non-finite coefficients at {bad.size} frequencies "
                         f"(omega = {listed} rad/s); pass failed='drop' to leave them out")
    if failed != "drop":
        raise ValueError(f"failed must be 'drop' or 'raise', got {failed!r}")
    if bad.size == ds.sizes[DIM]:
        raise HydroError("the BEM result has non-finite coefficients at every frequency")
    warnings.warn(f"dropped {bad.size} BEM frequencies with non-finite coefficients: "
                  f"omega = {listed} rad/s", FailedFrequencyWarning, stacklevel=2)
    out = ds.sel({DIM: ~np.isin(ds[DIM].values, bad)})
    out.attrs["dropped_frequencies"] = [float(w) for w in bad]
    return out


@_doc
def hinge_mode(reference_point, hinge_point, axis=(0.0, 1.0, 0.0)) -> np.ndarray:
    """Return the mode shape T = [u × d ; u] (d = r₀ − H) of a rotation about a hinge.

    Parameters
    ----------
    reference_point : sequence of float
        Reference point r₀ (x, y, z) [m] of the six-dof result.
    %(hinge_point)s
    axis : sequence of float, optional
        Hinge direction u (normalised here) [-].

    Returns
    -------
    numpy.ndarray
        T, shape (6,): translation of r₀ per unit rotation [m rad-1], then the rotation
        axis [-].

    Raises
    ------
    HydroError
        A zero or malformed axis, or points that are not 3-vectors.

    References
    ----------
    Newman, J. N. (1977). Marine Hydrodynamics. MIT Press, §7.1.

    Examples
    --------
    The OSWEC of the module notes, r₀ five metres above the hinge:

    >>> from flumekit.hydro.rigid_body import hinge_mode
    >>> hinge_mode((0.0, 0.0, 5.0), (0.0, 0.0, 0.0)).tolist()
    [5.0, 0.0, 0.0, 0.0, 1.0, 0.0]
    """
    u = np.asarray(axis, dtype=float)
    if u.shape != (3,) or not np.linalg.norm(u) > 0:
        raise HydroError(f"the hinge axis must be a non-zero 3-vector, got {axis}")
    u = u / np.linalg.norm(u)
    d = np.asarray(reference_point, dtype=float) - np.asarray(hinge_point, dtype=float)
    if d.shape != (3,):
        raise HydroError("reference_point and hinge_point must be (x, y, z) [m]")
    return np.concatenate([np.cross(u, d), u])


@_doc
def inertia_about_hinge(mass: float, inertia_cog: float, centre_of_gravity, hinge_point,
                        axis=(0.0, 1.0, 0.0)) -> float:
    """Compute the moment of inertia about the hinge axis, I_h = I_G + m r².

    The parallel-axis theorem, r the distance of the centre of gravity from the hinge axis,
    ‖u × (r_G − H)‖.

    Parameters
    ----------
    mass : float
        Body mass m [kg].
    inertia_cog : float
        I_G about the parallel axis through the centre of gravity [kg m2].
    centre_of_gravity : sequence of float
        r_G (x, y, z) [m].
    %(hinge_point)s
    axis : sequence of float, optional
        Hinge direction u [-].

    Returns
    -------
    float
        I_h [kg m2].

    Examples
    --------
    >>> from flumekit.hydro.rigid_body import inertia_about_hinge
    >>> inertia_about_hinge(2.0, 1.0, (0.0, 0.0, 3.0), (0.0, 0.0, 0.0))
    19.0
    """
    u = np.asarray(axis, dtype=float) / np.linalg.norm(axis)
    r = np.cross(u, np.asarray(centre_of_gravity, float) - np.asarray(hinge_point, float))
    return float(inertia_cog + mass * r @ r)


def about_hinge(ds: xr.Dataset, hinge_point, axis=(0.0, 1.0, 0.0), *, mass: float | None = None,
                displaced_volume: float | None = None, reference_point=None,
                hydrostatic_stiffness: float | None = None, passivity: str = "raise",
                failed: str = "drop") -> xr.Dataset:
    """Reduce a six-dof result to the one-dof container of a rotation about a hinge axis.

    A_h = Tᵀ A T, B_h = Tᵀ B T, F_h = Tᵀ F and C_h = Tᵀ C T + F_s · d − (F_s · u)(u · d)
    with the mode shape T of :func:`hinge_mode` (module notes).

    Parameters
    ----------
    ds : xarray.Dataset
        Six-dof dataset of :func:`rigid_body_dataset` (Capytaine or WAMIT reader).
    hinge_point : sequence of float
        A point (x, y, z) on the hinge axis [m], in the BEM frame.
    axis : sequence of float, optional
        Hinge direction u [-]; +y turns the top of a flap towards +x for positive θ.
    mass : float, optional
        Body mass m [kg] (the real one: WEC-Sim's OSWEC flap is 127 000 kg, not the ρV of
        Capytaine's default inertia matrix).
    displaced_volume : float, optional
        Displaced volume V at rest [m3].
    reference_point : sequence of float, optional
        r₀ [m]; default the dataset's ``reference_point`` attribute.
    hydrostatic_stiffness : float, optional
        C_h about the hinge [N m rad-1] if known otherwise; replaces the transformed value
        (then ``mass`` and ``displaced_volume`` are not needed).
    passivity : {"raise", "clip"}, optional
        :func:`~flumekit.hydro.coefficients.check_passive`, or
        :func:`~flumekit.hydro.coefficients.make_passive` (recorded in ``attrs``).
    failed : {"drop", "raise"}, optional
        What to do with non-finite frequencies (:func:`drop_failed`).

    Returns
    -------
    xarray.Dataset
        The container of :mod:`flumekit.hydro.coefficients` (A_h [kg m2], B_h [N m s], F_h
        [N m m-1], C_h [N m rad-1]; A∞ of the mode [kg m2] when the dataset has it), with
        ``attrs`` naming the transformation.

    Raises
    ------
    HydroError
        No reference point, no way to compute C_h, C_h ≤ 0 (statically unstable), negative
        damping with ``passivity="raise"``, or failed frequencies with ``failed="raise"``.
    ValueError
        An unknown ``passivity``.

    References
    ----------
    Newman, J. N. (1977). Marine Hydrodynamics. MIT Press, §7.1.
    Falnes, J. (2002). Ocean Waves and Oscillating Systems. Cambridge University Press, §5.7.

    Examples
    --------
    A flap whose reference point r₀ lies 5 m above the hinge, with a surge force of 10 N m-1
    and a pitch moment of 3 N m m-1 about r₀: about the hinge the moment is 3 + (r₀ − H) × F
    = 3 + 5 × 10, and the surge added mass counts with the lever squared.

    >>> import numpy as np
    >>> from flumekit.hydro.rigid_body import about_hinge, rigid_body_dataset
    >>> a = np.zeros((2, 6, 6))
    >>> a[:, 0, 0], a[:, 4, 4] = 100.0, 20.0  # surge [kg], pitch [kg m2]
    >>> f = np.zeros((2, 6), dtype=complex)
    >>> f[:, 0], f[:, 4] = 10.0, 3.0  # surge force, pitch moment
    >>> body = rigid_body_dataset([1.0, 2.0], a, 0.1 * a, f, np.zeros((6, 6)),
    ...                           reference_point=(0.0, 0.0, 5.0))
    >>> flap = about_hinge(body, (0.0, 0.0, 0.0), mass=500.0, displaced_volume=1.0)
    >>> flap["excitation_torque"].values.real.tolist()  # M + r × F
    [53.0, 53.0]
    >>> flap["added_inertia"].values.tolist()  # A₅₅ + 5² A₁₁
    [2520.0, 2520.0]
    >>> float(flap["hydrostatic_stiffness"])  # 5 m × (ρ g V − m g), C about r₀ zero here
    24525.0
    """
    r0 = reference_point if reference_point is not None else ds.attrs.get("reference_point")
    if r0 is None:
        raise HydroError("the BEM result does not say about which point its rotations are "
                         "taken: pass reference_point=(x, y, z) (Capytaine's rotation_center, "
                         "WAMIT's body origin)")
    ds = drop_failed(ds, failed)
    t = hinge_mode(r0, hinge_point, axis)
    a = np.einsum("i,nij,j->n", t, ds["added_mass"].values, t)
    b = np.einsum("i,nij,j->n", t, ds["radiation_damping"].values, t)
    f = ds["excitation_force"].values @ t
    if hydrostatic_stiffness is None:
        if mass is None or displaced_volume is None:
            raise HydroError("the stiffness about the hinge needs mass= and displaced_volume= "
                             "(net static force rho g V - m g), or hydrostatic_stiffness=")
        u = t[3:]
        d = np.asarray(r0, float) - np.asarray(hinge_point, float)
        fs = np.array([0.0, 0.0, ds.attrs["rho"] * ds.attrs["g"] * displaced_volume
                       - mass * ds.attrs["g"]])
        c = float(t @ ds["hydrostatic_stiffness"].values @ t + fs @ d - (fs @ u) * (u @ d))
        how = (f"C_h = T^T C T + F_s.d - (F_s.u)(u.d), F_s = rho g V - m g = {fs[2]:.6g} N "
               f"(V = {displaced_volume} m3, m = {mass} kg)")
    else:
        c = float(hydrostatic_stiffness)
        how = "C_h given"
    if not c > 0:
        raise HydroError(f"the hydrostatic stiffness about the hinge is {c:.6g} N m/rad (<= 0): "
                         "the body is statically unstable about this axis; check mass, "
                         "displaced_volume and the hinge point, or add a restoring spring")
    out = hydro_dataset(ds[DIM].values, a, b, f, c,
                        source=f"{ds.attrs.get('source', '')}; rotation about the hinge "
                               f"{list(map(float, hinge_point))} m, axis {list(map(float, axis))}")
    if passivity == "clip":
        out = make_passive(out)
    elif passivity == "raise":
        check_passive(out)
    else:
        raise ValueError(f"passivity must be 'raise' or 'clip', got {passivity!r}")
    if "added_mass_infinite" in ds:
        out["added_inertia_infinite"] = float(t @ ds["added_mass_infinite"].values @ t)
    out.attrs.update(hinge_mode=t.tolist(), hinge_stiffness=how,
                     reference_point=[float(v) for v in r0],
                     dropped_frequencies=ds.attrs.get("dropped_frequencies", []),
                     **{k: ds.attrs[k] for k in ("rho", "g", "water_depth", "wave_direction")})
    return conventions.annotate(out)
