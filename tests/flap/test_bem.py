"""Capytaine BEM path: mesh, layout, and the thin-flap comparison with the Renzi–Dias model."""

from __future__ import annotations

import numpy as np
import pytest

from flumekit import conventions
from flumekit.errors import GeometryError
from flumekit.flap import bem
from flumekit.flap.renzi_dias import model as rd
from flumekit.hydro import response as rs
from flumekit.io.netcdf import read_dataset, write_dataset

H, W, C = 0.825, 1.31, 0.10


def test_half_mesh_is_closed_wetted_box_with_outward_normals():
    """Areas: front + back + side = 2·(w/2)·h + t·h exactly; normals point away from the box."""
    t = 0.17
    v, f, moving = bem.flap_mesh(H, W, C, t, 0.05)
    p = v[f]
    cross = np.cross(p[:, 2] - p[:, 0], p[:, 3] - p[:, 1])
    area = 0.5 * np.linalg.norm(cross, axis=1)
    assert area.sum() == pytest.approx(2 * (W / 2) * H + t * H, rel=1e-12)
    centre = p.mean(axis=1)
    n = cross / np.linalg.norm(cross, axis=1)[:, None]
    on_side = np.isclose(centre[:, 1], -W / 2)
    assert np.all(n[on_side, 1] < -0.999)
    assert np.all(np.sign(n[~on_side, 0]) == np.sign(centre[~on_side, 0]))
    assert np.all(moving == (centre[:, 2] > -H + C))
    assert np.any(np.isclose(v[:, 2], -H + C))  # a node row on the hinge line


def test_bad_geometry_raises():
    with pytest.raises(GeometryError):
        bem.flap_mesh(H, W, H + 0.1, 0.02, 0.05)
    with pytest.raises(GeometryError):
        bem.flap_mesh(H, W, C, 0.0, 0.05)


capytaine = pytest.importorskip("capytaine")


@pytest.fixture(scope="module")
def thin():
    periods = [2.0, 3.0, 4.0]
    coarse = bem.coefficients(periods, H, W, C, thickness=0.02, panel_size=0.07)
    fine = bem.coefficients(periods, H, W, C, thickness=0.02, panel_size=0.05)
    return coarse, fine, bem.richardson(coarse, fine), rd.coefficients(periods, H, W, C)


def test_thin_flap_bem_agrees_with_the_thin_plate_model(thin):
    """0.02 m flap in open water, T = 2, 3, 4 s, BEM extrapolated to zero panel size (panels
    0.07 and 0.05 m, first-order convergence measured): μ, ν and |F| within 5 % of the model
    (measured μ +0.3..0.7 %, ν +4.2..4.9 %), arg F within 1°.

    ν carries the largest difference, and it is the plate's thickness rather than mesh error:
    the BEM obeys the 3-D Haskind scaling ν ∝ |F|² (checked here to 1 %), so ν carries twice
    the relative excess of |F|, which grows with the thickness (+2.5 % for t = 0.02 m). With the
    coarser panels 0.1/0.07 m the extrapolated ν was +4.3..5.1 %: the mesh matters at that level.
    """
    _, _, ext, model = thin
    f_b, f_m = rd.excitation(ext).values, rd.excitation(model).values
    mu_ratio = ext.added_inertia.values / model.added_inertia.values
    f_ratio = np.abs(f_b) / np.abs(f_m)
    nu_ratio = ext.radiation_damping.values / model.radiation_damping.values
    assert np.all(np.abs(mu_ratio - 1) < 0.05)
    assert np.all(np.abs(f_ratio - 1) < 0.05)
    assert np.all(np.abs(np.degrees(np.angle(f_b / f_m))) < 1.0)
    assert np.all(np.abs(nu_ratio - 1) < 0.05)
    np.testing.assert_allclose(nu_ratio, f_ratio**2, rtol=0.01)


def test_bem_converges_towards_the_model_with_the_panel_size(thin):
    coarse, fine, _, model = thin
    for name in ("added_inertia", "radiation_damping"):
        e_c = np.abs(coarse[name].values / model[name].values - 1)
        e_f = np.abs(fine[name].values / model[name].values - 1)
        assert np.all(e_f < e_c)


def test_bem_dataset_layout_feeds_the_response_and_caches(thin, tmp_path):
    _, fine, _, _ = thin
    conventions.check(fine)
    out = rs.response(fine, 0.1, 14.74, 605.0, rs.optimal_pto_damping(fine, 14.74, 605.0))
    assert np.all(out.capture_factor > 0)
    back = read_dataset(write_dataset(fine, tmp_path / "bem.nc"))
    np.testing.assert_array_equal(rd.excitation(back).values, rd.excitation(fine).values)
    assert back.attrs["n_panels"] == fine.attrs["n_panels"]
