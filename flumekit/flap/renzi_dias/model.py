"""Renzi–Dias linear thin-plate model of a bottom-hinged flap in a channel or in open water.

A flap of width w, zero thickness, hinged at height c above the bed of a fluid of depth h on a
fixed foundation, pitches about the hinge under regular waves coming from +x (crests parallel to
the flap, time factor e^{-iωt}, θ positive towards -x, the direction of wave travel). Renzi &
Dias (J. Fluid Mech. 701, 2012, "RD12") solve the channel of width b; Renzi & Dias
(Eur. J. Mech. B/Fluids 41, 2013, "RD13o") the open ocean. Per vertical mode n
(:mod:`flumekit.flap.renzi_dias.eigenmodes`) the jump of potential across the plate solves a
hypersingular integral equation, expanded in (1-u²)^{1/2} U_p(u) and collocated at the zeros of
T_{P+1} (:mod:`flumekit.flap.renzi_dias.hypersingular`). Only the radiation problem is solved: the
diffraction coefficients are β_p0 = α_p0 d_0/f_0 (RD12 App. C).

Dimensional results (RD12 Eqs. 2.34–2.36 with ρ and g restored):

- added inertia μ = ρ (πw/4) Re Σ_n f_n α_0n [kg m²];
- radiation damping ν = ρ ω (πw/4) Im Σ_n f_n α_0n [N m s];
- excitation torque per metre of wave amplitude at the hinge line F = -iωρ (πw/4) d_0 α_00
  [N m m-1], referenced to the incident elevation A e^{-iωt} at x = 0;
- channel only: plane-wave reflection and transmission coefficients of the fixed flap,
  R_0 = -i (π w k / 8b) α_00/f_0, T_0 = 1 - R_0 (RD13a Eqs. 29–37, dimensional).

Here α_pn is the Chebyshev coefficient of the radiation problem per unit V = iωΘ (m^{5/2}).
"""

from __future__ import annotations

import warnings
from typing import NamedTuple

import numpy as np
import xarray as xr

from flumekit import conventions
from flumekit.errors import GeometryError
from flumekit.flap.renzi_dias import eigenmodes, hypersingular
from flumekit.hydro import coefficients as hy
from flumekit.hydro.coefficients import join_complex
from flumekit.waves.theory import G, group_velocity, wavenumber

#: Default truncation orders. With these, μ, ν and |F| are within 1e-5 (relative) of the
#: converged values for the flume (h = 0.825 m, w = 1.31 m, b = 1.5 m, c = 0.1 m) at
#: T = 2–4 s and in open water; see ``flumekit.bench.renzi_dias`` and the convergence tests.
#: ``None`` means "chosen from the geometry" (documented in :func:`coefficients`).
DEFAULT_TRUNCATION = {
    "chebyshev_terms": None,
    "evanescent_modes": 8,
    "lattice_modes": None,
    "quadrature_nodes": None,
    "lattice": "spectral",
    "images": 400,
}


#: frequency grid (ω_min [rad s-1], ω_max [rad s-1], points) of :func:`channel_container`
CONTAINER_OMEGA = (0.4, 25.0, 400)


class Solution(NamedTuple):
    """Radiation-problem solution, the input of every coefficient."""

    period: np.ndarray  # [s], shape (nT,)
    omega: np.ndarray  # [rad s-1], shape (nT,)
    modes: eigenmodes.VerticalModes
    alpha: np.ndarray  # complex, (nT, n_modes + 1, P + 1) [m^(5/2)]
    flap_width: float
    channel_width: float | None
    truncation: dict


def _check(period, depth, flap_width, hinge_height, channel_width, rho, g):
    period = np.atleast_1d(np.asarray(period, dtype=float))
    if period.ndim != 1 or period.size == 0 or np.any(~np.isfinite(period)) or np.any(period <= 0):
        raise ValueError("period must be a non-empty 1-D array of finite values > 0 s, "
                         f"got {period}")
    for name, val in (("depth", depth), ("flap_width", flap_width), ("rho", rho), ("g", g)):
        if not (np.isfinite(val) and val > 0):
            raise GeometryError(f"{name} must be finite and > 0, got {val}")
    if not (np.isfinite(hinge_height) and 0 <= hinge_height < depth):
        raise GeometryError(
            f"hinge_height must lie in [0, depth) = [0, {depth}) m, got {hinge_height}")
    if channel_width is not None and not (np.isfinite(channel_width)
                                          and channel_width > flap_width):
        raise GeometryError(
            f"channel_width must exceed flap_width = {flap_width} m (a flap spanning the channel "
            f"is the 2-D problem, see two_dimensional()), got {channel_width}")
    return period


def _truncation(width, channel_width, kappa2, options) -> dict:
    unknown = set(options) - set(DEFAULT_TRUNCATION)
    if unknown:
        raise TypeError(f"unknown truncation option(s) {sorted(unknown)}; "
                        f"valid: {sorted(DEFAULT_TRUNCATION)}")
    t = {**DEFAULT_TRUNCATION, **options}
    if t["lattice"] not in ("spectral", "direct"):
        raise ValueError(f"lattice must be 'spectral' or 'direct', got {t['lattice']!r}")
    if t["chebyshev_terms"] is None:
        if channel_width is None:
            t["chebyshev_terms"] = 12
        else:
            # the density is analytic up to the image plates' edges u = ±(2b/w - 1); Chebyshev
            # coefficients fall like ρ^{-2p} (ρ: Bernstein parameter); aim at 1e-7
            z = 2 * channel_width / width - 1
            rho = z + np.sqrt(z * z - 1)
            t["chebyshev_terms"] = int(np.clip(np.ceil(np.log(3e7) / (2 * np.log(rho))), 12, 400))
    if t["quadrature_nodes"] is None:
        t["quadrature_nodes"] = (24 if channel_width is None or t["lattice"] == "direct"
                                 else hypersingular.channel_quadrature_nodes(width, channel_width))
    if channel_width is not None and t["lattice_modes"] is None:
        # Bessel decay of the density transform (λ_Q = πQw/b ≥ 80) and |β_Q| ≥ 2 max|κ_n|
        kmax = float(np.sqrt(np.max(np.abs(kappa2))))
        t["lattice_modes"] = int(max(16, np.ceil(80 * channel_width / (np.pi * width)),
                                     np.ceil(kmax * channel_width / np.pi)))
    for key in ("chebyshev_terms", "evanescent_modes", "quadrature_nodes", "images"):
        if int(t[key]) != t[key] or t[key] < (1 if key != "evanescent_modes" else 0):
            raise ValueError(f"truncation '{key}' must be a positive integer, got {t[key]}")
    return t


def sloshing_cutoff_periods(depth: float, channel_width: float, n: int = 2,
                            g: float = G) -> np.ndarray:
    """Periods T_q [s] of the symmetric sloshing cut-offs k b = 2πq, q = 1..n (RD12 §3.2)."""
    k = 2 * np.pi * np.arange(1, n + 1) / channel_width
    return 2 * np.pi / np.sqrt(g * k * np.tanh(k * depth))


def solve(period, depth: float, flap_width: float, hinge_height: float,
          channel_width: float | None = None, g: float = G, **truncation) -> Solution:
    """Solve the radiation problem; arguments as in :func:`coefficients` (no ``rho``)."""
    period = _check(period, depth, flap_width, hinge_height, channel_width, 1.0, g)
    n_ev = truncation.get("evanescent_modes", DEFAULT_TRUNCATION["evanescent_modes"])
    if int(n_ev) != n_ev or n_ev < 0:
        raise ValueError(f"truncation 'evanescent_modes' must be an integer >= 0, got {n_ev}")
    omega = 2 * np.pi / period
    modes = eigenmodes.vertical_modes(omega, depth, hinge_height, int(n_ev), g)
    t = _truncation(flap_width, channel_width, modes.kappa2, truncation)
    n_terms = int(t["chebyshev_terms"])
    if channel_width is None:
        a = hypersingular.open_water_matrix(modes.kappa2, flap_width, n_terms,
                                            int(t["quadrature_nodes"]))
    elif t["lattice"] == "direct":
        kb = modes.wavenumber * channel_width / (2 * np.pi)
        gap = np.abs(kb - np.round(kb))
        if np.any((gap < 0.05) & (np.round(kb) >= 1)):
            warnings.warn(
                "direct image sum within 5 % of a sloshing cut-off (kb = 2πq) at T = "
                f"{period[(gap < 0.05) & (np.round(kb) >= 1)]} s: it converges very slowly there "
                "(Wood anomaly); use lattice='spectral'", RuntimeWarning, stacklevel=2)
        a = hypersingular.open_water_matrix(modes.kappa2, flap_width, n_terms,
                                            int(t["quadrature_nodes"]), channel_width,
                                            int(t["images"]))
    else:
        a = hypersingular.channel_matrix(modes.kappa2, flap_width, channel_width, n_terms,
                                         int(t["lattice_modes"]), int(t["quadrature_nodes"]))
    rhs = np.broadcast_to(modes.f[..., None], a.shape[:-1]).astype(complex)
    alpha = np.linalg.solve(a, rhs[..., None])[..., 0]
    if not np.all(np.isfinite(alpha)):
        raise FloatingPointError("Renzi-Dias collocation system is singular at T = "
                                 f"{period[~np.all(np.isfinite(alpha), axis=(1, 2))]} s")
    return Solution(period, omega, modes, alpha, float(flap_width),
                    None if channel_width is None else float(channel_width), t)


def coefficients(period, depth: float, flap_width: float, hinge_height: float,
                 channel_width: float | None = None, rho: float = 1000.0, g: float = G,
                 **truncation) -> xr.Dataset:
    """Hydrodynamic coefficients of the thin flap (RD12 in a channel, RD13o in open water).

    Parameters
    ----------
    period : Wave periods T [s], scalar or 1-D.
    depth : Water depth h [m].
    flap_width : Flap width w [m].
    hinge_height : Height c of the hinge above the bed [m]; the foundation fills the bed to it.
    channel_width : Channel width b [m] (b > w, flap centred); ``None`` for open water.
    rho : Water density [kg m-3].
    g : Gravitational acceleration [m s-2].
    **truncation : Truncation orders (defaults in :data:`DEFAULT_TRUNCATION`):

        - ``chebyshev_terms`` P + 1, Chebyshev terms and collocation points (default 12 in open
          water; in a channel the number making ρ^{-2P} < 3e-7 with ρ = z + √(z²-1),
          z = 2b/w - 1, e.g. 12 for the flume, 42 for w/b = 0.99);
        - ``evanescent_modes`` N, evanescent vertical modes (default 8; error ∝ N^{-3.5},
          2e-6 at 8);
        - ``lattice_modes`` Q, transverse modes of the Kummer-accelerated modal lattice sum
          (default max(16, 80 b/(πw), max abs(κ_n) b/π); terms fall like q^{-9/2});
        - ``quadrature_nodes``: Gauss nodes for the smooth channel kernels (default from the
          Bernstein ellipse of w/b, 1e-14) or, in open water, Gauss–Legendre nodes per side of
          each collocation point (default 24);
        - ``lattice``: ``"spectral"`` (default, the modal sum above) or ``"direct"``, the direct
          image sum of RD12 with ``images`` terms per side (default 400; error ≈ 0.5/images,
          slow near cut-offs, where it warns).

    Returns
    -------
    Dataset over ``period`` with ``added_inertia`` [kg m2], ``radiation_damping`` [N m s],
    ``excitation_torque_real``/``excitation_torque_imag`` [N m m-1] (use :func:`excitation`
    for the complex F), ``wave_number`` [rad m-1], ``angular_frequency``; in a channel also
    ``reflection_coefficient_real/imag``, ``transmission_coefficient_real/imag`` (complex R_0,
    T_0 of the fixed flap for the plane wave; use :func:`reflection`, :func:`transmission`) and
    ``propagating_transverse_modes`` (number of sloshing modes above their cut-off; above the
    first one the plane-wave abs(R_0)² + abs(T_0)² < 1, the rest goes into transverse modes).

    Raises
    ------
    GeometryError
        Non-positive lengths, hinge outside the water column, channel not wider than the flap.
    ValueError
        Bad periods or truncation orders.
    """
    _check(period, depth, flap_width, hinge_height, channel_width, rho, g)
    sol = solve(period, depth, flap_width, hinge_height, channel_width, g, **truncation)
    return dataset(sol, depth, hinge_height, rho, g)


def channel_container(depth: float, flap_width: float, hinge_height: float,
                      channel_width: float, hydrostatic_stiffness: float, *,
                      omega: tuple[float, float, int] = CONTAINER_OMEGA, rho: float = 1000.0,
                      g: float = G) -> xr.Dataset:
    """Build the coefficient container of a thin flap in a channel (RD12), with A∞.

    The one container of the flume's flap: the comparison stage's linear model and simulator
    and the virtual flume use it. :func:`coefficients` on ``omega`` = (ω_min, ω_max, n) evenly
    spaced angular frequencies [rad s-1], :func:`flumekit.hydro.coefficients.from_renzi_dias`,
    and A∞ from the Ogilvie relation (median estimate, spread reported, not checked).

    Parameters
    ----------
    depth : Water depth h [m].
    flap_width : Flap width w [m].
    hinge_height : Hinge height above the bed c [m].
    channel_width : Channel (flume) width b [m].
    hydrostatic_stiffness : C [N m rad-1].
    omega : Frequency grid.
    rho : Water density [kg m-3].
    g : Gravitational acceleration [m s-2].
    """
    w = np.linspace(*omega)
    rd = coefficients(2 * np.pi / w[::-1], depth, flap_width, hinge_height,
                      channel_width=channel_width, rho=rho, g=g)
    return hy.with_infinite_frequency_inertia(hy.from_renzi_dias(rd, hydrostatic_stiffness),
                                              max_spread=None)


def dataset(sol: Solution, depth: float, hinge_height: float, rho: float = 1000.0,
            g: float = G) -> xr.Dataset:
    """Return the coefficients dataset of a :class:`Solution` (see :func:`coefficients`)."""
    m, w, omega = sol.modes, sol.flap_width, sol.omega
    s = np.sum(m.f * sol.alpha[..., 0], axis=-1)
    mu = rho * np.pi * w / 4 * s.real  # Eq. (2.34) in RD12
    nu = rho * omega * np.pi * w / 4 * s.imag  # Eq. (2.35) in RD12
    f_exc = -1j * omega * rho * np.pi * w / 4 * m.d0 * sol.alpha[:, 0, 0]  # Eq. (2.36) in RD12
    dims = ("period",)
    data = {
        "added_inertia": (dims, mu),
        "radiation_damping": (dims, nu),
        "excitation_torque_real": (dims, f_exc.real),
        "excitation_torque_imag": (dims, f_exc.imag),
        "wave_number": (dims, m.wavenumber),
    }
    attrs = {"depth": float(depth), "flap_width": w, "hinge_height": float(hinge_height),
             "rho": float(rho), "g": float(g),
             **{f"truncation_{k}": (v if isinstance(v, str) else int(v))
                for k, v in sol.truncation.items()
                if v is not None and (sol.channel_width is not None
                                      or k not in ("lattice", "lattice_modes", "images"))}}
    if sol.channel_width is not None:
        b = sol.channel_width
        refl = -1j * np.pi * w * m.wavenumber / (8 * b) * sol.alpha[:, 0, 0] / m.f[:, 0]
        trans = 1 - refl  # RD13a: T_0 = 1 - R_0
        data.update({
            "reflection_coefficient_real": (dims, refl.real),
            "reflection_coefficient_imag": (dims, refl.imag),
            "transmission_coefficient_real": (dims, trans.real),
            "transmission_coefficient_imag": (dims, trans.imag),
            "propagating_transverse_modes": (
                dims, np.floor(m.wavenumber * b / (2 * np.pi)).astype(np.int32)),
        })
        attrs["channel_width"] = b
        title = "Renzi-Dias thin-flap coefficients in a channel (RD12)"
    else:
        title = "Renzi-Dias thin-flap coefficients in open water (RD13o)"
    ds = xr.Dataset(data, coords={"period": ("period", sol.period),
                                  "angular_frequency": ("period", omega)})
    ds.attrs.update(conventions.global_attrs(
        title, "flumekit.flap.renzi_dias.model", {k: v for k, v in attrs.items()}))
    ds.attrs.update(attrs)
    ds.attrs["geometry"] = "channel" if sol.channel_width is not None else "open water"
    return conventions.annotate(ds)


def excitation(ds: xr.Dataset) -> xr.DataArray:
    """Complex excitation torque per metre of wave amplitude F [N m m-1] from a dataset."""
    return join_complex(ds, "excitation_torque")


def reflection(ds: xr.Dataset) -> xr.DataArray:
    """Complex plane-wave reflection coefficient R_0 [-] of the fixed flap (channel datasets)."""
    return join_complex(ds, "reflection_coefficient")


def transmission(ds: xr.Dataset) -> xr.DataArray:
    """Complex plane-wave transmission coefficient T_0 [-] of the fixed flap (channel datasets)."""
    return join_complex(ds, "transmission_coefficient")


def haskind_damping(excitation_torque, period, depth: float, hinge_height: float,
                    g: float = G) -> np.ndarray:
    """Radiation damping ν [N m s] from the excitation torque by the Haskind-type relation.

    ν = tanh kh / (k C_g) [h - c + (cosh kc - cosh kh)/(k sinh kh)] Re F, Eq. (C3) in RD12
    (Eq. 47 in RD13o), with F per metre of wave amplitude [N m m-1] and the group velocity C_g.
    It follows from β_p0 = α_p0 d_0/f_0, hence holds for the thin-plate model in a channel and
    in open water alike (not for a thick flap).
    """
    omega = 2 * np.pi / np.asarray(period, dtype=float)
    modes = eigenmodes.vertical_modes(omega, depth, hinge_height, 0, g)
    k, h, c = modes.wavenumber, float(depth), float(hinge_height)
    kh = k * h
    cg = group_velocity(period, h, g)
    # (cosh kc - cosh kh) / sinh kh without overflow for kh > 710
    e = np.exp(-2 * kh)
    ratio = (np.exp(k * c - kh) * (1 + np.exp(-2 * k * c)) - (1 + e)) / -np.expm1(-2 * kh)
    bracket = h - c + ratio / k
    return np.tanh(kh) / (k * cg) * bracket * np.real(excitation_torque)


def two_dimensional_excitation(omega, depth: float, hinge_height: float, width: float,
                               rho: float = 1000.0, g: float = G) -> np.ndarray:
    """Excitation torque per unit incident amplitude of a flap spanning the channel [N m m-1].

    F_2d = 2 ρ g w [(h − c) tanh(kh)/k − (cosh kh − cosh kc)/(k² cosh kh)] (RD12 Eq. 3.1):
    twice the incident dynamic pressure ρ g cosh k(z+h)/cosh kh of a fully reflecting wall
    integrated over the wetted flap with the lever arm about the hinge. The cosh ratio is
    written as e^{k(c−h)} (1 + e^{−2kc}) / (1 + e^{−2kh}), so it does not overflow for
    kh > 710; at ω = 0 the long-wave limit ρ g w (h − c)² (RD12 Eq. 3.2).

    Parameters
    ----------
    omega : Angular frequency [rad s-1], ≥ 0.
    depth : Water depth h [m].
    hinge_height : Hinge height above the bed c [m], < h.
    width : Flap width w [m].
    rho : Water density [kg m-3].
    g : Gravitational acceleration [m s-2].
    """
    w = np.asarray(omega, dtype=float)
    d = depth - hinge_height
    out = np.full(w.shape, rho * g * width * d**2)  # Eq. (3.2) in RD12
    pos = w > 0
    k = wavenumber(w[pos], depth, g)
    kh, kc = k * depth, k * hinge_height
    ratio = np.exp(kc - kh) * (1 + np.exp(-2 * kc)) / (1 + np.exp(-2 * kh))  # cosh kc / cosh kh
    out[pos] = 2 * rho * g * width * (d * np.tanh(kh) / k - (1.0 - ratio) / k**2)  # Eq. (3.1)
    return out


def two_dimensional(period, depth: float, hinge_height: float, width: float,
                    rho: float = 1000.0, g: float = G, evanescent_modes: int = 200
                    ) -> xr.Dataset:
    """Exact coefficients of a flap spanning a channel of width ``width`` (the 2-D problem).

    Eigenfunction solution on both sides of the plate (x ≷ 0: ϕ_n = ∓ V f_n e^{±iκ_n x}/(iκ_n)):
    μ_2d = 2ρ w Σ_{n≥1} f_n²/k_n, ν_2d = 2ρ w ω f_0²/k, and the excitation torque of the fully
    reflecting wall, F_2d = 2ρ g w [(h-c) tanh kh / k + (cosh kc - cosh kh)/(k² cosh kh)]
    (RD12 Eq. 3.1), whose long-wave limit is ρ g w (h-c)² (RD12 Eq. 3.2). The thin-plate channel
    model tends to these as w/b → 1 (slowly, like 1/ln(1/(1 - w/b))).
    """
    period = np.atleast_1d(np.asarray(period, dtype=float))
    omega = 2 * np.pi / period
    m = eigenmodes.vertical_modes(omega, depth, hinge_height, evanescent_modes, g)
    k, h, c = m.wavenumber, float(depth), float(hinge_height)
    kn = np.sqrt(-m.kappa2[:, 1:])
    mu = 2 * rho * width * np.sum(m.f[:, 1:] ** 2 / kn, axis=-1)
    nu = 2 * rho * width * omega * m.f[:, 0] ** 2 / k
    f2d = two_dimensional_excitation(omega, h, c, width, rho, g)
    ds = xr.Dataset(
        {"added_inertia": ("period", mu), "radiation_damping": ("period", nu),
         "excitation_torque_real": ("period", f2d),
         "excitation_torque_imag": ("period", np.zeros_like(f2d)),
         "wave_number": ("period", k)},
        coords={"period": period, "angular_frequency": ("period", omega)})
    ds.attrs.update(conventions.global_attrs(
        "2-D flap (full channel width): eigenfunction solution", "flumekit.flap.renzi_dias.model",
        {"depth": depth, "hinge_height": hinge_height, "width": width}))
    return conventions.annotate(ds)
