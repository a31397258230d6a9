"""Froude scaling: each exponent against its unit, the round trip, the campaign's [scale]."""

from __future__ import annotations

import numpy as np
import pytest
import xarray as xr

import flumekit
from flumekit import conventions
from flumekit.scaling import dimensions, froude_factor

LAM = 10.0


@pytest.mark.parametrize("units, exponent", [
    # Froude similitude (ITTC 7.5-02-07-03.7 §2.1), same density: the textbook table
    ("m", 1.0), ("s", 0.5), ("m s-1", 0.5), ("m s-2", 0.0), ("rad", 0.0), ("1", 0.0),
    ("Hz", -0.5), ("rad s-1", -0.5), ("N", 3.0), ("N m", 4.0), ("W", 3.5), ("W m-1", 2.5),
    ("Pa", 1.0), ("kg", 3.0), ("kg m2", 5.0), ("kg m-3", 0.0), ("m3 s-1", 2.5), ("J", 4.0),
    ("m2 s", 2.5), ("N m s", 4.5), ("N m rad-1", 4.0), ("Pa s2 rad-2", 2.0), ("N m m-1", 3.0),
])
def test_exponent_of_each_unit(units, exponent):
    assert dimensions(units).froude_exponent == exponent
    assert froude_factor(units, LAM) == pytest.approx(LAM ** exponent, rel=1e-14)


def test_density_enters_with_the_mass_power():
    # a force is a mass times an acceleration: one power of the density ratio; a length none
    r = 1025.0 / 1000.0
    assert froude_factor("N", LAM, r) == pytest.approx(1e3 * r, rel=1e-14)
    assert froude_factor("W m-1", LAM, r) == pytest.approx(LAM ** 2.5 * r, rel=1e-14)
    assert froude_factor("m", LAM, r) == LAM


@pytest.mark.parametrize("units", ["V", "K", "m V-1", "furlong"])
def test_unscalable_units_are_refused(units):
    with pytest.raises(ValueError, match="Froude"):
        dimensions(units)


def _summary():
    rng = np.random.default_rng(3)
    n = 5
    return xr.Dataset(
        {k: ("run", rng.uniform(0.1, 300.0, n)) for k in (
            "incident_height", "measured_period", "reflection_coefficient", "theta_amplitude",
            "torque_amplitude", "mean_power", "capture_factor", "energy_flux",
            "pressure_loss_coefficient", "incident_power")},
        coords={"run": [f"r{i}" for i in range(n)], "wave_period": ("run", rng.uniform(2, 4, n)),
                "wave_height": ("run", rng.uniform(0.1, 0.3, n))})


def test_every_registry_unit_of_a_summary_scales_as_its_dimensions():
    ds = _summary()
    full = flumekit.scale(ds, LAM, model_density=1000.0, prototype_density=1025.0)
    r = 1.025
    expect = {"incident_height": LAM, "measured_period": LAM ** 0.5, "reflection_coefficient": 1,
              "theta_amplitude": 1, "torque_amplitude": LAM ** 4 * r, "mean_power": LAM ** 3.5 * r,
              "capture_factor": 1, "energy_flux": LAM ** 2.5 * r, "incident_power": LAM ** 3.5 * r,
              "pressure_loss_coefficient": LAM ** 2 * r, "wave_period": LAM ** 0.5,
              "wave_height": LAM}
    for k, f in expect.items():
        np.testing.assert_allclose(full[k].values, ds[k].values * f, rtol=1e-14, err_msg=k)
    assert list(full.run.values) == list(ds.run.values)
    assert full.attrs["froude_scaled_to"] == "prototype"


def test_round_trip_is_the_identity():
    ds = conventions.annotate(_summary())
    back = flumekit.scale(flumekit.scale(ds, 37.0, 998.2, 1027.0), 37.0, 998.2, 1027.0,
                          to="model")
    for k in ds.variables:
        if ds[k].dtype.kind == "f":
            np.testing.assert_allclose(back[k].values, ds[k].values, rtol=1e-12, atol=0,
                                       err_msg=k)
        assert back[k].attrs == ds[k].attrs


def test_refusals_name_the_variable():
    ds = _summary().assign(probe_voltage=("run", np.ones(5)))
    with pytest.raises(ValueError, match="probe_voltage"):
        flumekit.scale(ds, LAM)
    with pytest.raises(ValueError, match="my_thing"):
        flumekit.scale(_summary().assign(my_thing=("run", np.ones(5))), LAM)
    full = flumekit.scale(_summary(), LAM)
    with pytest.raises(ValueError, match="already at prototype"):
        flumekit.scale(full, LAM)


def test_campaign_scale_is_read_and_used(tmp_path):
    import shutil
    from importlib import resources

    from flumekit.campaign import load_campaign

    src = resources.files("flumekit") / "data" / "default_campaign.toml"
    text = src.read_text() + ("\n[scale]\nfactor = 10\nmodel_density = 1000.0\n"
                              "prototype_density = 1025.0\n")
    (tmp_path / "campaign.toml").write_text(text)
    c = load_campaign(tmp_path)
    assert (c.scale.factor, c.scale.model_density, c.scale.prototype_density) == \
        (10.0, 1000.0, 1025.0)
    ds = _summary()
    a = flumekit.scale(ds, c.scale)
    b = flumekit.scale(ds, 10.0, 1000.0, 1025.0)
    xr.testing.assert_identical(a, b)
    (tmp_path / "campaign.toml").write_text(src.read_text() + "\n[scale]\nfactor = -2\n")
    with pytest.raises(flumekit.InputError, match="scale.factor"):
        load_campaign(tmp_path)
    shutil.rmtree(tmp_path)
