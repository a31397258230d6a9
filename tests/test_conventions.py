"""A dataset built annotated equals the one built, then annotated."""

import numpy as np
import xarray as xr

from flumekit.conventions import annotate, annotated_dataset


def test_annotated_dataset_is_the_annotated_dataset():
    """Registered and unregistered variables, dimension coordinates, a scalar, attributes
    of the caller's (a long name refined, a wrong unit replaced) and the dataset's."""
    t = np.arange(5) * 0.1
    data = {"eta_incident": ("time", np.sin(t)),
            "reflection_coefficient": ((), 0.2, {"long_name": "Kr of the first harmonic",
                                                 "units": "percent"}),
            "not_registered": (("time",), np.cos(t), {"note": "kept"})}
    coords = {"time": t, "harmonic": np.arange(1, 4)}
    built = annotated_dataset(data, coords, {"method": "test"})
    expected = annotate(xr.Dataset(data, coords=coords, attrs={"method": "test"}))
    assert built.identical(expected)
    for name in built.variables:
        assert list(built[name].attrs) == list(expected[name].attrs), name
    assert built["reflection_coefficient"].attrs["units"] != "percent"
    assert built["reflection_coefficient"].attrs["long_name"] == "Kr of the first harmonic"
    assert list(built.indexes) == ["time", "harmonic"]
    assert list(built.variables) == list(expected.variables)


def test_annotated_dataset_with_coordinates_off_their_dimensions():
    """A dimension without a coordinate (probe), a coordinate on another dimension (x), and
    inputs xarray's constructor refuses (two sizes of one dimension) refused as it does."""
    import pytest

    data = {"eta": (("probe", "time"), np.zeros((3, 4)))}
    coords = {"time": np.arange(4) * 0.1, "x": ("probe", [-3.0, -2.5, -2.0])}
    built = annotated_dataset(data, coords)
    assert built.identical(annotate(xr.Dataset(data, coords=coords)))
    assert list(built.indexes) == ["time"] and built.sizes == {"probe": 3, "time": 4}
    with pytest.raises(ValueError):
        annotated_dataset({"eta": ("time", np.zeros(5))}, {"time": np.arange(4) * 0.1})
