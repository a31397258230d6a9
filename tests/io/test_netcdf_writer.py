"""The netCDF writer (flumekit.io.netcdf.write_dataset): the netCDF4 library called directly
writes the file xarray's ``to_netcdf`` writes, byte for byte, and leaves to xarray what it
does not know."""

import filecmp

import numpy as np
import pytest
import xarray as xr

from flumekit.io import netcdf


def _product() -> xr.Dataset:
    """A dataset with what the products hold: records (one long enough to be compressed)
    with NaN, 64-bit integers stored as 32-bit ones, byte flags with their flag values,
    strings (a coordinate, a scalar, a record), coordinates that are not dimensions (per
    probe, a scalar run label), and global attributes of every kind."""
    rng = np.random.default_rng(3)
    long = rng.standard_normal((3, 5000))
    long[1, 10:20] = np.nan
    return xr.Dataset(
        {"eta": (("probe", "time"), long, {"units": "m", "long_name": "elevation"}),
         "flags": (("probe", "time"), rng.integers(1, 5, (3, 5000)).astype(np.int8),
                   {"units": "1", "long_name": "flags",
                    "flag_values": np.array([1, 2, 3, 4, 9], np.int8)}),
         "n_cycles": ((), np.int64(57), {"units": "1", "long_name": "cycles"}),
         "counts": ("probe", np.array([3, 4, 5], np.int64), {"units": "1", "long_name": "n"}),
         "criterion": ((), "tolerance", {"units": "1", "long_name": "criterion"}),
         "kr": ((), 0.2, {"units": "1", "long_name": "Kr", "comment": "first harmonic"}),
         "labels": ("probe", np.array(["a", "bb", "ccc"], object),
                    {"units": "1", "long_name": "labels"})},
        coords={"probe": ("probe", ["WP1", "WP2", "WP3"], {"units": "1", "long_name": "p"}),
                "time": ("time", np.arange(5000) / 50.0, {"units": "s", "long_name": "t"}),
                "x": ("probe", [-3.0, -2.4, -2.1], {"units": "m", "long_name": "x"}),
                "run": ((), "T2.00_H0.150_r0", {"units": "1", "long_name": "run"})},
        attrs={"Conventions": "CF-1.8", "title": "a product", "source": "a test",
               "history": "made", "n_draws": 20, "tolerance": 0.02,
               "edges": [0.1, 0.2, 0.4], "names": ["WP1", "WP2"], "seed": np.int32(7)})


def _both(ds: xr.Dataset, tmp_path, compress: bool = True):
    encoding = netcdf._encoding(ds, compress)
    by_xarray, direct = tmp_path / "xarray.nc", tmp_path / "direct.nc"
    ds.to_netcdf(by_xarray, engine="netcdf4", encoding=encoding)
    return netcdf._netcdf4_written(ds, direct, encoding), by_xarray, direct


@pytest.mark.parametrize("compress", [True, False])
def test_the_netcdf4_library_writes_the_file_xarray_writes(tmp_path, compress):
    written, by_xarray, direct = _both(_product(), tmp_path, compress)
    assert written
    assert filecmp.cmp(by_xarray, direct, shallow=False)
    back = netcdf.read_dataset(direct)
    assert back["x"].dims == ("probe",) and "run" in back.coords
    assert back["n_cycles"].dtype == np.int32 and np.isnan(back["eta"][1, 15])


def test_a_dataset_read_back_is_written_as_xarray_writes_it(tmp_path):
    """Read from a file, variables carry its encoding (their coordinates, storage)."""
    path = tmp_path / "first.nc"
    ds = _product()
    ds.to_netcdf(path, engine="netcdf4", encoding=netcdf._encoding(ds))
    read = netcdf.read_dataset(path)
    assert read["eta"].encoding.get("coordinates")
    read = read.drop_vars("x")  # a coordinate named in the encoding no longer there
    (tmp_path / "again").mkdir()
    written, by_xarray, direct = _both(read, tmp_path / "again")
    assert written and filecmp.cmp(by_xarray, direct, shallow=False)


@pytest.mark.parametrize("change", ["bounds", "bool attribute", "datetime", "nested list",
                                    "slash"])
def test_what_the_writer_does_not_know_is_left_to_xarray(tmp_path, change):
    """Declined before the file is made: xarray writes it (cell bounds, a datetime) or says
    what is wrong (an attribute netCDF cannot hold, a name with a slash)."""
    ds = _product()
    if change == "bounds":
        ds["time"].attrs["bounds"] = "time_bounds"
        ds["time_bounds"] = (("time", "nv"), np.zeros((5000, 2)), {"long_name": "b"})
    elif change == "bool attribute":
        ds["kr"].attrs["valid"] = True
    elif change == "datetime":
        ds["start"] = ((), np.datetime64("2020-01-01T00:00:00", "ns"), {"long_name": "s"})
    elif change == "nested list":
        ds.attrs["nested"] = [[1, 2], [3, 4]]
    else:
        ds = ds.rename({"kr": "k/r"})
    assert not netcdf._netcdf4_written(ds, tmp_path / "d.nc", netcdf._encoding(ds))
    assert not (tmp_path / "d.nc").exists()
    if change in ("bounds", "datetime"):
        written, by_xarray, _ = _both(ds, tmp_path)
        back = netcdf.read_dataset(by_xarray)
        assert ("time_bounds" if change == "bounds" else "start") in back
