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
