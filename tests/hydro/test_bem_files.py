"""BEM files as users have them: WEC-Sim's OSWEC Capytaine file (vendored, unmodified) and
WAMIT's .1/.3/.hst; rotation about the hinge against a transformation written out by hand."""

import hashlib
import warnings
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from flumekit.errors import InputError
from flumekit.hydro import coefficients as H
from flumekit.hydro.capytaine import read_capytaine
from flumekit.hydro.rigid_body import DOFS, about_hinge, drop_failed
from flumekit.hydro.wamit import read_wamit

OSWEC = Path(__file__).resolve().parents[1] / "data" / "wecsim" / "oswec_hydrodynamics.nc"
SHA256 = "5ca162303dc0e71b33f1451535be5b0d75fb77e30e26fb2fbc9bcac3462e5898"
COG, HINGE = (0.0, 0.0, -3.9), (0.0, 0.0, -8.9)  # WEC-Sim's OSWEC example
MASS = 127000.0  # [kg], wecSimInputFile.m


@pytest.fixture(scope="module")
def raw():
    return xr.load_dataset(OSWEC)


@pytest.fixture(scope="module")
def rigid():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", H.FailedFrequencyWarning)
        return read_capytaine(OSWEC, body="oswec_flap", reference_point=COG)


def displaced_volume(raw):
    # Capytaine's default inertia matrix is rho V (the file's mass is not the flap's)
    return float(raw["inertia_matrix"].sel(influenced_dof="oswec_flap__Surge",
                                           radiating_dof="oswec_flap__Surge")) / 1000.0


def test_vendored_file_is_unmodified():
    assert hashlib.sha256(OSWEC.read_bytes()).hexdigest() == SHA256
    assert (OSWEC.parent / "LICENSE").is_file() and (OSWEC.parent / "COPYRIGHT").is_file()


def test_failed_frequencies_dropped_with_their_names(rigid):
    with pytest.warns(H.FailedFrequencyWarning, match=r"omega = 0\.04, 0\.08, 0\.12 rad/s"):
        hy = about_hinge(rigid, HINGE, mass=MASS, displaced_volume=297.38, passivity="clip")
    assert hy["angular_frequency"].values[0] == pytest.approx(0.16)
    assert hy.attrs["dropped_frequencies"] == pytest.approx([0.04, 0.08, 0.12])
    with pytest.raises(H.HydroError, match=r"0\.04, 0\.08, 0\.12"):
        drop_failed(rigid, "raise")


def test_hinge_coefficients_match_a_manual_transformation(raw, rigid):
    """Pitch about the hinge = pitch about the CoG + 5 m x surge, written out by hand from the
    file's 6x6 matrices (Capytaine layout: radiating, influenced; complex split re/im)."""
    v = displaced_volume(raw)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", H.FailedFrequencyWarning)
        hy = about_hinge(rigid, HINGE, mass=MASS, displaced_volume=v, passivity="clip")
    lever = COG[2] - HINGE[2]  # 5 m
    ok = np.isfinite(raw["added_mass"].values).all(axis=(1, 2))
    s, p = "oswec_flap__Surge", "oswec_flap__Pitch"

    def m(name, r, i):
        return raw[name].sel(radiating_dof=r, influenced_dof=i).values[ok]

    a = (m("added_mass", p, p) + lever * (m("added_mass", s, p) + m("added_mass", p, s))
         + lever**2 * m("added_mass", s, s))
    b = (m("radiation_damping", p, p) + lever * (m("radiation_damping", s, p)
                                                 + m("radiation_damping", p, s))
         + lever**2 * m("radiation_damping", s, s))
    exc = raw["excitation_force"].sel(wave_direction=0.0)
    f = exc.sel(influenced_dof=p) + lever * exc.sel(influenced_dof=s)
    f = (f.sel(complex="re") + 1j * f.sel(complex="im")).values[ok]
    c55 = float(raw["hydrostatic_stiffness"].sel(influenced_dof=p, radiating_dof=p))
    c = c55 + lever * (1000.0 * 9.81 * v - MASS * 9.81)
    np.testing.assert_allclose(hy["added_inertia"].values, a, rtol=1e-12)
    np.testing.assert_allclose(hy["radiation_damping"].values, np.maximum(b, 0), rtol=1e-12)
    np.testing.assert_allclose(hy["excitation_torque"].values, f, rtol=1e-12)
    assert float(hy["hydrostatic_stiffness"]) == pytest.approx(c, rel=1e-12)
    # the numbers: 6.8e7 kg m2 at 0.8 rad/s about the hinge against 6.7e6 at the CoG
    assert float(hy["added_inertia"].sel(angular_frequency=0.8)) == pytest.approx(6.76e7, rel=2e-3)
    assert c > 0 > c55


def test_cog_pitch_and_non_passive_damping_are_refused(rigid):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", H.FailedFrequencyWarning)
        with pytest.raises(H.HydroError, match="statically unstable"):
            about_hinge(rigid, COG, mass=MASS, displaced_volume=297.38)  # pitch about the CoG
        with pytest.raises(H.HydroError, match="negative at 132 of 497 frequencies"):
            about_hinge(rigid, HINGE, mass=MASS, displaced_volume=297.38)
    with pytest.raises(H.HydroError, match="<= 0"):
        H.hydro_dataset([1.0, 2.0], [1.0, 1.0], [1.0, 1.0], [1.0, 1.0], -1.0)
    with pytest.raises(H.HydroError, match="reference_point"):
        unknown = rigid.copy()
        unknown.attrs = {k: v for k, v in rigid.attrs.items() if k != "reference_point"}
        about_hinge(unknown, HINGE, mass=MASS, displaced_volume=297.38)


def test_capytaine_reader_errors_name_the_file(tmp_path):
    with pytest.raises(InputError, match="no such file"):
        read_capytaine(tmp_path / "missing.nc")
    with pytest.raises(InputError, match="pass body="):
        read_capytaine(OSWEC)


#: the pairs of modes a body symmetric about y = 0 couples: (surge, heave, pitch) and
#: (sway, roll, yaw); WAMIT writes only these 18 of the 36
SYMMETRIC_PAIRS = {(i, j) for group in ((0, 2, 4), (1, 3, 5)) for i in group for j in group}


def write_wamit(stem, rigid, length, pairs=None, excited=range(6)):
    """WAMIT-format files (manual §4.2-4.9, e^{+iwt}) from a six-dof dataset: every pair of
    modes, or only ``pairs`` in ``.1`` and the modes ``excited`` in ``.3``."""
    rho, g = rigid.attrs["rho"], rigid.attrs["g"]
    w = rigid["angular_frequency"].values
    rot = np.array([d in ("Roll", "Pitch", "Yaw") for d in DOFS])
    lines1, lines3 = [], []
    for n, om in enumerate(w):
        for i in range(6):
            for j in range(6):
                if pairs is not None and (i, j) not in pairs:
                    continue
                k = 3 + rot[i] + rot[j]
                a = rigid["added_mass"].values[n, j, i] / (rho * length**k)
                b = rigid["radiation_damping"].values[n, j, i] / (rho * length**k * om)
                lines1.append(f"{2 * np.pi / om:.9E} {i + 1} {j + 1} {a:.9E} {b:.9E}")
        for i in excited:
            x = np.conj(rigid["excitation_force"].values[n, i]) / (rho * g * length ** (2 + rot[i]))
            lines3.append(f"{2 * np.pi / om:.9E} 0.0 {i + 1} {abs(x):.9E} "
                          f"{np.degrees(np.angle(x)):.9E} {x.real:.9E} {x.imag:.9E}")
    lines1.append(f"0.0 5 5 {1.0 / (rho * length**5):.9E}")  # zero period: A_inf
    (stem.parent / (stem.name + ".1")).write_text("\n".join(lines1) + "\n")
    (stem.parent / (stem.name + ".3")).write_text("\r\n".join(lines3) + "\r\n")  # CRLF too
    c = rigid["hydrostatic_stiffness"].values
    (stem.parent / (stem.name + ".hst")).write_text("\n".join(
        f"{i + 1} {j + 1} {c[i, j] / (rho * g * length ** (2 + rot[i] + rot[j])):.9E}"
        for i in range(6) for j in range(6)))


def test_wamit_reader_restores_dimensional_values(tmp_path, rigid):
    sub = rigid.isel(angular_frequency=slice(3, 40))
    write_wamit(tmp_path / "oswec", sub, length=2.0)
    back = read_wamit(tmp_path / "oswec", length_scale=2.0, reference_point=COG)
    for name in ("added_mass", "radiation_damping", "excitation_force"):
        np.testing.assert_allclose(back[name].values, sub[name].values, rtol=1e-8,
                                   atol=1e-9 * float(np.abs(sub[name]).max()))
    np.testing.assert_allclose(back["hydrostatic_stiffness"].values,
                               sub["hydrostatic_stiffness"].values, rtol=1e-8, atol=1e-6)
    assert float(back["added_mass_infinite"].sel(radiating_dof="Pitch",
                                                 influenced_dof="Pitch")) == pytest.approx(1.0)
    hw = about_hinge(back, HINGE, mass=MASS, displaced_volume=297.38, passivity="clip")
    hc = about_hinge(sub, HINGE, mass=MASS, displaced_volume=297.38, passivity="clip")
    np.testing.assert_allclose(hw["added_inertia"].values, hc["added_inertia"].values, rtol=1e-8)


def test_wamit_pairs_left_out_by_symmetry_are_zero_and_unlisted_modes_nan(tmp_path, rigid):
    """A symmetric body's files as WAMIT writes them: 18 pairs in .1, surge, heave and pitch
    in .3 for head seas. What WAMIT leaves out is zero, and the flap's hinge coefficients are
    those of the full files; a mode never listed is not computed, so it stays NaN."""
    sub = rigid.isel(angular_frequency=slice(3, 12))
    write_wamit(tmp_path / "sym", sub, length=1.0, pairs=SYMMETRIC_PAIRS, excited=(0, 2, 4))
    back = read_wamit(tmp_path / "sym", reference_point=COG)
    keep = np.array([[(i, j) in SYMMETRIC_PAIRS for i in range(6)] for j in range(6)])
    for name in ("added_mass", "radiation_damping"):
        want = np.where(keep, sub[name].values, 0.0)
        np.testing.assert_allclose(back[name].values, want, rtol=1e-8,
                                   atol=1e-9 * float(np.abs(sub[name]).max()))
    f = back["excitation_force"].values
    assert np.all(f[:, [1, 3, 5]] == 0) and np.all(np.isfinite(f))
    full = sub.copy(deep=True)
    full["added_mass"].values[:] = np.where(keep, sub["added_mass"].values, 0.0)
    hinge = dict(mass=MASS, displaced_volume=297.38, passivity="clip")
    np.testing.assert_allclose(about_hinge(back, HINGE, **hinge)["added_inertia"].values,
                               about_hinge(full, HINGE, **hinge)["added_inertia"].values,
                               rtol=1e-8)
    # only surge, heave and pitch computed (the other modes never listed)
    write_wamit(tmp_path / "three", sub, length=1.0,
                pairs={p for p in SYMMETRIC_PAIRS if p[0] % 2 == 0}, excited=(0, 2, 4))
    part = read_wamit(tmp_path / "three", reference_point=COG)
    a = part["added_mass"].values
    assert np.isnan(a[:, 1, 1]).all() and np.isnan(a[:, 0, 1]).all()
    assert np.isfinite(a[:, 0, 4]).all() and np.isnan(part["excitation_force"].values[:, 1]).all()


def test_wamit_reader_errors(tmp_path):
    with pytest.raises(InputError, match="no such file"):
        read_wamit(tmp_path / "none")
    for ext, text in ((".1", "10.0 1 1 x 2.0\n"), (".3", ""), (".hst", "")):
        (tmp_path / f"bad{ext}").write_text(text)
    with pytest.raises(InputError, match="line 1"):
        read_wamit(tmp_path / "bad")
