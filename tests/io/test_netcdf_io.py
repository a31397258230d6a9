"""Writing and reading netCDF (flumekit.io.netcdf): the netCDF4 library called directly writes
the file xarray's ``to_netcdf`` writes, byte for byte, and reads the dataset xarray's
``open_dataset`` reads (encodings included); each leaves to xarray what it does not know."""

import filecmp
import os

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


def _same(a, b) -> bool:
    """Equal as :func:`xarray.Dataset.identical` and in every order, type and encoding."""
    def attrs(x, y):
        return list(x) == list(y) and all(
            type(x[k]) is type(y[k]) and np.array_equal(x[k], y[k]) for k in x)

    def encoding(v):
        return {k: str(e) for k, e in v.encoding.items()}

    return (a.identical(b) and list(a.variables) == list(b.variables)
            and list(a.dims) == list(b.dims) and list(a.coords) == list(b.coords)
            and list(a.indexes) == list(b.indexes) and attrs(a.attrs, b.attrs)
            and all(a[k].dtype == b[k].dtype and attrs(a[k].attrs, b[k].attrs)
                    and encoding(a.variables[k]) == encoding(b.variables[k])
                    for k in a.variables))


@pytest.mark.parametrize("compress", [True, False])
def test_the_netcdf4_library_reads_the_dataset_xarray_reads(tmp_path, compress):
    ds = _product()
    ds["eta"][0, :5] = np.nan
    path = tmp_path / "p.nc"
    ds.to_netcdf(path, engine="netcdf4", encoding=netcdf._encoding(ds, compress))
    read = netcdf._netcdf4_read(path)
    assert read is not None
    assert _same(netcdf._xarray_read(path), read)
    assert _same(netcdf.read_dataset(path), read)
    assert read["labels"].dtype.kind == "U" and read["n_cycles"].dtype == np.int32
    assert "x" in read.coords and "run" in read.coords and np.isnan(read["eta"][0, 0])


def test_a_float_fill_value_other_than_nan_reads_as_nan(tmp_path):
    path = tmp_path / "f.nc"
    ds = xr.Dataset({"h": ("time", [1.0, -999.0, 3.0])}, coords={"time": [0.0, 0.1, 0.2]})
    ds.to_netcdf(path, encoding={"h": {"_FillValue": -999.0}})
    read = netcdf.read_dataset(path)
    assert _same(netcdf._xarray_read(path), read)
    assert np.isnan(read["h"][1]) and read["h"].encoding["_FillValue"] == -999.0


@pytest.mark.parametrize("case", ["integer fill", "scale factor", "netCDF-3", "unlimited",
                                  "characters"])
def test_what_the_reader_does_not_know_is_left_to_xarray(tmp_path, case):
    path = tmp_path / "r.nc"
    ds = xr.Dataset({"n": ("time", np.array([1, 2, 3], np.int16))},
                    coords={"time": [0.0, 0.1, 0.2]})
    kw: dict = {}
    if case == "integer fill":
        kw["encoding"] = {"n": {"_FillValue": np.int16(2)}}
    elif case == "scale factor":
        ds["n"] = ds["n"] * 0.5
        kw["encoding"] = {"n": {"dtype": "int16", "scale_factor": 0.5}}
    elif case == "netCDF-3":
        kw["format"] = "NETCDF3_64BIT"
    elif case == "unlimited":
        kw["unlimited_dims"] = ["time"]
    else:
        ds["c"] = ("time", np.array(["a", "b", "c"]))
        kw["encoding"] = {"c": {"dtype": "S1"}}
    ds.to_netcdf(path, **kw)
    assert netcdf._netcdf4_read(path) is None
    assert netcdf.read_dataset(path).identical(netcdf._xarray_read(path))


def test_enumerations_and_ragged_arrays_are_left_to_xarray(tmp_path):
    import netCDF4

    path = tmp_path / "types.nc"
    with netCDF4.Dataset(path, "w") as nc:
        nc.createDimension("n", 2)
        kind = nc.createEnumType(np.uint8, "flag_type", {"ok": 1, "bad": 4})
        nc.createVariable("flag", kind, ("n",))[:] = np.array([1, 4], np.uint8)
    assert netcdf._netcdf4_read(path) is None
    path = tmp_path / "ragged.nc"
    with netCDF4.Dataset(path, "w") as nc:
        nc.createDimension("n", 2)
        ragged = nc.createVLType(np.float64, "ragged_type")
        var = nc.createVariable("r", ragged, ("n",))
        var[0], var[1] = np.array([1.0]), np.array([2.0, 3.0])
    assert netcdf._netcdf4_read(path) is None


@pytest.fixture
def remembering():
    netcdf.remember_reads(64 * 2**20)
    yield
    netcdf.remember_reads(None)


def _counted_reads(monkeypatch) -> list:
    reads = []
    read = netcdf._netcdf4_read

    def counted(path):
        reads.append(path)
        return read(path)

    monkeypatch.setattr(netcdf, "_netcdf4_read", counted)
    return reads


def test_a_remembered_file_is_read_once_and_each_reader_gets_its_own_copy(
        tmp_path, monkeypatch, remembering):
    path = tmp_path / "p.nc"
    netcdf.write_dataset(_product(), path)
    reads = _counted_reads(monkeypatch)
    first = netcdf.read_dataset(path)
    first["eta"].values[0, 0] = 1e9  # a reader that changes its dataset in place
    first.attrs["title"] = "changed"
    second = netcdf.read_dataset(path)
    assert len(reads) == 1
    assert second["eta"].values[0, 0] != 1e9 and second.attrs["title"] == "a product"
    assert second.identical(netcdf._netcdf4_read(path))


def test_a_remembered_file_replaced_or_rewritten_is_read_again(tmp_path, monkeypatch,
                                                                 remembering):
    path = tmp_path / "p.nc"
    netcdf.write_dataset(_product(), path)
    reads = _counted_reads(monkeypatch)
    netcdf.read_dataset(path)
    kr = {"units": "1", "long_name": "Kr"}
    # a new file in its place (another inode)
    netcdf.write_dataset(_product().assign(kr=((), 0.3, kr)), path)
    assert float(netcdf.read_dataset(path)["kr"]) == 0.3
    # rewritten in place, the same size: the file's times tell it (set apart here, as a
    # rewrite within the same tick of the file system's clock would not be)
    other = tmp_path / "other.nc"
    netcdf.write_dataset(_product().assign(kr=((), 0.4, kr)), other)
    before = path.stat()
    path.write_bytes(other.read_bytes())
    assert path.stat().st_ino == before.st_ino and path.stat().st_size == before.st_size
    os.utime(path, ns=(before.st_atime_ns, before.st_mtime_ns + 10**9))
    assert float(netcdf.read_dataset(path)["kr"]) == 0.4
    assert len(reads) == 3


def test_reads_beyond_the_memory_are_forgotten_and_none_stops(tmp_path, monkeypatch):
    path = tmp_path / "p.nc"
    netcdf.write_dataset(_product(), path)
    reads = _counted_reads(monkeypatch)
    try:
        netcdf.remember_reads(1000)  # less than the dataset: nothing is kept
        netcdf.read_dataset(path)
        netcdf.read_dataset(path)
        assert len(reads) == 2
    finally:
        netcdf.remember_reads(None)
    netcdf.read_dataset(path)
    assert len(reads) == 3 and netcdf._remembered is None
