"""The second bad-input corpus, reader by reader: files written with the libraries themselves
(npTDMS, h5py, netCDF4, plain text in other encodings), each with one fault, read through the
instrument readers. Each case is a clear error naming the file and what is wrong (the
dataset, channel or line and the values that disagree), or the right record."""

from pathlib import Path

import numpy as np
import pytest

from flumekit.errors import InputError
from flumekit.io.instruments import read_flap, read_probes

PROBES = ("WP1", "WP2", "WP3", "WP4")
FS = 25.0  # [Hz]
N = 500


def waves(n: int = N) -> np.ndarray:
    """(probe, time) voltages of a 2 s wave at four probes."""
    t = np.arange(n) / FS
    return np.array([1.0 + 0.3 * np.sin(2 * np.pi * t / 2.0 + k) for k in range(4)])


# ---- TDMS: the file's own timing ---------------------------------------------------------

def _tdms(path: Path, x: np.ndarray, increment: float | list | None = None, start=None,
          time: bool = False) -> Path:
    from nptdms import ChannelObject, TdmsWriter

    objs = []
    if time:
        objs.append(ChannelObject("Wave probes", "time", np.arange(x.shape[1]) / FS,
                                  {"unit_string": "s"}))
    for j, name in enumerate(PROBES):
        props = {"unit_string": "V"}
        inc = increment[j] if isinstance(increment, list) else increment
        if inc is not None:
            props["wf_increment"] = inc
        st = start[j] if isinstance(start, list) else start
        if st is not None:
            props["wf_start_time"] = np.datetime64(st, "us")
        objs.append(ChannelObject("Wave probes", name, x[j], props))
    with TdmsWriter(path) as w:
        w.write_segment(objs)
    return path


TDMS = {"format": "tdms", "group": "Wave probes"}


def test_tdms_increment_contradicting_the_declared_rate_is_an_error(tmp_path):
    path = _tdms(tmp_path / "p.tdms", waves(), increment=0.02)  # 50 Hz, 25 declared
    with pytest.raises(InputError) as e:
        read_probes(path, PROBES, FS, {**TDMS, "time": "rate"})
    msg = str(e.value)
    assert "p.tdms" in msg and "Wave probes/WP1 wf_increment" in msg
    assert "0.02 s" in msg and "25 Hz" in msg


def test_tdms_increment_gives_the_time_when_none_is_declared(tmp_path):
    path = _tdms(tmp_path / "p.tdms", waves(), increment=1 / FS,
                 start="2024-05-01T10:00:00")
    ds = read_probes(path, PROBES, FS, TDMS)  # no 'time' channel, no time = "rate"
    np.testing.assert_allclose(ds["time"].values, np.arange(N) / FS, rtol=0, atol=1e-12)
    assert ds["time"].attrs["record_start"] == "2024-05-01T10:00:00Z"
    # and without the increment there is no time to take: the missing channel is named
    path = _tdms(tmp_path / "q.tdms", waves())
    with pytest.raises(InputError, match="no channel 'time'"):
        read_probes(path, PROBES, FS, TDMS)


def test_tdms_channels_with_different_timing_are_not_one_record(tmp_path):
    path = _tdms(tmp_path / "p.tdms", waves(), increment=[0.04, 0.04, 0.02, 0.04])
    with pytest.raises(InputError, match=r"wf_increment disagree.*WP3 0.02 s"):
        read_probes(path, PROBES, FS, {**TDMS, "time": "rate"})
    starts = ["2024-05-01T10:00:00"] * 3 + ["2024-05-01T11:00:00"]
    path = _tdms(tmp_path / "s.tdms", waves(), increment=0.04, start=starts)
    with pytest.raises(InputError, match=r"wf_start_time disagree.*WP4 2024-05-01T11:00:00Z"):
        read_probes(path, PROBES, FS, {**TDMS, "time": "rate"})


def test_tdms_channel_shorter_than_its_siblings_is_refused(tmp_path):
    from nptdms import ChannelObject, TdmsWriter

    x = waves()
    path = tmp_path / "p.tdms"
    with TdmsWriter(path) as w:  # the last segment lost one channel's data
        w.write_segment([ChannelObject("Wave probes", n, x[j, :300], {"unit_string": "V"})
                         for j, n in enumerate(PROBES)])
        w.write_segment([ChannelObject("Wave probes", n, x[j, 300:], {"unit_string": "V"})
                         for j, n in enumerate(PROBES[:3])])
    with pytest.raises(InputError) as e:
        read_probes(path, PROBES, FS, {**TDMS, "time": "rate"})
    assert "'Wave probes/WP4' 300" in str(e.value) and "the others 500" in str(e.value)


# ---- HDF5 and netCDF: shape and dtype ----------------------------------------------------

def _h5(path: Path, **datasets) -> Path:
    import h5py

    with h5py.File(path, "w") as h:
        h.create_dataset("probes/time", data=np.arange(N) / FS).attrs["units"] = "s"
        for name, data in datasets.items():
            h.create_dataset(f"probes/{name}", data=data).attrs["units"] = "V"
    return path


H5 = {"format": "hdf5", "group": "probes"}


def test_hdf5_column_vectors_are_squeezed(tmp_path):
    x = waves()
    path = _h5(tmp_path / "r.h5", **{n: x[j][:, None] for j, n in enumerate(PROBES)})
    ds = read_probes(path, PROBES, FS, H5)
    np.testing.assert_array_equal(ds["probe_voltage"].values, x)


@pytest.mark.parametrize("case", ["n2", "all_probes", "string", "compound"])
def test_hdf5_dataset_of_the_wrong_shape_or_dtype_is_named(tmp_path, case):
    x = waves()
    data = {n: x[j] for j, n in enumerate(PROBES)}
    if case == "n2":
        data["WP2"] = np.column_stack([x[1], x[1]])
        expect = r"'probes/WP2' has shape \(500, 2\); expected .*shape \(n,\)"
    elif case == "all_probes":
        data = {"WP1": x.T, **{n: x[j] for j, n in enumerate(PROBES) if n != "WP1"}}
        expect = r"'probes/WP1' has shape \(500, 4\).*4 columns: all channels in one dataset"
    elif case == "string":
        data["WP3"] = np.array([f"{v:.4f}".encode() for v in x[2]])
        expect = r"'probes/WP3' holds text \(dtype \|S6\)"
    else:
        rec = np.zeros(N, dtype=[("t", "f8"), ("v", "f8")])
        rec["v"] = x[3]
        data["WP4"] = rec
        expect = r"'probes/WP4' is a compound dataset \(fields \['t', 'v'\]\)"
    path = _h5(tmp_path / "r.h5", **data)
    with pytest.raises(InputError, match=expect) as e:
        read_probes(path, PROBES, FS, H5)
    assert str(e.value).startswith(str(path))


def test_integers_are_counts_not_volts(tmp_path):
    """int16 ADC counts declared in volts are refused; integer encoder counts are read."""
    import h5py

    x = waves()
    counts = np.round(x * 1000).astype(np.int16)
    path = _h5(tmp_path / "r.h5", **{n: counts[j] for j, n in enumerate(PROBES)})
    with pytest.raises(InputError, match=r"'probes/WP1' holds integers \(dtype int16\), but "
                                         r"it is a voltage in \[V\]"):
        read_probes(path, PROBES, FS, H5)
    enc = np.round(2000 * np.sin(np.arange(N) / FS)).astype(np.int32)
    flap = tmp_path / "flap.h5"
    with h5py.File(flap, "w") as h:
        h.create_dataset("time", data=np.arange(N) / FS).attrs["units"] = "s"
        h.create_dataset("encoder", data=enc).attrs["units"] = "counts"
        h.create_dataset("pressure", data=1e4 * x[0]).attrs["units"] = "Pa"
    ds = read_flap(flap, FS, {"format": "hdf5"})
    np.testing.assert_array_equal(ds["encoder_counts"].values, enc)


def test_netcdf_variable_with_two_dimensions_is_named(tmp_path):
    import netCDF4

    path = tmp_path / "p.nc"
    with netCDF4.Dataset(path, "w") as nc:
        nc.createDimension("t", N)
        nc.createDimension("probe", 4)
        t = nc.createVariable("time", "f8", ("t",))
        t[:], t.units = np.arange(N) / FS, "s"
        v = nc.createVariable("eta", "f8", ("t", "probe"))
        v[:], v.units = waves().T, "V"
    cols = {n: "eta" for n in PROBES}
    with pytest.raises(InputError, match=r"'eta' has shape \(500, 4\); expected one dataset "
                                         r"per channel of shape \(n,\)"):
        read_probes(path, PROBES, FS, {"format": "netcdf", "columns": cols})


# ---- a file's real format ------------------------------------------------------------------

@pytest.mark.parametrize("real,declared,name", [("hdf5", "csv", "an HDF5"),
                                               ("tdms", "hdf5", "a TDMS"),
                                               ("netcdf", "tdms", "a netCDF (classic)"),
                                               ("hdf5", "tdms", "an HDF5")])
def test_real_format_from_the_first_bytes(tmp_path, real, declared, name):
    import netCDF4

    path = tmp_path / "probes.dat"
    if real == "hdf5":
        _h5(path, **{n: waves()[j] for j, n in enumerate(PROBES)})
    elif real == "tdms":
        _tdms(path, waves(), increment=1 / FS)
    else:
        with netCDF4.Dataset(path, "w", format="NETCDF3_CLASSIC") as nc:
            nc.createDimension("t", 3)
    with pytest.raises(InputError) as e:
        read_probes(path, PROBES, FS, {"format": declared})
    assert f"this is {name}" in str(e.value)
    assert f'declare format = "{real}"' in str(e.value)


def test_a_workbook_declared_as_csv(tmp_path):
    import zipfile

    path = tmp_path / "probes.csv"
    with zipfile.ZipFile(path, "w") as z:  # what Excel's "save" writes
        z.writestr("xl/workbook.xml", "<workbook/>")
    with pytest.raises(InputError, match=r"probes.csv: this is a ZIP archive \(an Excel .xlsx "
                                         r"workbook\?\), which no dialect reads"):
        read_probes(path, PROBES, FS)


# ---- text: encodings, time zones, decimal commas -------------------------------------------

def _csv(path: Path, rows: list[str], encoding: str = "utf-8") -> Path:
    path.write_bytes("\n".join(rows).encode(encoding) + b"\n")
    return path


def _rows(stamps, x):
    return [f"{s};" + ";".join(f"{v:.5f}" for v in x[:, k]) for k, s in enumerate(stamps)]


def test_encoding_undecodable_byte_names_the_line_and_the_key(tmp_path):
    x = waves()
    t = np.arange(N) / FS
    rows = ["Messung: Wellenhöhe", "time [s];" + ";".join(f"{p} [V]" for p in PROBES)]
    rows += _rows([f"{v:.2f}" for v in t], x)
    path = _csv(tmp_path / "p.csv", rows, "cp1252")
    d = {"delimiter": ";", "skip_lines": 1}
    with pytest.raises(InputError) as e:
        read_probes(path, PROBES, FS, d)
    assert "line 1" in str(e.value) and "0xf6" in str(e.value)
    assert 'encoding = "cp1252"' in str(e.value)
    for enc in ("cp1252", "latin-1"):
        ds = read_probes(path, PROBES, FS, {**d, "encoding": enc})
        np.testing.assert_allclose(ds["probe_voltage"].values, x, atol=5e-6)
    # UTF-8 with a byte-order mark is the default
    path = _csv(tmp_path / "u.csv", rows, "utf-8-sig")
    assert read_probes(path, PROBES, FS, d).sizes["time"] == N


def test_stamps_with_utc_offsets_across_a_dst_change(tmp_path):
    """2024-03-31, Europe/Lisbon... Berlin: 01:59:59.96+01:00 is followed by 03:00:00+02:00
    (the same instant as 02:00:00+01:00): the time axis runs on without a jump."""
    import pandas as pd

    x = waves()
    utc = pd.Timestamp("2024-03-31T00:59:50Z") + pd.to_timedelta(np.arange(N) / FS, "s")
    local = utc.tz_convert("Europe/Berlin")
    stamps = [s.isoformat(timespec="milliseconds") for s in local]
    assert stamps[0].endswith("+01:00") and stamps[-1].endswith("+02:00")
    rows = ["stamp;" + ";".join(f"{p} [V]" for p in PROBES)] + _rows(stamps, x)
    path = _csv(tmp_path / "p.csv", rows)
    ds = read_probes(path, PROBES, FS, {"delimiter": ";", "time": "stamp"})
    np.testing.assert_allclose(ds["time"].values, np.arange(N) / FS, rtol=0, atol=1e-9)
    assert ds["time"].attrs["record_start"] == "2024-03-31T00:59:50Z"
    # the same instants as naive local stamps need the zone they were written in
    naive = [s.strftime("%Y-%m-%d %H:%M:%S.%f")[:-3] for s in local]
    path = _csv(tmp_path / "n.csv", ["stamp;" + ";".join(f"{p} [V]" for p in PROBES)]
                + _rows(naive, x))
    with pytest.raises(InputError, match="sampling interval 3600.04 s.*daylight-saving change"
                                         r"\? Declare timezone"):
        read_probes(path, PROBES, FS, {"delimiter": ";", "time": "stamp"})
    ds = read_probes(path, PROBES, FS, {"delimiter": ";", "time": "stamp",
                                        "timezone": "Europe/Berlin"})
    np.testing.assert_allclose(ds["time"].values, np.arange(N) / FS, rtol=0, atol=1e-9)
    assert ds["time"].attrs["record_start"] == "2024-03-31T00:59:50Z"


def test_autumn_repeated_hour_resolved_by_order_and_skipped_hour_named(tmp_path):
    import pandas as pd

    x = waves()
    utc = pd.Timestamp("2024-10-27T00:59:55Z") + pd.to_timedelta(np.arange(N) / FS, "s")
    naive = [s.strftime("%Y-%m-%d %H:%M:%S.%f")[:-3] for s in utc.tz_convert("Europe/Berlin")]
    head = ["stamp;" + ";".join(f"{p} [V]" for p in PROBES)]
    path = _csv(tmp_path / "a.csv", head + _rows(naive, x))
    ds = read_probes(path, PROBES, FS, {"delimiter": ";", "time": "stamp",
                                        "timezone": "Europe/Berlin"})
    np.testing.assert_allclose(ds["time"].values, np.arange(N) / FS, rtol=0, atol=1e-9)
    utc = pd.Timestamp("2024-03-31T00:59:50Z") + pd.to_timedelta(np.arange(N) / FS, "s")
    spring = [s.strftime("%Y-%m-%d %H:%M:%S.%f")[:-3] for s in utc.tz_convert("Europe/Berlin")]
    bad = spring[:10] + ["2024-03-31 02:30:00.000"] + spring[11:]
    path = _csv(tmp_path / "b.csv", head + _rows(bad, x))
    with pytest.raises(InputError, match=r"line 12.*does not exist in Europe/Berlin"):
        read_probes(path, PROBES, FS, {"delimiter": ";", "time": "stamp",
                                       "timezone": "Europe/Berlin"})


def test_undeclared_decimal_comma_after_a_comment_preamble(tmp_path):
    x = waves()
    t = np.arange(N) / FS
    rows = ["# LabVIEW export", "# channels in volts",
            "time [s];" + ";".join(f"{p} [V]" for p in PROBES), "# start"]
    rows += [f"{a:.2f};".replace(".", ",") + ";".join(f"{v:.5f}".replace(".", ",")
                                                      for v in x[:, k])
             for k, a in enumerate(t)]
    path = _csv(tmp_path / "p.csv", rows)
    with pytest.raises(InputError) as e:
        read_probes(path, PROBES, FS, {"delimiter": ";", "comment": "#"})
    msg = str(e.value)
    assert ", line 5:" in msg and "decimal = ','" in msg  # the first data line, not line 4
    ds = read_probes(path, PROBES, FS, {"delimiter": ";", "comment": "#", "decimal": ","})
    np.testing.assert_allclose(ds["probe_voltage"].values, x, atol=5e-6)


def test_bad_stamp_after_interleaved_comments_names_its_line(tmp_path):
    x = waves(6)
    stamps = [f"2024-05-01T10:00:00.{4 * k:02d}" for k in range(6)]
    stamps[4] = "yesterday"
    rows = ["stamp;" + ";".join(f"{p} [V]" for p in PROBES)]
    body = _rows(stamps, x)
    rows += body[:2] + ["# probe 3 re-zeroed"] + body[2:]
    path = _csv(tmp_path / "p.csv", rows)
    with pytest.raises(InputError, match=r", line 7: time column 'stamp': 'yesterday'"):
        read_probes(path, PROBES, FS, {"delimiter": ";", "time": "stamp", "comment": "#"})


def test_a_folder_where_a_file_should_be(tmp_path):
    (tmp_path / "probes.csv").mkdir()
    with pytest.raises(InputError, match="is a folder, not a file"):
        read_probes(tmp_path / "probes.csv", PROBES, FS)
