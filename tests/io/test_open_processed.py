"""Opening a stage's runs (flumekit.open_processed): the dataset xarray's concatenation of the
files gives, read straight into the stacked arrays (no run held in memory beside them); the
HDF5 reader (h5py, attributes decoded from the object headers' bytes) describes a file as the
netCDF4 library does, and leaves what it does not know, or a damaged header, to the netCDF4
library."""

import tracemalloc

import numpy as np
import pytest
import xarray as xr

from flumekit.errors import InputError
from flumekit.io.netcdf import read_dataset
from flumekit.io.processed import open_processed
from flumekit.io.run_files import Hdf5Runs, Netcdf4Runs, open_runs

N_VARS = 8


def _run(i: int, n: int, freq: np.ndarray, with_extra: bool) -> xr.Dataset:
    """One run: records of ``n`` samples at 100 Hz, a spectrum on its own frequencies, an
    integer flag record, scalar run coordinates; ``with_extra`` adds a variable the other
    runs lack."""
    rng = np.random.default_rng(i)
    t = np.arange(n) / 100.0
    ds = xr.Dataset(
        {f"record{k}": ("time", rng.standard_normal(n), {"units": "m", "long_name": f"r{k}"})
         for k in range(N_VARS)},
        coords={"time": ("time", t, {"units": "s"}), "run": f"run{i}",
                "wave_period": 2.0 + i, "frequency": ("frequency", freq, {"units": "Hz"})})
    ds["flag"] = ("time", (rng.random(n) > 0.9).astype(np.int8), {"units": "1"})
    ds["spectrum"] = ("frequency", rng.random(freq.size), {"units": "m2 s"})
    ds["mean_power"] = ((), float(i), {"units": "W", "note": "same" if i else "first"})
    if with_extra:
        ds["extra"] = ("time", np.full(n, float(i)), {"units": "1"})
    ds.attrs = {"title": f"run {i}", "Conventions": "CF-1.8"}
    return ds


def _write_runs(folder, lengths):
    """Runs of the given record lengths; the frequencies of odd runs fall between those of
    even runs (not a contiguous stretch of their union), run 1 lacks nothing, run 2 has an
    extra variable."""
    return _write(folder, [_run(i, n, np.arange(5) * 0.1 + (0.05 if i % 2 else 0.0),
                                with_extra=i == 2) for i, n in enumerate(lengths)])


def _write(folder, runs, axes=("time", "frequency")) -> list:
    """Write the runs' datasets as netCDF-4 files (dimension coordinates ``axes`` without a
    fill value, as flumekit writes them)."""
    folder.mkdir()
    files = []
    for i, ds in enumerate(runs):
        path = folder / f"run{i}.nc"
        ds.to_netcdf(path, engine="netcdf4",
                     encoding={name: {"_FillValue": None} for name in axes})
        files.append(path)
    return files


def _concat(files) -> xr.Dataset:
    """xarray's concatenation of the runs, the dataset open_processed must give."""
    return xr.concat([read_dataset(f) for f in files], dim="run", join="outer",
                     combine_attrs="drop_conflicts", coords="different", compat="equals")


def test_open_processed_is_xarrays_concatenation_of_the_runs(tmp_path):
    files = _write_runs(tmp_path / "stage", [300, 500, 400, 500])
    got = open_processed(tmp_path, "stage")
    want = _concat(files)
    xr.testing.assert_identical(got, want)
    for name in got.variables:
        assert got[name].dtype == want[name].dtype, name
    # padding where a run is shorter or lacks a variable: NaN (the 8-bit integer flags became
    # 32-bit floats, as xarray promotes them)
    assert got.sizes["time"] == 500 and got.sizes["frequency"] == 10
    assert np.isnan(got["record0"].values[0, 300:]).all()
    assert got["flag"].dtype == np.float32 and np.isnan(got["flag"].values[0, 300:]).all()
    assert np.isnan(got["extra"].values[[0, 1, 3]]).all()
    np.testing.assert_array_equal(got["extra"].values[2, :400], 2.0)
    assert "note" not in got["mean_power"].attrs  # the runs disagree: dropped


def test_runs_are_read_straight_into_the_stacked_arrays(tmp_path):
    """Memory at its peak is the stacked dataset and little more: a run's values are read and
    placed one variable at a time, not every run read first and then copied (which needs the
    records of every run twice)."""
    lengths = [20_000, 30_000, 25_000, 30_000, 15_000, 30_000]
    _write_runs(tmp_path / "stage", lengths)
    payload = sum(n * (N_VARS + 2) * 8 for n in lengths)  # the runs' records as read [bytes]
    open_processed(tmp_path, "stage")  # imports and caches warmed outside the measurement
    tracemalloc.start()
    try:
        ds = open_processed(tmp_path, "stage")
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    # beside the result: the coordinates' union (every run's time axis once) and one
    # variable of one run; every run held at once would add the whole payload
    assert peak - ds.nbytes < 0.35 * payload, (peak, ds.nbytes, payload)


def _rich_run(i: int) -> xr.Dataset:
    """A run with every kind of variable and attribute the pipeline writes, and more."""
    n = 50 + 10 * i
    t = np.arange(n) / 100.0
    many = {f"note{k}": f"attribute {k}" for k in range(10)}  # stored outside the header
    more = {f"extra{k}": float(k) for k in range(40)}  # names indexed in a B-tree of nodes
    ds = xr.Dataset(
        {"theta": ("time", np.sin(t), {"units": "rad", "long_name": "angle",
                                       "valid_range": np.array([-1.0, 1.0])}),
         "single": ("time", t.astype(np.float32), {"units": "m", "scale": np.float32(2.0)}),
         "counts": ("time", np.arange(n, dtype=np.int16), {"units": "1"}),
         "flag": ("time", np.ones(n, np.int8), {"flag_values": np.array([1, 4], np.int8),
                                               "flag_meanings": "pass fail"}),
         "field": (("time", "probe"), np.ones((n, 3)), {"units": "m", **many}),
         "bins": ("bin", np.arange(4.0), {"units": "1", **more}),  # a dimension without
         # coordinate
         "text": ("time", t, {"units": "m", "probes": ["a", "bb"],  # a list of strings
                              "comment": "déjà vu"}),  # not ASCII: a variable-length string
         "mean_power": ((), float(i), {"units": "W", "fit": np.int32(3)})},
        coords={"time": ("time", t, {"units": "s", "standard_name": "time"}),
                "probe": ("probe", [0.0, 0.6, 0.9], {"units": "m"}),
                "run": f"run{i}", "repeat": np.int32(i)})
    ds.attrs = {"title": f"run {i}", "Conventions": "CF-1.8", "cutoff": 4.0,
                "orders": np.array([1, 2, 3], np.int32), "names": ["x", "y"],
                **{f"global{k}": k for k in range(10)}}
    return ds


def test_the_hdf5_reader_describes_files_as_the_netcdf4_library_does(tmp_path):
    files = _write(tmp_path / "stage", [_rich_run(i) for i in range(3)], ("time", "probe"))
    with open_runs(files) as fast, Netcdf4Runs(files) as ref:
        assert isinstance(fast, Hdf5Runs)
        for i, ((got, got_attrs, got_coords), (want, want_attrs, want_coords)) in enumerate(
                zip(fast.metas, ref.metas)):
            assert list(got) == list(want) and got_coords == want_coords
            for name in want:
                (dims, shape, attrs, fill, dtype), w = got[name], want[name]
                assert (dims, tuple(shape), dtype) == (w[0], tuple(w[1]), w[4]), name
                assert list(attrs) == list(w[2]), name
                for key, value in w[2].items():
                    assert type(attrs[key]) is type(value), (name, key)
                    np.testing.assert_array_equal(attrs[key], value)
                    assert np.asarray(attrs[key]).dtype == np.asarray(value).dtype
                np.testing.assert_array_equal(fill, w[3])
                values, expected = fast.values(i, name), ref.values(i, name)
                assert values.dtype == expected.dtype, name
                np.testing.assert_array_equal(values, expected)
            assert list(got_attrs) == list(want_attrs)
            for key, value in want_attrs.items():
                assert type(got_attrs[key]) is type(value), key
                np.testing.assert_array_equal(got_attrs[key], value)


def test_the_stack_of_such_files_is_still_xarrays_concatenation(tmp_path):
    files = _write(tmp_path / "stage", [_rich_run(i) for i in range(3)], ("time", "probe"))
    got = open_processed(tmp_path, "stage")
    xr.testing.assert_identical(got, _concat(files))
    assert np.isnan(got["theta"].values[0, 50:]).all()


def test_a_file_with_a_group_is_read_by_the_netcdf4_library(tmp_path):
    runs = [_rich_run(i) for i in range(2)]
    files = _write(tmp_path / "stage", runs, ("time", "probe"))
    xr.Dataset({"x": ("y", [1.0, 2.0])}).to_netcdf(files[1], mode="a", group="extra")
    with open_runs(files) as runs_read:
        assert isinstance(runs_read, Netcdf4Runs)
    xr.testing.assert_identical(open_processed(tmp_path, "stage"), _concat(files))


@pytest.mark.parametrize("text", [b"pass fail", b"attribute 3"])
def test_a_damaged_header_is_no_silent_wrong_attribute(tmp_path, text):
    """A byte changed in an attribute stored in an object header (``pass fail``) or in the
    heap of a variable's many attributes (``attribute 3``): the checksum no longer matches,
    the HDF5 reader declines and the netCDF4 library refuses the file as HDF5 does."""
    files = _write(tmp_path / "stage", [_rich_run(i) for i in range(2)], ("time", "probe"))
    data = bytearray(files[1].read_bytes())
    at = data.index(text)
    data[at:at + 4] = text[:4].upper()
    files[1].write_bytes(bytes(data))
    with pytest.raises(Exception) as caught:
        open_processed(tmp_path, "stage")
    assert text[:4].upper().decode() not in str(caught.value)


def test_the_runs_scalars_stack_as_a_campaign_summary_concatenates_them(tmp_path):
    # the summaries' way: every variable without a dimension, each along run (a coordinate too
    # where every run has the same value), as xr.concat(..., coords="all") gives it; the
    # records are never read
    from flumekit.io.processed import stack_files

    runs = [_run(i, 300 + 100 * i, np.arange(5) * 0.1, with_extra=False) for i in range(3)]
    for ds in runs:
        ds.coords["repeat"] = np.int32(0)  # equal in every run: stacked all the same
        ds.attrs["flumekit_warnings"] = f"warning of {ds.attrs['title']}"
    files = _write(tmp_path / "stage", runs)
    attrs: list[dict] = []
    got = stack_files(files, scalars=True, coords="all", run_attrs=attrs)
    rows = []
    for f in files:
        ds = read_dataset(f)
        rows.append(ds[[v for v in ds.data_vars if ds[v].ndim == 0]].expand_dims("run"))
    want = xr.concat(rows, dim="run", coords="all", compat="override")
    want.attrs = got.attrs
    want["mean_power"].attrs.pop("note")  # the runs disagree: dropped, not the first run's
    xr.testing.assert_identical(got, want)
    assert set(got.dims) == {"run"} and got["repeat"].dims == ("run",)
    assert [a["flumekit_warnings"] for a in attrs] == [f"warning of run {i}" for i in range(3)]


def test_text_attributes_read_as_the_netcdf_library_does(tmp_path):
    """ASCII (stored as characters), UTF-8 (a string array of one), absent; netCDF-3 too."""
    import netCDF4

    from flumekit.io.run_files import text_attributes

    texts = ["run T2: 12 cycles, Kr = 0.2", "θ ± 0.1 rad\nsecond line", None]
    paths = []
    for i, text in enumerate(texts):
        for fmt in ("NETCDF4", "NETCDF3_64BIT"):
            path = tmp_path / f"{i}_{fmt}.nc"
            xr.Dataset(attrs={} if text is None else {"note": text}).to_netcdf(path, format=fmt)
            paths.append(path)
    expected = []
    for p in paths:
        with netCDF4.Dataset(p) as nc:
            expected.append(getattr(nc, "note", None))
    assert text_attributes(paths, "note") == expected == [t for t in texts for _ in range(2)]


def test_one_run_is_opened_by_its_id_though_the_id_holds_dots(tmp_path):
    # run ids hold the condition ("T3.50_H0.250_r0"): the dots are no file suffix
    (files,) = [_write(tmp_path / "waves", [_run(0, 5, np.arange(3) * 0.1, False)])]
    files[0].rename(tmp_path / "waves" / "T3.50_H0.250_r0.nc")
    ds = open_processed(tmp_path, "waves/T3.50_H0.250_r0")
    assert "run" not in ds.dims and ds["record0"].shape == (5,)
    assert open_processed(tmp_path, "waves/T3.50_H0.250_r0.nc").identical(ds)
    with pytest.raises(InputError, match="no processed dataset here"):
        open_processed(tmp_path, "waves/T3.50_H0.250_r1")
