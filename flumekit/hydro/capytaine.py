"""Reader of Capytaine's netCDF output (``cpt.assemble_dataset`` + ``to_netcdf``).

The format as WEC-Sim ships it.

The file holds ``added_mass`` and ``radiation_damping`` over (frequency, ``radiating_dof``,
``influenced_dof``), ``excitation_force`` (or ``diffraction_force`` + ``Froude_Krylov_force``)
over (frequency, ``wave_direction``, ``influenced_dof``) with complex values split along a
``complex`` dimension ("re", "im"), and ``hydrostatic_stiffness`` over (``influenced_dof``,
``radiating_dof``). Multi-body runs name the dofs ``<body>__<Dof>`` (WEC-Sim's OSWEC:
``oswec_flap__Pitch``, ``oswec_base_shift__Surge``, ...). Capytaine uses the time factor
e^{-iωt} and references the excitation to the incident wave at the origin, as flumekit does.

Capytaine does not store the rotation centre of the rigid dofs in the file: pass it as
``reference_point`` (WEC-Sim's OSWEC: the flap's centre of gravity, (0, 0, −3.9) m).

:func:`read_capytaine` returns the six-dof dataset of :mod:`flumekit.hydro.rigid_body`; for a
hinged flap continue with :func:`flumekit.hydro.rigid_body.about_hinge`.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import xarray as xr

from flumekit.docstrings import doc
from flumekit.errors import InputError
from flumekit.hydro.bem_layout import (
    excitation_of,
    frequency_dim,
    merge_complex_dim,
    select_direction,
)
from flumekit.hydro.rigid_body import DOFS, rigid_body_dataset


@doc
def read_capytaine(source: str | Path | xr.Dataset, *, body: str | None = None,
                   wave_direction: float = 0.0, reference_point=None) -> xr.Dataset:
    """Read the six-dof coefficients of one body from a Capytaine dataset or netCDF file.

    Parameters
    ----------
    source : str, pathlib.Path or xarray.Dataset
        Path of the netCDF file, or the dataset.
    body : str, optional
        Body name in a multi-body file (dofs ``<body>__Surge`` ...); by default the dofs
        without a body prefix.
    wave_direction : float, optional
        Incident direction [rad] to keep (0: waves towards +x).
    reference_point : sequence of float, optional
        Rotation centre of the body's rigid dofs (x, y, z) [m].

    Returns
    -------
    xarray.Dataset
        Dataset of :func:`flumekit.hydro.rigid_body.rigid_body_dataset`; frequencies that
        failed (NaN) are kept (see :func:`flumekit.hydro.rigid_body.drop_failed`), ω = 0 is
        dropped and ω = ∞ becomes ``added_mass_infinite`` [kg, kg m, kg m2].

    Raises
    ------
    flumekit.errors.InputError
        The file is missing or not a usable Capytaine result (missing variables or dofs, an
        unknown wave direction), naming the file.

    %(references_ancellin_dias2019)s.

    Examples
    --------
    A file as Capytaine writes it for a body "flap" of a multi-body run: dofs named
    ``flap__Surge`` ..., the limits ω = 0 and ω = ∞ among the frequencies, the complex
    excitation split along ``complex``:

    >>> import tempfile
    >>> from pathlib import Path
    >>> import numpy as np
    >>> import xarray as xr
    >>> from flumekit.hydro.capytaine import read_capytaine
    >>> from flumekit.hydro.rigid_body import DOFS
    >>> dofs = [f"flap__{d}" for d in DOFS]
    >>> a = np.eye(6) * np.array([400.0, 300.0, 250.0, 200.0])[:, None, None]  # per ω
    >>> f = np.zeros((2, 4, 1, 6))
    >>> f[:, :, 0, 4] = [[30.0], [-40.0]]  # pitch moment 30 − 40i, as ("re", "im")
    >>> rad = ("omega", "radiating_dof", "influenced_dof")
    >>> raw = xr.Dataset(
    ...     {"added_mass": (rad, a), "radiation_damping": (rad, 0.1 * a),
    ...      "excitation_force": (("complex", "omega", "wave_direction", "influenced_dof"), f)},
    ...     coords={"omega": [0.0, 1.0, 2.0, np.inf], "radiating_dof": dofs,
    ...             "influenced_dof": dofs, "wave_direction": [0.0], "complex": ["re", "im"]})
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     path = Path(tmp) / "flap.nc"
    ...     raw.to_netcdf(path)
    ...     body = read_capytaine(path, body="flap", reference_point=(0.0, 0.0, -3.9))
    >>> body["angular_frequency"].values.tolist()  # ω = 0 and ω = ∞ left out
    [1.0, 2.0]
    >>> complex(body["excitation_force"].sel(influenced_dof="Pitch")[0])
    (30-40j)
    >>> float(body["added_mass_infinite"].sel(radiating_dof="Pitch", influenced_dof="Pitch"))
    200.0
    """
    path = None if isinstance(source, xr.Dataset) else Path(source)
    try:
        if path is None:
            raw = source
        else:
            if not path.is_file():
                raise ValueError("no such file")
            raw = xr.load_dataset(path)
        return _read(raw, body, wave_direction, reference_point, str(path or "dataset"))
    except (ValueError, KeyError, OSError) as e:
        raise InputError(path, f"not a usable Capytaine result: {e}") from None


def _read(raw: xr.Dataset, body, wave_direction, reference_point, name) -> xr.Dataset:
    ds = merge_complex_dim(raw)
    fdim = frequency_dim(ds)
    for var in ("added_mass", "radiation_damping"):
        if var not in ds:
            raise ValueError(f"no '{var}' variable (radiation problems)")
    names = [str(v) for v in ds["radiating_dof"].values]
    prefix = f"{body}__" if body else ""
    wanted = [prefix + d for d in DOFS]
    missing = [w for w in wanted if w not in names]
    if missing:
        bodies = sorted({n.split("__")[0] for n in names if "__" in n})
        raise ValueError(f"dofs {missing} are not in the file (dofs: {names}"
                         + (f"; bodies: {bodies}, pass body=" if bodies else "") + ")")
    sel = {"radiating_dof": wanted, "influenced_dof": wanted}

    def pick(da):
        return select_direction(da.sel({k: v for k, v in sel.items() if k in da.dims}),
                                wave_direction)

    exc = pick(excitation_of(ds))
    a = pick(ds["added_mass"]).transpose(fdim, "radiating_dof", "influenced_dof")
    b = pick(ds["radiation_damping"]).transpose(fdim, "radiating_dof", "influenced_dof")
    exc = exc.transpose(fdim, "influenced_dof")
    if "hydrostatic_stiffness" in ds:
        c = np.real(pick(ds["hydrostatic_stiffness"]).transpose(
            "influenced_dof", "radiating_dof").values)
    else:
        c = np.zeros((6, 6))
    omega = np.asarray(ds["omega"].values, dtype=float).ravel()
    keep = np.isfinite(omega) & (omega > 0)
    a_inf = np.real(a.values[np.isinf(omega)][0]) if np.any(np.isinf(omega)) else None
    scalar = {k: float(ds[k].values) for k in ("rho", "g", "water_depth") if k in ds}
    return rigid_body_dataset(
        omega[keep], np.real(a.values[keep]), np.real(b.values[keep]), exc.values[keep], c,
        reference_point=reference_point, wave_direction=wave_direction,
        added_mass_infinite=a_inf, source=f"Capytaine {raw.attrs.get('capytaine_version', '')}"
        f" result {Path(name).name}, body '{body or ''}'", **scalar)
