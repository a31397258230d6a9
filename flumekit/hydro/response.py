"""Frequency-domain response of the flap to regular waves: rotation, power and capture factor.

Appendix A of Brito et al. (2020, "Brito") with the coefficients of
:func:`flumekit.flap.renzi_dias.model.coefficients` (or a BEM dataset of the same layout):

- Θ = F A / [-ω²(I + μ + I_pto) + C + C_pto - iω(ν + ν_pto)]: Eq. (A1) in Brito, RD12 Eq. (2.33)
  (I_pto, C_pto = 0 in both papers);
- mean power P = ½ ν_pto ω² |Θ|²: RD12 Eq. (2.37). Brito writes ⟨W_out⟩ = ν_PTO ⟨θ̇⟩², the time
  mean of ν_pto θ̇², which is the same thing; Brito's "θ̇ = iωθ" is a sign slip for e^{-iωt}
  (θ̇ = -iωΘ), irrelevant to |Θ| and P;
- optimal PTO damping ν_opt = √((C + C_pto - (I + μ + I_pto)ω²)²/ω² + ν²): RD12 Eq. (2.40);
- capture factor, two normalisations:

  * ``capture_factor`` (Brito §3.2 and App. A, **identical** to RD12 Eq. 2.41):
    C_f = P / W_I with W_I = (1/8) ρ g H² C_g w, the incident energy flux across the **flap**
    width w (Brito Eq. A2; RD12 writes ½ ρ g A² C_g w, the same with H = 2A). In a channel it
    is bounded by b/(2w) (RD13a), 0.573 for the flume;
  * ``capture_factor_channel``: P over the incident flux across the **channel** width b, the
    fraction of the incident power absorbed, bounded by ½ below the first sloshing cut-off.

The phase convention is that of the models: η = Re(A e^{-iωt}) at the hinge line (x = 0), so
θ(t) = |Θ| cos(ωt - arg Θ) and θ peaks arg Θ/ω after the crest passes the hinge line.

%(references_brito2020)s.
%(renzi_dias2012)s (RD12).
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from flumekit import conventions
from flumekit.docstrings import doc, fill
from flumekit.hydro.coefficients import join_complex
from flumekit.waves.theory import energy_flux

__doc__ = fill(__doc__)


def _omega(coefficients: xr.Dataset) -> xr.DataArray:
    return 2 * np.pi / coefficients["period"]


def _nonnegative(name: str, value) -> None:
    arr = np.asarray(value, dtype=float)
    if np.any(~np.isfinite(arr)) or np.any(arr < 0):
        raise ValueError(f"{name} must be finite and >= 0, got {value}")


@doc
def optimal_pto_damping(coefficients: xr.Dataset, inertia: float, stiffness: float,
                        pto_stiffness: float = 0.0, pto_inertia: float = 0.0) -> xr.DataArray:
    """Compute the PTO damping that maximises the mean power at each period.

    ν_opt = √((C + C_pto − (I + μ + I_pto)ω²)²/ω² + ν²), RD12 Eq. (2.40).

    Parameters
    ----------
    coefficients : xarray.Dataset
        ``added_inertia`` μ [kg m2] and ``radiation_damping`` ν [N m s] over ``period`` [s].
    inertia : float
        Moment of inertia of the flap about the hinge I [kg m2], ≥ 0.
    stiffness : float
        Net buoyancy (hydrostatic) stiffness C [N m rad-1].
    pto_stiffness : float, optional
        PTO stiffness C_pto [N m rad-1].
    pto_inertia : float, optional
        PTO inertia I_pto [kg m2].

    Returns
    -------
    xarray.DataArray
        ``optimal_pto_damping`` ν_opt [N m s] over ``period``.

    Raises
    ------
    ValueError
        ``inertia`` negative or not finite.

    %(references_renzi_dias2012)s.

    Examples
    --------
    At resonance (C = (I + μ)ω²) the optimum equals the radiation damping:

    >>> import numpy as np, xarray as xr
    >>> from flumekit.hydro.response import optimal_pto_damping
    >>> coef = xr.Dataset({"added_inertia": ("period", [5.0]),
    ...                    "radiation_damping": ("period", [3.0])}, coords={"period": [2.0]})
    >>> float(optimal_pto_damping(coef, 10.0, 15.0 * np.pi**2)[0])
    3.0
    """
    _nonnegative("inertia", inertia)
    omega = _omega(coefficients)
    reactance = stiffness + pto_stiffness - (inertia + pto_inertia
                                             + coefficients["added_inertia"]) * omega**2
    # Eq. (2.40) in RD12
    out = np.sqrt((reactance / omega) ** 2 + coefficients["radiation_damping"] ** 2)
    out.name = "optimal_pto_damping"
    out.attrs = {}
    return conventions.annotate(out)


@doc
def response(coefficients: xr.Dataset, wave_amplitude, inertia: float, stiffness: float,
             pto_damping, pto_stiffness: float = 0.0, pto_inertia: float = 0.0,
             channel_width: float | None = None) -> xr.Dataset:
    """Compute the linear flap response to regular waves (Brito Eq. A1) and its power.

    Parameters
    ----------
    coefficients : xarray.Dataset
        Dataset over ``period`` [s] with ``added_inertia`` [kg m2], ``radiation_damping``
        [N m s], ``excitation_torque_real``/``_imag`` [N m m-1] and the attributes ``depth``
        [m], ``flap_width`` [m], ``rho`` [kg m-3], ``g`` [m s-2] (as made by
        :func:`flumekit.flap.renzi_dias.model.coefficients` or :mod:`flumekit.flap.bem`).
    wave_amplitude : float or xarray.DataArray
        Incident wave amplitude A = H/2 [m], ≥ 0; a DataArray (e.g. over ``wave_height``) is
        broadcast against ``period``.
    inertia : float
        Moment of inertia I of the flap about the hinge [kg m2] (14.74 in Brito §2.2).
    stiffness : float
        Net buoyancy stiffness C [N m rad-1] (605 in Brito App. A).
    pto_damping : float or xarray.DataArray
        Linear PTO damping ν_pto [N m s], ≥ 0 (e.g. the result of
        :func:`optimal_pto_damping`).
    pto_stiffness : float, optional
        PTO stiffness [N m rad-1].
    pto_inertia : float, optional
        PTO inertia [kg m2].
    channel_width : float, optional
        Channel width b [m] for ``capture_factor_channel``; default: the dataset's
        ``channel_width`` attribute if any (otherwise that variable is omitted).

    Returns
    -------
    xarray.Dataset
        ``theta_real``, ``theta_imag``, ``theta_amplitude``, ``theta_phase`` [rad],
        ``mean_power`` [W], ``incident_power`` W_I [W], ``capture_factor`` [-] (flap-width
        normalisation, Brito = RD12), ``capture_factor_channel`` [-] (channel-width
        normalisation), ``torque_amplitude`` [N m] (amplitude of the wave torque
        F A + (ω²μ + iων)Θ on the moving flap, hydrostatics excluded) and ``pto_damping``
        [N m s].

    Raises
    ------
    ValueError
        A negative or non-finite amplitude, PTO damping or inertia, or a missing attribute.

    %(references_brito2020)s, Appendix A.
    %(renzi_dias2012)s.
    """
    _nonnegative("wave_amplitude", wave_amplitude)
    _nonnegative("pto_damping", pto_damping)
    _nonnegative("inertia", inertia)
    for key in ("depth", "flap_width", "rho", "g"):
        if key not in coefficients.attrs:
            raise ValueError(f"coefficients dataset lacks the attribute '{key}'")
    a = coefficients.attrs
    omega = _omega(coefficients)
    mu, nu = coefficients["added_inertia"], coefficients["radiation_damping"]
    force = join_complex(coefficients, "excitation_torque") * wave_amplitude
    nu_pto = xr.DataArray(pto_damping) if np.ndim(pto_damping) == 0 else pto_damping
    # Eq. (A1) in Brito et al. 2020; RD12 Eq. (2.33)
    denom = (-omega**2 * (inertia + pto_inertia + mu) + stiffness + pto_stiffness
             - 1j * omega * (nu + nu_pto))
    theta = force / denom
    power = 0.5 * nu_pto * omega**2 * np.abs(theta) ** 2  # Eq. (2.37) in RD12
    flux = xr.apply_ufunc(lambda amp, period: energy_flux(2 * amp, period, a["depth"],
                                                          a["rho"], a["g"]),
                          xr.DataArray(wave_amplitude) if np.ndim(wave_amplitude) == 0
                          else wave_amplitude, coefficients["period"])
    w_i = flux * a["flap_width"]  # Eq. (A2) in Brito et al. 2020
    with np.errstate(invalid="ignore", divide="ignore"):
        cf = xr.where(w_i > 0, power / w_i, 0.0)
    torque = force + (omega**2 * mu + 1j * omega * nu) * theta
    out = xr.Dataset({
        "theta_real": np.real(theta), "theta_imag": np.imag(theta),
        "theta_amplitude": np.abs(theta),
        "theta_phase": xr.apply_ufunc(np.angle, theta),
        "mean_power": power, "incident_power": w_i, "capture_factor": cf,
        "torque_amplitude": np.abs(torque),
        "pto_damping": nu_pto * xr.ones_like(omega),
    })
    b = channel_width if channel_width is not None else a.get("channel_width")
    if b is not None:
        with np.errstate(invalid="ignore", divide="ignore"):
            out["capture_factor_channel"] = xr.where(flux > 0, power / (flux * float(b)), 0.0)
    for name in out.data_vars:
        out[name].attrs = {}
    out["mean_power"].attrs["long_name"] = "mean PTO power of the linear model, RD12 Eq. (2.37)"
    out["capture_factor"].attrs["long_name"] = (
        "capture factor P / W_I, W_I across the flap width (Brito Eq. A2 = RD12 Eq. 2.41)")
    out["torque_amplitude"].attrs["long_name"] = (
        "amplitude of the wave (excitation + radiation) torque on the moving flap")
    out.attrs.update(conventions.global_attrs(
        "Linear flap response (Brito et al. 2020 App. A)", "flumekit.hydro.response",
        {"inertia": inertia, "stiffness": stiffness, "pto_stiffness": pto_stiffness,
         "pto_inertia": pto_inertia, "coefficients": a.get("title", "")}))
    out.attrs.update({"inertia": float(inertia), "stiffness": float(stiffness),
                      "pto_stiffness": float(pto_stiffness), "pto_inertia": float(pto_inertia)})
    return conventions.annotate(out)
