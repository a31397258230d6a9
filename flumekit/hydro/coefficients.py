"""Hydrodynamic coefficients of one rotational degree of freedom about a hinge, as data.

One container, an ``xr.Dataset`` over ``angular_frequency`` [rad s-1] (ascending, > 0):

* ``added_inertia`` A(ω) [kg m2] and ``radiation_damping`` B(ω) [N m s];
* ``excitation_torque`` F(ω) [N m m-1], complex, per unit amplitude of the incident wave at the
  hinge line x = 0 (in memory; :func:`split_complex` / :func:`merge_complex` give the
  ``excitation_torque_real`` / ``excitation_torque_imag`` pair for netCDF);
* ``hydrostatic_stiffness`` C [N m rad-1] (scalar);
* optionally ``added_inertia_infinite`` A∞ [kg m2] (scalar) once checked.

Conventions. Complex amplitudes use the time factor e^{-iωt}, as Renzi & Dias (2012) and
Capytaine do: θ(t) = Re{Θ e^{-iωt}}, η(x=0, t) = Re{a e^{-iωt}}, T_exc = Re{F a e^{-iωt}}, so
that (Eq. A1 in Brito et al. 2020)

    Θ = F a / [−ω²(I + A) + C − iω(B + ν_pto)].

Brito et al. (2020, App. A) write θ̇ = iωθ, which belongs to the opposite time factor; with
e^{-iωt} the physically correct derivative is θ̇ = −iωΘ. θ is positive when the top of the
flap moves towards the beach (+x), the direction the incident waves travel.

Checks before use: finite values and C > 0 (:func:`hydro_dataset`, always),
passivity (B ≥ 0, :func:`check_passive`, explicit fix
:func:`make_passive`) and the infinite-frequency inertia from the Ogilvie (1964) relation at
every frequency with its spread (:func:`infinite_frequency_inertia`).

%(references_brito2020)s, Appendix A.
%(renzi_dias2012)s.
%(ogilvie1964)s.
"""

from __future__ import annotations

import warnings

import numpy as np
import xarray as xr

from flumekit import conventions
from flumekit.docstrings import doc, fill
from flumekit.errors import FlumekitError

__doc__ = fill(__doc__)

DIM = "angular_frequency"


class HydroError(FlumekitError, ValueError):
    """Hydrodynamic coefficients that cannot be used as they are (with a report of why)."""


class FailedFrequencyWarning(UserWarning):
    """BEM frequencies with non-finite coefficients were dropped."""


def hydro_dataset(angular_frequency, added_inertia, radiation_damping, excitation_torque,
                  hydrostatic_stiffness: float, *, source: str = "") -> xr.Dataset:
    """Build the coefficient container (sorted by frequency, checked for shape and finiteness).

    Parameters
    ----------
    angular_frequency : array_like
        Angular frequencies ω [rad s-1], > 0, distinct, at least two.
    added_inertia : array_like
        Added inertia A(ω) [kg m2], one value per frequency.
    radiation_damping : array_like
        Radiation damping B(ω) [N m s], one value per frequency.
    excitation_torque : array_like of complex
        Excitation torque F(ω) [N m m-1] per unit incident amplitude at x = 0 (time factor
        e^{-iωt}), one value per frequency.
    hydrostatic_stiffness : float
        Net hydrostatic (gravity + buoyancy) stiffness C [N m rad-1], > 0.
    source : str, optional
        Where the coefficients come from (kept in ``attrs``).

    Returns
    -------
    xarray.Dataset
        ``added_inertia`` [kg m2], ``radiation_damping`` [N m s] and ``excitation_torque``
        [N m m-1] over ascending ``angular_frequency`` [rad s-1], and the scalar
        ``hydrostatic_stiffness`` [N m rad-1].

    Raises
    ------
    HydroError
        Fewer than two frequencies, frequencies not finite, not positive or not distinct, a
        coefficient of the wrong length or not finite, or C not finite or ≤ 0.

    Examples
    --------
    >>> from flumekit.hydro.coefficients import hydro_dataset
    >>> ds = hydro_dataset([2.0, 1.0], [50.0, 60.0], [10.0, 5.0], [30 + 1j, 20 + 2j], 400.0)
    >>> ds["added_inertia"].values.tolist()
    [60.0, 50.0]
    """
    w = np.asarray(angular_frequency, dtype=float).ravel()
    arrays = {"added_inertia": np.asarray(added_inertia, dtype=float).ravel(),
              "radiation_damping": np.asarray(radiation_damping, dtype=float).ravel(),
              "excitation_torque": np.asarray(excitation_torque, dtype=complex).ravel()}
    if w.size < 2:
        raise HydroError("hydrodynamic coefficients need at least two frequencies")
    if not np.all(np.isfinite(w)) or np.any(w <= 0):
        raise HydroError("angular frequencies must be finite and > 0")
    for name, a in arrays.items():
        if a.shape != w.shape:
            raise HydroError(f"{name} has {a.size} values for {w.size} frequencies")
        if not np.all(np.isfinite(a)):
            bad = w[~np.isfinite(a)]
            raise HydroError(f"{name} is not finite at omega = {np.round(bad, 4).tolist()} rad/s")
    if not np.isfinite(hydrostatic_stiffness):
        raise HydroError(f"hydrostatic stiffness must be finite, got {hydrostatic_stiffness}")
    if not hydrostatic_stiffness > 0:
        raise HydroError(
            f"hydrostatic stiffness {hydrostatic_stiffness:.6g} N m/rad <= 0: the body has no "
            "static equilibrium about this axis. A rigid-body BEM result taken about its centre "
            "of gravity must be transformed to the hinge first "
            "(flumekit.hydro.rigid_body.about_hinge); a statically unstable body needs its "
            "restoring spring included in C")
    order = np.argsort(w)
    if np.any(np.diff(w[order]) <= 0):
        raise HydroError("angular frequencies are not distinct")
    ds = xr.Dataset({k: (DIM, v[order]) for k, v in arrays.items()},
                    coords={DIM: w[order]})
    ds["hydrostatic_stiffness"] = float(hydrostatic_stiffness)
    ds.attrs["source"] = source
    ds.attrs["time_convention"] = "exp(-i omega t)"
    return conventions.annotate(ds)


@doc
def kernel_response(omega, amplitude, decay_rate, frequency) -> np.ndarray:
    """Compute the Fourier transform of a radiation kernel that is a sum of damped cosines.

    K̂(ω) = ∫₀^∞ K(t) e^{iωt} dt of K(t) = Σ a_j e^{−α_j t} cos(β_j t); each term gives
    a_j (α_j − iω)/((α_j − iω)² + β_j²) (time factor e^{-iωt}).

    Parameters
    ----------
    omega : array_like
        Angular frequencies ω [rad s-1].
    amplitude : array_like
        Term amplitudes a_j [N m].
    decay_rate : array_like
        Decay rates α_j [s-1], > 0.
    frequency : array_like
        Oscillation frequencies β_j [rad s-1], ≥ 0 (broadcast against ``amplitude`` and
        ``decay_rate``).

    Returns
    -------
    numpy.ndarray of complex
        K̂(ω) [N m s], shape of ``omega``: B(ω) = Re K̂ and A(ω) − A∞ = −Im K̂ / ω.

    %(references_ogilvie1964)s.

    Examples
    --------
    >>> from flumekit.hydro.coefficients import kernel_response
    >>> kernel_response([0.0], 2.0, 4.0, 0.0)  # a/α at ω = 0
    array([0.5+0.j])
    """
    w = np.asarray(omega, dtype=float)[..., None]
    a, al, be = (np.atleast_1d(np.asarray(v, dtype=float)) for v in
                 (amplitude, decay_rate, frequency))
    z = al - 1j * w
    return np.sum(a * z / (z * z + be * be), axis=-1)


@doc
def from_kernel(angular_frequency, amplitude, decay_rate, frequency, *,
                added_inertia_infinite: float, excitation_torque,
                hydrostatic_stiffness: float) -> xr.Dataset:
    """Exactly causal coefficients of a body whose radiation kernel is a sum of damped cosines.

    K(t) = Σ a_j e^{−α_j t} cos(β_j t) gives (Ogilvie 1964) B(ω) = Re K̂(ω) and
    A(ω) = A∞ − Im K̂(ω)/ω with K̂ of :func:`kernel_response`: a Kramers-Kronig pair with a
    known impulse response and a finite-order state-space model, used as the truth in tests
    and benchmarks. The caller chooses the terms so that B ≥ 0 (checked by
    :func:`check_passive`).

    Parameters
    ----------
    angular_frequency : array_like
        Angular frequencies ω [rad s-1], > 0.
    amplitude, decay_rate, frequency : array_like
        Kernel terms a_j [N m], α_j [s-1] and β_j [rad s-1] (see :func:`kernel_response`).
    added_inertia_infinite : float
        Infinite-frequency added inertia A∞ [kg m2] (stored as ``added_inertia_infinite``).
    excitation_torque : array_like of complex
        F(ω) [N m m-1] per unit incident amplitude at x = 0.
    hydrostatic_stiffness : float
        C [N m rad-1], > 0.

    Returns
    -------
    xarray.Dataset
        The container of :func:`hydro_dataset` with ``added_inertia_infinite`` [kg m2] and
        the kernel's terms in ``attrs["kernel"]``.

    Raises
    ------
    HydroError
        As :func:`hydro_dataset`.

    %(references_ogilvie1964)s.

    Examples
    --------
    >>> from flumekit.hydro.coefficients import from_kernel
    >>> ds = from_kernel([1.0, 2.0], 2.0, 4.0, 0.0, added_inertia_infinite=10.0,
    ...                  excitation_torque=[1.0, 1.0], hydrostatic_stiffness=100.0)
    >>> round(float(ds["radiation_damping"][0]), 4)  # a α / (α² + ω²)
    0.4706
    """
    w = np.asarray(angular_frequency, dtype=float)
    kh = kernel_response(w, amplitude, decay_rate, frequency)
    ds = hydro_dataset(w, added_inertia_infinite - kh.imag / w, kh.real, excitation_torque,
                       hydrostatic_stiffness, source="analytic damped-cosine radiation kernel")
    ds["added_inertia_infinite"] = float(added_inertia_infinite)
    ds.attrs["kernel"] = str({"amplitude": np.atleast_1d(amplitude).tolist(),
                              "decay_rate": np.atleast_1d(decay_rate).tolist(),
                              "frequency": np.atleast_1d(frequency).tolist()})
    return conventions.annotate(ds)


def split_complex(hydro: xr.Dataset) -> xr.Dataset:
    """Replace every complex variable X by ``X_real`` and ``X_imag`` (for netCDF).

    Parameters
    ----------
    hydro : xarray.Dataset
        Dataset with complex variables (e.g. the container of :func:`hydro_dataset`).

    Returns
    -------
    xarray.Dataset
        The same dataset with each complex variable replaced by its real and imaginary parts
        (same units, long name suffixed with "(real part)" / "(imag part)").

    Examples
    --------
    netCDF has no complex type; the excitation torque F = 20 + 2i N m m-1 at ω = 1 rad/s
    becomes two real variables:

    >>> from flumekit.hydro.coefficients import hydro_dataset, split_complex
    >>> hydro = hydro_dataset([1.0, 2.0], [60.0, 50.0], [5.0, 10.0], [20 + 2j, 30 + 1j], 400.0)
    >>> flat = split_complex(hydro)
    >>> sorted(name for name in flat.data_vars if name.startswith("excitation"))
    ['excitation_torque_imag', 'excitation_torque_real']
    >>> flat["excitation_torque_imag"].values.tolist(), flat["excitation_torque_imag"].units
    ([2.0, 1.0], 'N m m-1')
    """
    out = hydro.copy()
    for name in [n for n in hydro.data_vars if hydro[n].dtype.kind == "c"]:
        da = out[name]
        out = out.drop_vars(name)
        for part, values in (("real", da.real), ("imag", da.imag)):
            out[f"{name}_{part}"] = values.assign_attrs(
                {**da.attrs, "long_name": f"{da.attrs.get('long_name', name)} ({part} part)"})
    return conventions.annotate(out)


_PARTS = (("_real", "_imag"), ("_re", "_im"))


def join_complex(ds: xr.Dataset, name: str) -> xr.DataArray:
    """Join the complex variable ``name`` of ``ds`` from its real and imaginary parts.

    The parts are ``name_real``/``name_imag`` (as :func:`split_complex` writes them) or
    ``name_re``/``name_im``.

    Parameters
    ----------
    ds : xarray.Dataset
        Dataset holding the two parts.
    name : str
        Name of the complex variable, without suffix.

    Returns
    -------
    xarray.DataArray
        The complex variable (units of its parts); it keeps the real part's attributes, its
        long name without the "real part of the " prefix or " (real part)" suffix.

    Raises
    ------
    KeyError
        Neither pair of parts is in ``ds``.
    """
    for re_s, im_s in _PARTS:
        if name + re_s in ds and name + im_s in ds:
            re = ds[name + re_s]
            out = re + 1j * ds[name + im_s]
            out.name = name
            long_name = str(re.attrs.get("long_name", name))
            long_name = long_name.replace("real part of the ", "").replace(" (real part)", "")
            out.attrs = {**re.attrs, "long_name": long_name}
            return out
    raise KeyError(f"no real and imaginary parts of '{name}' among {sorted(ds.data_vars)}")


def merge_complex(ds: xr.Dataset) -> xr.Dataset:
    """Join every ``X_real``/``X_imag`` (or ``_re``/``_im``) pair into a complex ``X``.

    The inverse of :func:`split_complex`.

    Parameters
    ----------
    ds : xarray.Dataset
        Dataset with split complex variables.

    Returns
    -------
    xarray.Dataset
        The dataset with each pair replaced by one complex variable.

    Examples
    --------
    A round trip through :func:`split_complex` gives back the container, values and
    attributes alike:

    >>> from flumekit.hydro.coefficients import hydro_dataset, merge_complex, split_complex
    >>> hydro = hydro_dataset([0.5, 1.5], [80.0, 70.0], [2.0, 6.0], [10 - 1j, 15 + 3j], 300.0)
    >>> merge_complex(split_complex(hydro)).identical(hydro)
    True

    Parts named ``_re``/``_im`` are joined too:

    >>> import xarray as xr
    >>> complex(merge_complex(xr.Dataset({"f_re": 3.0, "f_im": -4.0}))["f"])
    (3-4j)
    """
    out = ds.copy()
    for name in list(ds.data_vars):
        for re_s, im_s in _PARTS:
            if name.endswith(re_s) and name[: -len(re_s)] + im_s in ds:
                base = name[: -len(re_s)]
                joined = join_complex(ds, base)
                out = out.drop_vars([name, base + im_s])
                # the registry's long name of the complex variable, where it has one
                out[base] = joined.assign_attrs(
                    {k: v for k, v in joined.attrs.items() if k != "long_name"})
    return conventions.annotate(out)


def _excitation_from(ds: xr.Dataset, names: tuple[str, ...]) -> xr.DataArray:
    merged = merge_complex(ds)
    for name in names:
        if name in merged:
            return merged[name]
    raise HydroError(f"no excitation torque among the variables {sorted(ds.data_vars)}; "
                     f"expected one of {list(names)} (complex, or _real/_imag parts)")


@doc
def from_renzi_dias(coefficients: xr.Dataset, hydrostatic_stiffness: float) -> xr.Dataset:
    """Build the container from the Renzi-Dias model's coefficients (over ``period``).

    Parameters
    ----------
    coefficients : xarray.Dataset
        Output of :func:`flumekit.flap.renzi_dias.model.coefficients`: over ``period`` [s]
        (or ``angular_frequency`` [rad s-1]) with ``added_inertia`` [kg m2],
        ``radiation_damping`` [N m s] and the excitation torque per unit amplitude [N m m-1],
        complex or as real/imaginary parts (``excitation_torque_real``/``_imag``), time factor
        e^{-iωt}.
    hydrostatic_stiffness : float
        C [N m rad-1] (the campaign's ``flap.buoyancy_stiffness``).

    Returns
    -------
    xarray.Dataset
        The container of :func:`hydro_dataset`.

    Raises
    ------
    HydroError
        No ``period`` or ``angular_frequency`` dimension, no excitation torque, or values that
        :func:`hydro_dataset` rejects.

    %(references_renzi_dias2012)s.

    Examples
    --------
    Coefficients over the wave period T, the excitation as real and imaginary parts, become
    the container over ω = 2π/T, ascending:

    >>> import numpy as np
    >>> import xarray as xr
    >>> from flumekit.hydro.coefficients import from_renzi_dias
    >>> model = xr.Dataset({"added_inertia": ("period", [50.0, 60.0]),
    ...                     "radiation_damping": ("period", [10.0, 5.0]),
    ...                     "excitation_torque_real": ("period", [30.0, 20.0]),
    ...                     "excitation_torque_imag": ("period", [1.0, 2.0])},
    ...                    coords={"period": [np.pi, 2 * np.pi]})
    >>> hydro = from_renzi_dias(model, hydrostatic_stiffness=400.0)
    >>> hydro["angular_frequency"].values.tolist()  # 2π / T
    [1.0, 2.0]
    >>> hydro["added_inertia"].values.tolist(), hydro["excitation_torque"].values.tolist()
    ([60.0, 50.0], [(20+2j), (30+1j)])
    """
    dim = "period" if "period" in coefficients.dims else DIM
    if dim not in coefficients.dims:
        raise HydroError("Renzi-Dias coefficients need a 'period' or 'angular_frequency' dim")
    x = coefficients[dim].values.astype(float)
    omega = 2 * np.pi / x if dim == "period" else x
    exc = _excitation_from(coefficients, ("excitation_torque", "excitation"))
    return hydro_dataset(omega, coefficients["added_inertia"].values,
                         coefficients["radiation_damping"].values, exc.values,
                         hydrostatic_stiffness,
                         source=coefficients.attrs.get("source", "Renzi & Dias (2012)"))


@doc
def from_capytaine(bem: xr.Dataset, dof: str | None = None, wave_direction: float = 0.0,
                   hydrostatic_stiffness: float | None = None,
                   failed: str = "drop") -> xr.Dataset:
    """Build the container from a Capytaine result (``cpt.assemble_dataset`` or its netCDF).

    The degree of freedom must be a rotation about the hinge axis, e.g.
    ``body.add_rotation_dof(rotation_center=(0, 0, z_hinge), direction=(0, 1, 0))``: with waves
    travelling towards +x (``wave_direction = 0``) a positive rotation about +y moves the top of
    the flap towards +x, which is flumekit's positive θ. Capytaine references the excitation to
    the incident elevation at its origin, so the hinge line must lie at x = 0 of the mesh.

    Parameters
    ----------
    bem : xarray.Dataset
        Capytaine dataset: ``added_mass``, ``radiation_damping`` over (frequency,
        ``influenced_dof``, ``radiating_dof``) and ``excitation_force`` or
        ``diffraction_force`` + ``Froude_Krylov_force`` over (frequency, ``wave_direction``,
        ``influenced_dof``); complex values either complex or split along a ``complex`` dim
        ("re", "im") as ``cpt.io.xarray.separate_complex_values`` writes them. The frequency
        dim may be ``omega`` or another of Capytaine's (then ``omega`` must be a coordinate).
        ω = 0 and ω = ∞ entries are dropped from the frequency axis; the ω = ∞ added inertia is
        kept as ``added_inertia_infinite``.
    dof : str, optional
        Name of the rotation dof; by default the only radiating dof.
    wave_direction : float, optional
        Incident wave direction [rad], 0 for waves towards +x.
    hydrostatic_stiffness : float, optional
        C [N m rad-1]; by default the dataset's ``hydrostatic_stiffness`` (which must then be
        about the hinge and include the flap's weight).
    failed : {"drop", "raise"}, optional
        Frequencies where the BEM run failed (non-finite values): dropped (with a
        :class:`FailedFrequencyWarning` naming them) or an error.

    Returns
    -------
    xarray.Dataset
        The container of :func:`hydro_dataset`, with ``added_inertia_infinite`` [kg m2] when
        the result holds ω = ∞.

    Raises
    ------
    HydroError
        No frequency dimension, no radiation or excitation results, an ambiguous or unknown
        ``dof``, failed frequencies with ``failed="raise"``, or no hydrostatic stiffness.

    See Also
    --------
    flumekit.hydro.capytaine.read_capytaine, flumekit.hydro.rigid_body.about_hinge :
        For a six-dof rigid body (rotations about a body point, as WEC-Sim's files).

    %(references_ancellin_dias2019)s.

    Examples
    --------
    A run with one rotation dof, its excitation as diffraction plus Froude-Krylov parts and an
    ω = ∞ radiation problem (no diffraction there, hence NaN):

    >>> import numpy as np
    >>> import xarray as xr
    >>> from flumekit.hydro.coefficients import from_capytaine
    >>> rad, exc = ("omega", "radiating_dof", "influenced_dof"), ("omega", "wave_direction",
    ...                                                           "influenced_dof")
    >>> bem = xr.Dataset({"added_mass": (rad, [[[60.0]], [[50.0]], [[40.0]]]),
    ...                   "radiation_damping": (rad, [[[5.0]], [[10.0]], [[0.0]]]),
    ...                   "diffraction_force": (exc, [[[15 + 2j]], [[20 + 1j]], [[np.nan]]]),
    ...                   "Froude_Krylov_force": (exc, [[[5.0]], [[10.0]], [[np.nan]]])},
    ...                  coords={"omega": [1.0, 2.0, np.inf], "radiating_dof": ["Flap"],
    ...                          "influenced_dof": ["Flap"], "wave_direction": [0.0]})
    >>> hydro = from_capytaine(bem, hydrostatic_stiffness=400.0)
    >>> hydro["excitation_torque"].values.tolist()  # diffraction + Froude-Krylov
    [(20+2j), (30+1j)]
    >>> float(hydro["added_inertia_infinite"])  # the ω = ∞ row
    40.0
    """
    from flumekit.hydro.bem_layout import (
        excitation_of,
        frequency_dim,
        merge_complex_dim,
        select_direction,
    )

    ds = merge_complex_dim(bem)
    try:
        fdim = frequency_dim(ds)
    except ValueError as e:
        raise HydroError(f"the Capytaine dataset: {e}") from None
    for name in ("added_mass", "radiation_damping"):
        if name not in ds:
            raise HydroError(f"the Capytaine dataset has no '{name}' (radiation problems)")
    dofs = [str(d) for d in ds["radiating_dof"].values]
    if dof is None:
        if len(dofs) != 1:
            raise HydroError(f"several radiating dofs {dofs}: name the hinge rotation with dof=")
        dof = dofs[0]
    if dof not in dofs:
        raise HydroError(f"dof '{dof}' is not among the radiating dofs {dofs}")

    def pick(da):
        sel = {}
        for d in ("radiating_dof", "influenced_dof"):
            if d in da.dims:
                sel[d] = da[d].values[[str(v) for v in da[d].values].index(dof)]
        try:
            da = select_direction(da.sel(sel), wave_direction)
        except ValueError as e:
            raise HydroError(str(e)) from None
        extra = [d for d in da.dims if d != fdim]
        if extra:
            if any(da.sizes[d] != 1 for d in extra):
                raise HydroError(f"'{da.name}' varies along {extra}: select one value first")
            da = da.squeeze(extra, drop=True)
        return da

    try:
        exc = pick(excitation_of(ds))
    except ValueError as e:
        raise HydroError(str(e)) from None
    a, b = pick(ds["added_mass"]), pick(ds["radiation_damping"])
    omega = np.asarray(ds["omega"].values, dtype=float).ravel()
    if omega.size != ds.sizes[fdim]:
        raise HydroError("the 'omega' coordinate does not run along the frequency dimension")
    finite = np.isfinite(omega) & (omega > 0)
    bad = finite & ~(np.isfinite(a.values) & np.isfinite(b.values) & np.isfinite(exc.values))
    if bad.any():
        listed = ", ".join(f"{w:.4g}" for w in omega[bad])
        if failed == "raise":
            raise HydroError(f"the Capytaine result is not finite at omega = {listed} rad/s "
                             "(failed BEM frequencies); pass failed='drop' to leave them out")
        warnings.warn(f"dropped {int(bad.sum())} BEM frequencies with non-finite coefficients:"
                      f" omega = {listed} rad/s", FailedFrequencyWarning, stacklevel=2)
        finite &= ~bad
    a_inf = None
    if np.any(np.isinf(omega)):
        a_inf = float(np.real(a.values[np.isinf(omega)][0]))
    if hydrostatic_stiffness is None:
        if "hydrostatic_stiffness" not in ds:
            raise HydroError("no hydrostatic_stiffness in the Capytaine dataset: pass "
                             "hydrostatic_stiffness= (the campaign's flap.buoyancy_stiffness)")
        hydrostatic_stiffness = float(np.real(pick(ds["hydrostatic_stiffness"]).values))
    out = hydro_dataset(omega[finite], np.real(a.values[finite]), np.real(b.values[finite]),
                        exc.values[finite], hydrostatic_stiffness,
                        source=f"Capytaine {bem.attrs.get('capytaine_version', '')}, dof "
                               f"'{dof}', wave direction {wave_direction} rad".replace("  ", " "))
    if a_inf is not None:
        out["added_inertia_infinite"] = a_inf
    return conventions.annotate(out)


# --- checks -------------------------------------------------------------------------------

@doc
def passivity_report(hydro: xr.Dataset, rtol: float = 1e-6) -> xr.Dataset:
    """List the frequencies where the radiation damping is negative (below −rtol·max B).

    A passive body cannot give energy to the waves on average, so B(ω) ≥ 0; negative values come
    from irregular frequencies or under-resolved meshes in BEM results, or from interpolation.

    Parameters
    ----------
    %(hydro)s
    rtol : float, optional
        Tolerance [-] relative to the largest damping below which B counts as negative.

    Returns
    -------
    xarray.Dataset
        ``radiation_damping`` [N m s] over the offending ``angular_frequency`` values
        [rad s-1]; ``attrs``: ``n_negative``, ``min_damping`` [N m s], ``max_damping``
        [N m s].

    Examples
    --------
    >>> from flumekit.hydro.coefficients import hydro_dataset, passivity_report
    >>> ds = hydro_dataset([1.0, 2.0, 3.0], [5.0, 5.0, 5.0], [1.0, -0.5, 2.0], [1, 1, 1], 10.0)
    >>> passivity_report(ds).attrs["n_negative"]
    1
    """
    b = hydro["radiation_damping"]
    bmax = float(b.max())
    bad = b < -rtol * max(bmax, 0.0) if bmax > 0 else b < 0
    rep = b.where(bad, drop=True).to_dataset()
    rep.attrs.update(n_negative=int(bad.sum()), min_damping=float(b.min()), max_damping=bmax)
    return rep


@doc
def check_passive(hydro: xr.Dataset, rtol: float = 1e-6) -> None:
    """Raise :class:`HydroError` listing the frequencies where B(ω) < −rtol·max B.

    The fix is explicit: :func:`make_passive` (clip to zero, recorded in ``attrs``) or better
    coefficients (finer mesh, irregular-frequency removal).

    Parameters
    ----------
    %(hydro)s
    rtol : float, optional
        Tolerance [-] relative to the largest damping (see :func:`passivity_report`).

    Raises
    ------
    HydroError
        The damping is negative at one or more frequencies (the first eight are listed).
    """
    rep = passivity_report(hydro, rtol)
    n = rep.attrs["n_negative"]
    if n:
        pairs = ", ".join(f"{w:.3f} rad/s: {v:.4g} N m s" for w, v in
                          zip(rep[DIM].values[:8], rep["radiation_damping"].values[:8]))
        more = f" (and {n - 8} more)" if n > 8 else ""
        raise HydroError(
            f"radiation damping is negative at {n} of {hydro.sizes[DIM]} frequencies: "
            f"{pairs}{more}; minimum {rep.attrs['min_damping']:.4g} N m s against a maximum "
            f"{rep.attrs['max_damping']:.4g} N m s. A passive body has B >= 0; use "
            "flumekit.hydro.coefficients.make_passive(hydro) to clip it to zero, or better "
            "coefficients.")


@doc
def make_passive(hydro: xr.Dataset) -> xr.Dataset:
    """Clip negative radiation damping to zero, recorded in ``attrs["passivity_fix"]``.

    Parameters
    ----------
    %(hydro)s

    Returns
    -------
    xarray.Dataset
        A copy with B(ω) [N m s] ≥ 0.

    Examples
    --------
    >>> from flumekit.hydro.coefficients import hydro_dataset, make_passive
    >>> ds = hydro_dataset([1.0, 2.0], [5.0, 5.0], [1.0, -0.5], [1, 1], 10.0)
    >>> make_passive(ds)["radiation_damping"].values.tolist()
    [1.0, 0.0]
    """
    b = hydro["radiation_damping"]
    neg = b < 0
    out = hydro.copy()
    out["radiation_damping"] = b.where(~neg, 0.0).assign_attrs(b.attrs)
    out.attrs["passivity_fix"] = (f"radiation damping clipped to 0 at {int(neg.sum())} "
                                  f"frequencies (minimum was {float(b.min()):.4g} N m s)")
    return out


@doc
def infinite_frequency_inertia(hydro: xr.Dataset, *, duration: float | None = None,
                               dt: float | None = None, **irf_options) -> xr.Dataset:
    """Estimate the infinite-frequency added inertia by the Ogilvie (1964) relation.

        A∞ = A(ω) + (1/ω) ∫₀^∞ K(t) sin(ωt) dt        Ogilvie (1964), Eq. (A.5)-type relation

    with K(t) the radiation impulse response of :func:`flumekit.hydro.radiation.impulse_response`
    (same options). For coefficients that obey the Kramers-Kronig relations and a well-resolved
    K(t) the estimate is the same at every frequency; its spread measures how far they are from
    that (truncated frequency range, a thin-plate model, interpolation, a constant added inertia
    paired with frequency-dependent damping, ...).

    The sine transform is evaluated exactly for piecewise-linear K between its samples.

    Parameters
    ----------
    %(hydro)s
    duration : float, optional
        Length of K(t) [s] (default of :func:`flumekit.hydro.radiation.impulse_response`).
    dt : float, optional
        Time step of K(t) [s] (default of :func:`flumekit.hydro.radiation.impulse_response`).
    **irf_options
        Further options of :func:`flumekit.hydro.radiation.impulse_response`.

    Returns
    -------
    xarray.Dataset
        ``added_inertia_infinite_estimate`` over ``angular_frequency`` [kg m2] and the scalar
        ``added_inertia_infinite`` (median of the estimates) [kg m2]; ``attrs``: ``spread`` =
        (90th − 10th percentile)/abs(median) of the estimates [-] (robust to the lowest
        frequencies, where the 1/ω factor amplifies the error of the low-frequency extension of
        B), ``full_spread`` = (max − min)/abs(median) [-], ``rms_spread`` = std/abs(median)
        [-].

    %(references_ogilvie1964)s.

    Examples
    --------
    Coefficients of a damped-cosine kernel built with A∞ = 10 kg m2 (:func:`from_kernel`,
    exactly causal): every frequency gives back A∞ from A(ω) and B(ω) alone.

    >>> import numpy as np
    >>> from flumekit.hydro.coefficients import from_kernel, infinite_frequency_inertia
    >>> w = np.linspace(0.2, 20.0, 100)
    >>> hydro = from_kernel(w, 50.0, 1.0, 3.0, added_inertia_infinite=10.0,
    ...                     excitation_torque=np.ones(w.size), hydrostatic_stiffness=100.0)
    >>> est = infinite_frequency_inertia(hydro)
    >>> round(float(est["added_inertia_infinite"]), 3), est.attrs["spread"] < 0.001
    (10.0, True)
    """
    from flumekit.hydro.radiation import impulse_response, sine_transform

    irf = impulse_response(hydro, duration=duration, dt=dt, **irf_options)
    w = hydro[DIM].values
    est = hydro["added_inertia"].values + sine_transform(irf, w) / w
    med = float(np.median(est))
    scale = abs(med) if med != 0 else 1.0
    out = xr.Dataset({"added_inertia_infinite_estimate": (DIM, est),
                      "added_inertia_infinite": med}, coords={DIM: w})
    p10, p90 = np.percentile(est, [10, 90])
    out.attrs.update(spread=float((p90 - p10) / scale),
                     full_spread=float((est.max() - est.min()) / scale),
                     rms_spread=float(est.std() / scale),
                     method="Ogilvie (1964): A_inf = A(w) + (1/w) int_0^inf K(t) sin(wt) dt, "
                            "median over frequencies")
    return conventions.annotate(out)


@doc
def with_infinite_frequency_inertia(hydro: xr.Dataset, *, max_spread: float | None = 0.05,
                                    at_frequency: float | None = None,
                                    **irf_options) -> xr.Dataset:
    """Set ``added_inertia_infinite`` from the Ogilvie relation, after checks.

    Parameters
    ----------
    hydro : xarray.Dataset
        Coefficient container (passivity is checked first).
    max_spread : float or None, optional
        Largest accepted robust spread [-] (``spread`` of :func:`infinite_frequency_inertia`)
        of the per-frequency estimates. ``None`` skips the check.
    at_frequency : float, optional
        Instead of the median, take the estimate at this angular frequency [rad s-1]
        (interpolated): the time-domain model then reproduces A and B exactly at that
        frequency even if the coefficients are not causal (e.g. a constant added inertia),
        which is what a regular-wave comparison needs. The spread is still reported and
        checked against ``max_spread``: for such coefficients pass ``max_spread=None`` too.
    **irf_options
        Passed to :func:`flumekit.hydro.radiation.impulse_response`.

    Returns
    -------
    xarray.Dataset
        A copy of ``hydro`` with ``added_inertia_infinite`` [kg m2], the per-frequency
        ``added_inertia_infinite_estimate`` [kg m2] and the spread and method in ``attrs``.

    Raises
    ------
    HydroError
        The damping is negative somewhere, the spread exceeds ``max_spread``, or
        ``at_frequency`` lies outside the coefficients' range.

    %(references_ogilvie1964)s.

    Examples
    --------
    A constant added inertia with frequency-dependent damping is not causal: the Ogilvie
    estimates disagree and the check refuses them.

    >>> import numpy as np
    >>> from flumekit.hydro.coefficients import hydro_dataset, with_infinite_frequency_inertia
    >>> w = np.linspace(0.5, 10.0, 39)  # every 0.25 rad/s
    >>> hydro = hydro_dataset(w, np.full(w.size, 50.0), 100.0 * w * np.exp(-w),
    ...                       np.ones(w.size), 400.0)
    >>> with_infinite_frequency_inertia(hydro)
    Traceback (most recent call last):
    ...
    flumekit.hydro.coefficients.HydroError: the Ogilvie estimates ... spread by 17.0% ...

    Matched at the frequency of a regular-wave test instead, the memory of the time-domain
    model gives back A(2 rad/s) = 50 kg m2 there (A∞ − S(ω)/ω, Ogilvie):

    >>> from flumekit.hydro.radiation import impulse_response, sine_transform
    >>> matched = with_infinite_frequency_inertia(hydro, max_spread=None, at_frequency=2.0)
    >>> a_inf = float(matched["added_inertia_infinite"])
    >>> round(a_inf, 1), round(a_inf - float(sine_transform(impulse_response(hydro), 2.0)) / 2, 6)
    (60.8, 50.0)
    """
    check_passive(hydro)
    est = infinite_frequency_inertia(hydro, **irf_options)
    spread = est.attrs["spread"]
    if max_spread is not None and spread > max_spread:
        e = est["added_inertia_infinite_estimate"]
        raise HydroError(
            f"the Ogilvie estimates of the infinite-frequency added inertia spread by "
            f"{spread:.1%} between their 10th and 90th percentiles (all from "
            f"{float(e.min()):.4g} to {float(e.max()):.4g} kg m2, median "
            f"{float(est['added_inertia_infinite']):.4g}) over the frequencies, more than "
            f"{max_spread:.1%}: the added inertia and damping are not consistent (Kramers-Kronig), "
            "or the frequency range is too short. Widen the range, check the data, or pass "
            "max_spread=None to accept the median (max_spread=None with at_frequency= to "
            "match one frequency instead).")
    if at_frequency is not None:
        w = hydro[DIM].values
        if not w[0] <= at_frequency <= w[-1]:
            raise HydroError(f"at_frequency {at_frequency} rad/s is outside the coefficients' "
                             f"range [{w[0]:.4g}, {w[-1]:.4g}] rad/s")
        value = float(np.interp(at_frequency, w, est["added_inertia_infinite_estimate"].values))
    else:
        value = float(est["added_inertia_infinite"])
    out = hydro.copy()
    out["added_inertia_infinite"] = value
    out["added_inertia_infinite_estimate"] = est["added_inertia_infinite_estimate"]
    where = f"at omega = {at_frequency:.4g} rad/s" if at_frequency is not None else "median"
    out.attrs.update(added_inertia_infinite_spread=spread,
                     added_inertia_infinite_method=f"Ogilvie (1964), {where}")
    return conventions.annotate(out)
