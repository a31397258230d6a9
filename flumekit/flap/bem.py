"""Boundary-element coefficients of a thick bottom-hinged flap with Capytaine (optional ``[bem]``).

The flap is a rectangular box of width w (along y) and thickness t (along x), from the hinge at
height c above the bed up to (and piercing) the free surface, standing on a fixed foundation of
the same width and thickness that fills the water column below the hinge. The only degree of
freedom is the rotation about the hinge axis (x = 0, z = -h + c, along +y), applied to the flap
panels only (the foundation panels do not move). The results go into the dataset layout of
:func:`flumekit.flap.renzi_dias.model.coefficients` so that the response and comparison code takes
either; the caller caches them as netCDF (:func:`flumekit.io.netcdf.write_dataset`).

Conventions: Capytaine uses e^{-iωt} and waves travelling towards +x for ``wave_direction = 0``;
with the pitch positive about +y the top of the flap moves towards +x, the direction of wave
travel, which is the Renzi–Dias θ (their waves travel towards -x and θ is positive towards -x).
The incident elevation is A e^{-iωt} at x = 0, the hinge line, in both. Open water only.

Meshing: uniform panels with a node row at the hinge; the xOz symmetry halves the BEM cost.
Panels graded towards the side edges would have a high aspect ratio, which converges worse.
Measured convergence for a 0.02 m thick flap (h = 0.825 m, w = 1.31 m, c = 0.1 m, T = 2–4 s):
first order in the panel size d; at d = 0.07 m (464 panels) the errors against the
extrapolated values are 0.6–2.9 % (μ), 1.6–3.8 % (|F|), 2.6–7.3 % (ν), and :func:`richardson`
of d = 0.1 and 0.07 m removes most of them. Thin walls need d ≲ t for full accuracy.

References
----------
Ancellin, M. & Dias, F. (2019). Capytaine: a Python-based linear potential flow solver.
J. Open Source Software 4(36), 1341.
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from flumekit import conventions
from flumekit.docstrings import doc
from flumekit.errors import GeometryError
from flumekit.waves.theory import G, wavenumber


def available() -> bool:
    """Tell whether Capytaine can be imported.

    Returns
    -------
    bool
        True when ``import capytaine`` succeeds.
    """
    try:
        import capytaine  # noqa: F401
    except ImportError:
        return False
    return True


def _grid_faces(n_a: int, n_b: int, offset: int) -> np.ndarray:
    """Quadrilaterals of a structured (n_a + 1) × (n_b + 1) node grid, vertices a-major."""
    i, j = np.meshgrid(np.arange(n_a), np.arange(n_b), indexing="ij")
    v0 = offset + i * (n_b + 1) + j
    return np.stack([v0, v0 + 1, v0 + 1 + (n_b + 1), v0 + (n_b + 1)], axis=-1).reshape(-1, 4)


@doc
def flap_mesh(depth: float, flap_width: float, hinge_height: float, thickness: float,
              panel_size: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Build the half (y ≤ 0) panel mesh of the flap and its foundation.

    The faces are the wetted front (x = -t/2), back (x = +t/2) and side (y = -w/2) walls from
    the bed to z = 0, with outward normals; no panel on the bed or the free surface.

    Parameters
    ----------
    %(depth)s
    %(flap_width)s
    hinge_height : float
        Hinge height c above the bed [m], 0 ≤ c < h.
    thickness : float
        Flap (and foundation) thickness t [m].
    panel_size : float
        Target panel size [m] (in z, and the mean size in y).

    Returns
    -------
    vertices : numpy.ndarray
        Node coordinates, shape (n, 3) [m].
    faces : numpy.ndarray
        Vertex indices of the quadrilaterals, shape (m, 4).
    moving : numpy.ndarray of bool
        Shape (m,), True on flap panels (above the hinge).

    Raises
    ------
    flumekit.errors.GeometryError
        A non-positive size, or the hinge outside the water column.

    Examples
    --------
    >>> from flumekit.flap.bem import flap_mesh
    >>> vertices, faces, moving = flap_mesh(1.0, 1.0, 0.2, 0.1, 0.25)
    >>> faces.shape, int(moving.sum())
    ((25, 4), 20)
    """
    h, w, c, t, d = map(float, (depth, flap_width, hinge_height, thickness, panel_size))
    if not (h > 0 and w > 0 and t > 0 and d > 0 and 0 <= c < h):
        raise GeometryError(f"bad flap geometry: depth={h}, width={w}, hinge={c}, "
                            f"thickness={t}, panel_size={d}")
    n_y = max(1, int(np.ceil(0.5 * w / d)))  # panels across the half width
    y = np.linspace(-w / 2, 0.0, n_y + 1)
    n_lo = max(1, int(np.ceil(c / d))) if c > 0 else 0
    n_up = max(2, int(np.ceil((h - c) / d)))
    z = np.concatenate([np.linspace(-h, -h + c, n_lo + 1)[:-1] if n_lo else np.empty(0),
                        np.linspace(-h + c, 0.0, n_up + 1)])
    n_x = max(1, int(np.ceil(t / d)))
    x = np.linspace(-t / 2, t / 2, n_x + 1)
    verts, faces = [], []
    offset = 0
    for xf in (-t / 2, t / 2):  # front and back walls: grid over (y, z)
        yy, zz = np.meshgrid(y, z, indexing="ij")
        verts.append(np.stack([np.full(yy.size, xf), yy.ravel(), zz.ravel()], axis=-1))
        faces.append(_grid_faces(y.size - 1, z.size - 1, offset))
        offset += yy.size
    xx, zz = np.meshgrid(x, z, indexing="ij")  # side wall y = -w/2: grid over (x, z)
    verts.append(np.stack([xx.ravel(), np.full(xx.size, -w / 2), zz.ravel()], axis=-1))
    faces.append(_grid_faces(x.size - 1, z.size - 1, offset))
    vertices = np.concatenate(verts)
    faces = np.concatenate(faces)
    # orient every face outwards (away from the box centre line x = 0, y = 0)
    p = vertices[faces]
    normal = np.cross(p[:, 2] - p[:, 0], p[:, 3] - p[:, 1])
    centre = p.mean(axis=1)
    outward = np.where(np.abs(centre[:, 0]) >= t / 2 - 1e-12,
                       np.sign(centre[:, 0]) * normal[:, 0], -normal[:, 1])
    faces = np.where((outward < 0)[:, None], faces[:, ::-1], faces)
    moving = centre[:, 2] > -h + c
    return vertices, faces, moving


@doc
def coefficients(period, depth: float, flap_width: float, hinge_height: float,
                 thickness: float, rho: float = 1000.0, g: float = G,
                 panel_size: float = 0.05) -> xr.Dataset:
    """Compute the added inertia, radiation damping and excitation torque of the flap by BEM.

    Parameters
    ----------
    period : array_like
        Wave periods [s], finite and > 0.
    %(depth)s
    %(flap_width)s
    hinge_height : float
        Hinge height c above the bed [m].
    thickness : float
        Flap thickness t [m] (0.17 m for the flume's flap).
    rho : float, optional
        Water density [kg m-3].
    g : float, optional
        Gravitational acceleration [m s-2].
    panel_size : float, optional
        Target panel size [m]. The error falls roughly like panel_size (edges of the thin
        walls); use :func:`richardson` on two panel sizes (e.g. 0.1 and 0.07 m).

    Returns
    -------
    xarray.Dataset
        ``added_inertia`` [kg m2], ``radiation_damping`` [N m s], ``excitation_torque_real`` /
        ``_imag`` [N m m-1] and ``wave_number`` [rad m-1] over ``period`` [s], as
        :func:`flumekit.flap.renzi_dias.model.coefficients` (open water, no reflection
        coefficients), with attributes ``thickness``, ``panel_size``, ``n_panels`` and
        ``solver``.

    Raises
    ------
    ImportError
        Capytaine is not installed (``pip install flumekit[bem]``).
    ValueError
        Periods not 1-D, not finite or not positive.
    flumekit.errors.GeometryError
        An impossible geometry (:func:`flap_mesh`).

    References
    ----------
    Ancellin, M. & Dias, F. (2019). Capytaine: a Python-based linear potential flow solver.
    J. Open Source Software 4(36), 1341.
    """
    try:
        import capytaine as cpt
        from capytaine.bem.airy_waves import froude_krylov_force
        from capytaine.bodies.dofs import DofOnSubmesh, RotationDof
    except ImportError as exc:  # pragma: no cover - exercised without capytaine
        raise ImportError("flumekit.flap.bem needs Capytaine: pip install 'flumekit[bem]'"
                          ) from exc
    period = np.atleast_1d(np.asarray(period, dtype=float))
    if period.ndim != 1 or np.any(~np.isfinite(period)) or np.any(period <= 0):
        raise ValueError(f"period must be a 1-D array of finite values > 0 s, got {period}")
    vertices, faces, _ = flap_mesh(depth, flap_width, hinge_height, thickness, panel_size)
    half = cpt.Mesh(vertices, faces, auto_clean=False, auto_check=False, name="half_flap")
    mesh = cpt.ReflectionSymmetricMesh(half, plane="xOz", name="flap")
    moving = mesh.faces_centers[:, 2] > -depth + hinge_height
    dof = DofOnSubmesh(RotationDof(rotation_center=(0.0, 0.0, -depth + hinge_height),
                                   direction=(0.0, 1.0, 0.0)), moving)
    body = cpt.FloatingBody(mesh=mesh, dofs={"pitch": dof}, name="flap")
    solver = cpt.BEMSolver()
    mu, nu = np.empty(period.size), np.empty(period.size)
    fexc = np.empty(period.size, dtype=complex)
    for i, T in enumerate(period):  # one BEM solve per period (dense panel systems)
        kw = dict(body=body, period=float(T), water_depth=float(depth), rho=float(rho),
                  g=float(g))
        dif_problem = cpt.DiffractionProblem(wave_direction=0.0, **kw)
        with np.errstate(divide="ignore"):  # Capytaine's irregular-frequency estimate, thin box
            rad = solver.solve(cpt.RadiationProblem(radiating_dof="pitch", **kw),
                               keep_details=False)
            dif = solver.solve(dif_problem, keep_details=False)
        mu[i] = rad.added_masses["pitch"]
        nu[i] = rad.radiation_dampings["pitch"]
        fexc[i] = dif.forces["pitch"] + froude_krylov_force(dif_problem)["pitch"]
    omega = 2 * np.pi / period
    ds = xr.Dataset(
        {"added_inertia": ("period", mu), "radiation_damping": ("period", nu),
         "excitation_torque_real": ("period", fexc.real),
         "excitation_torque_imag": ("period", fexc.imag),
         "wave_number": ("period", wavenumber(omega, depth, g))},
        coords={"period": period, "angular_frequency": ("period", omega)})
    attrs = {"depth": float(depth), "flap_width": float(flap_width),
             "hinge_height": float(hinge_height), "thickness": float(thickness),
             "rho": float(rho), "g": float(g), "panel_size": float(panel_size),
             "n_panels": int(mesh.nb_faces), "solver": f"capytaine {cpt.__version__}",
             "geometry": "open water"}
    ds.attrs.update(conventions.global_attrs(
        "BEM coefficients of the thick flap on its fixed foundation (Capytaine)",
        "flumekit.flap.bem", attrs))
    ds.attrs.update(attrs)
    return conventions.annotate(ds)


def richardson(coarse: xr.Dataset, fine: xr.Dataset) -> xr.Dataset:
    """Extrapolate two BEM datasets to zero panel size (first-order Richardson).

    X_0 = (d_c X_f - d_f X_c) / (d_c - d_f) for μ, ν and the real and imaginary parts of F,
    with d the ``panel_size`` attributes (the BEM error falls like d, see the module notes).

    Parameters
    ----------
    coarse : xarray.Dataset
        Result of :func:`coefficients` at the larger panel size d_c [m].
    fine : xarray.Dataset
        Result of :func:`coefficients` at the smaller panel size d_f [m], same periods.

    Returns
    -------
    xarray.Dataset
        ``fine`` with the extrapolated coefficients (units unchanged), ``panel_size`` 0 and
        the two panel sizes in ``richardson_panel_sizes`` [m].

    Raises
    ------
    ValueError
        Panel sizes not ordered d_c > d_f > 0, or different periods.

    References
    ----------
    Richardson, L. F. (1911). The approximate arithmetical solution by finite differences of
    physical problems involving differential equations. Phil. Trans. R. Soc. A 210, 307-357.
    """
    dc, df = float(coarse.attrs["panel_size"]), float(fine.attrs["panel_size"])
    if not dc > df > 0:
        raise ValueError(f"need coarse panel size > fine panel size > 0, got {dc} and {df}")
    if not np.allclose(coarse["period"], fine["period"]):
        raise ValueError("richardson needs the two datasets on the same periods")
    out = fine.copy()
    for name in ("added_inertia", "radiation_damping", "excitation_torque_real",
                 "excitation_torque_imag"):
        out[name] = (dc * fine[name] - df * coarse[name]) / (dc - df)
        out[name].attrs = fine[name].attrs
    out.attrs["panel_size"] = 0.0
    out.attrs["richardson_panel_sizes"] = [dc, df]
    out.attrs["n_panels"] = int(fine.attrs["n_panels"])
    return out
