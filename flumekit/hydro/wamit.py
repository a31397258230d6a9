"""Reader of WAMIT's numeric output: ``.1``, ``.3`` and ``.hst`` files.

``.1`` holds added mass and damping, ``.3`` the diffraction excitation and ``.hst`` the
hydrostatic restoring (WAMIT User Manual v7, §4.2-4.3 and §4.9).

Every file is whitespace-separated text in WAMIT's non-dimensional form (length scale L =
ULEN of the run, ρ, g):

* ``.1``: ``PER I J Ā B̄`` with A_ij = Ā ρ L^k and B_ij = B̄ ρ L^k ω, k = 3 when i, j are
  both translations, 4 for one rotation, 5 for two. PER = 0 (zero period) lines hold the
  infinite-frequency Ā only, PER = −1 (infinite period) the zero-frequency Ā only.
* ``.3``: ``PER β I |X̄| arg X̄ Re X̄ Im X̄`` with X_i = X̄ ρ g L^m per unit wave amplitude,
  m = 2 for forces, 3 for moments, β the heading [deg].
* ``.hst``: ``I J C̄`` with C_ij = C̄ ρ g L^k, k = 2, 3, 4 as for ``.1`` minus one.

The first column is the period [s] (WAMIT's default IPEROUT = 1); pass
``first_column="angular_frequency"`` for files written with IPEROUT = 2. Indices above 6 belong
to further bodies (I = 6(b − 1) + dof). WAMIT's time factor is e^{+iωt}; flumekit's is e^{-iωt},
so the excitation is conjugated. The rotations are about the body's origin (XBODY): pass it as
``reference_point`` for :func:`flumekit.hydro.rigid_body.about_hinge`.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import xarray as xr

from flumekit.errors import InputError
from flumekit.hydro.rigid_body import rigid_body_dataset


def _table(path: Path, ncol: int) -> np.ndarray:
    if not path.is_file():
        raise InputError(path, "no such file")
    rows = []
    text = path.read_text(encoding="utf-8-sig", errors="strict")
    for i, line in enumerate(text.splitlines(), start=1):
        parts = line.replace("D", "E").replace("d", "e").split()
        if not parts:
            continue
        try:
            vals = [float(p) for p in parts]
        except ValueError:
            raise InputError(path, f"not a number in {line.strip()!r}", line=i) from None
        if len(vals) != ncol and not (ncol == 5 and len(vals) == 4):
            raise InputError(path, f"{len(vals)} columns, expected {ncol}", line=i)
        rows.append(vals + [np.nan] * (ncol - len(vals)))
    if not rows:
        raise InputError(path, "the file is empty")
    return np.array(rows)


def _power(i: np.ndarray, j: np.ndarray, base: int) -> np.ndarray:
    return base + ((i - 1) % 6 >= 3).astype(int) + ((j - 1) % 6 >= 3).astype(int)


def read_wamit(stem: str | Path, *, length_scale: float = 1.0, rho: float = 1000.0,
               g: float = 9.81, body: int = 1, wave_direction: float = 0.0,
               reference_point=(0.0, 0.0, 0.0), water_depth: float = np.inf,
               first_column: str = "period") -> xr.Dataset:
    r"""Read the six-dof coefficients of one body from ``<stem>.1``, ``.3`` and ``.hst``.

    Parameters
    ----------
    stem : str or pathlib.Path
        Path without extension.
    length_scale : float, optional
        WAMIT's ULEN [m].
    rho : float, optional
        Water density [kg m-3] of the dimensional values.
    g : float, optional
        Gravitational acceleration [m s-2] of the dimensional values.
    body : int, optional
        Body number (1 for the first).
    wave_direction : float, optional
        Heading to keep [rad] (0: waves towards +x).
    reference_point : sequence of float, optional
        Body origin (x, y, z) [m] in the frame of the excitation phase reference.
    water_depth : float, optional
        Depth of the run [m].
    first_column : {"period", "angular_frequency"}, optional
        What the first column holds: the period [s] (IPEROUT = 1) or the angular frequency
        [rad s-1] (IPEROUT = 2).

    Returns
    -------
    xarray.Dataset
        Dataset of :func:`flumekit.hydro.rigid_body.rigid_body_dataset`. A coefficient the
        files leave out is zero where WAMIT omits it by symmetry (both modes listed at that
        period, in ``.1`` on the diagonal); it is NaN where a period or a mode is missing
        altogether (see :func:`flumekit.hydro.rigid_body.drop_failed`).

    Raises
    ------
    flumekit.errors.InputError
        A file is missing, empty, holds a non-number or a wrong column count (file and line
        named), has no positive period, or lacks the requested heading.
    ValueError
        ``first_column`` is neither "period" nor "angular_frequency".

    References
    ----------
    WAMIT, Inc. (2016). WAMIT User Manual, Version 7, §4.2-4.3 and §4.9.

    Examples
    --------
    Non-dimensional files of one period T = 2π s (ω = 1 rad/s), run with ULEN L = 2 m: Ā = 1
    and B̄ = 0.5 on the diagonal, X̄ = −i in every mode (WAMIT's e^{+iωt}), C̄₃₃ = 1.

    >>> import tempfile
    >>> from pathlib import Path
    >>> import numpy as np
    >>> from flumekit.hydro.wamit import read_wamit
    >>> per, pairs = 2 * np.pi, [(i, j) for i in range(1, 7) for j in range(1, 7)]
    >>> files = {".1": [f"{per} {i} {j} {float(i == j)} {0.5 * (i == j)}" for i, j in pairs],
    ...          ".3": [f"{per} 0.0 {i} 1.0 -90.0 0.0 -1.0" for i in range(1, 7)],
    ...          ".hst": [f"{i} {j} {float(i == j == 3)}" for i, j in pairs]}
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     stem = Path(tmp) / "buoy"
    ...     for ext, lines in files.items():
    ...         _ = stem.with_suffix(ext).write_text("\n".join(lines) + "\n")
    ...     body = read_wamit(stem, length_scale=2.0)
    >>> body["angular_frequency"].values.tolist()  # 2π / T
    [1.0]
    >>> np.diag(body["added_mass"].values[0]).tolist()  # ρ L³ Ā, rotations ρ L⁵ Ā
    [8000.0, 8000.0, 8000.0, 32000.0, 32000.0, 32000.0]
    >>> float(body["radiation_damping"].sel(radiating_dof="Heave", influenced_dof="Heave")[0])
    4000.0
    >>> complex(body["excitation_force"].sel(influenced_dof="Heave")[0])  # ρ g L² (+i)
    39240j
    >>> float(body["hydrostatic_stiffness"].sel(influenced_dof="Heave", radiating_dof="Heave"))
    39240.0
    """
    stem = Path(stem)
    p1, p3, ph = (stem.with_name(stem.name + ext) for ext in (".1", ".3", ".hst"))
    t1, t3, th = _table(p1, 5), _table(p3, 7), _table(ph, 3)
    if first_column not in ("period", "angular_frequency"):
        raise ValueError(f"first_column must be 'period' or 'angular_frequency', got "
                         f"{first_column!r}")
    lo = 6 * (body - 1)

    def omega_of(x):
        with np.errstate(divide="ignore"):
            return 2 * np.pi / x if first_column == "period" else x

    regular = t1[:, 0] > 0
    w1 = omega_of(t1[regular, 0])
    omega = np.unique(w1)
    if omega.size == 0:
        raise InputError(p1, "no line with a positive period")
    n = omega.size
    a, b = np.full((n, 6, 6), np.nan), np.full((n, 6, 6), np.nan)
    i, j = t1[:, 1].astype(int), t1[:, 2].astype(int)
    mine = (i > lo) & (i <= lo + 6) & (j > lo) & (j <= lo + 6)
    k = _power(i, j, 3)
    scale = rho * length_scale ** k.astype(float)
    rows = regular & mine
    idx = np.searchsorted(omega, omega_of(t1[rows, 0]))
    # WAMIT's A_ij is the force in mode i from a motion in mode j: (radiating j, influenced i)
    a[idx, j[rows] - lo - 1, i[rows] - lo - 1] = t1[rows, 3] * scale[rows]
    b[idx, j[rows] - lo - 1, i[rows] - lo - 1] = t1[rows, 4] * scale[rows] * omega[idx]
    # WAMIT leaves out the pairs that the body's symmetry makes zero (18 of the 36 for a body
    # symmetric about y = 0): a pair absent at a period where both modes' diagonal is listed
    # is zero; a mode the file never lists stays NaN (not computed)
    listed = np.isfinite(np.diagonal(a, axis1=1, axis2=2))
    zero = listed[:, :, None] & listed[:, None, :]
    a, b = np.where(np.isnan(a) & zero, 0.0, a), np.where(np.isnan(b) & zero, 0.0, b)
    inf_rows = (t1[:, 0] == 0) & mine if first_column == "period" else np.zeros_like(mine)
    a_inf = None
    if inf_rows.any():
        a_inf = np.zeros((6, 6))
        a_inf[j[inf_rows] - lo - 1, i[inf_rows] - lo - 1] = t1[inf_rows, 3] * scale[inf_rows]

    heading = np.deg2rad(t3[:, 1])
    gap = np.abs(np.angle(np.exp(1j * (heading - wave_direction))))
    if gap.min() > 1e-6:
        raise InputError(p3, f"heading {np.rad2deg(wave_direction):g} deg not computed; "
                             f"available: {sorted(set(t3[:, 1].tolist()))}")
    i3 = t3[:, 2].astype(int)
    rows = (gap <= 1e-6) & (i3 > lo) & (i3 <= lo + 6) & (t3[:, 0] > 0)
    f = np.full((n, 6), np.nan, dtype=complex)
    idx = np.searchsorted(omega, omega_of(t3[rows, 0]))
    ok = (idx < n) & np.isclose(omega[np.minimum(idx, n - 1)], omega_of(t3[rows, 0]))
    m = np.where((i3[rows] - 1) % 6 >= 3, 3, 2)
    # WAMIT's e^{+iωt} -> flumekit's e^{-iωt}: complex conjugate
    x = (t3[rows, 5] - 1j * t3[rows, 6]) * rho * g * length_scale ** m.astype(float)
    f[idx[ok], i3[rows][ok] - lo - 1] = x[ok]
    # likewise a listed mode absent at a period the heading has: no excitation by symmetry
    seen = np.zeros(n, dtype=bool)
    seen[idx[ok]] = True
    f = np.where(np.isnan(f) & seen[:, None] & listed, 0.0, f)

    c = np.zeros((6, 6))
    ih, jh = th[:, 0].astype(int), th[:, 1].astype(int)
    rows = (ih > lo) & (ih <= lo + 6) & (jh > lo) & (jh <= lo + 6)
    kh = _power(ih[rows], jh[rows], 2)
    c[ih[rows] - lo - 1, jh[rows] - lo - 1] = th[rows, 2] * rho * g * length_scale ** kh.astype(
        float)
    return rigid_body_dataset(omega, a, b, f, c, reference_point=reference_point, rho=rho, g=g,
                              water_depth=water_depth, wave_direction=wave_direction,
                              added_mass_infinite=a_inf,
                              source=f"WAMIT output {stem.name}.1/.3/.hst, body {body}")
