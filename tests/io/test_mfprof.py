"""Met-Flow .mfprof reader/writer: the real sample's facts (FORMAT.md §9), exact round trips,
multiplexed files and corrupt files."""

from __future__ import annotations

import warnings
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
from hypothesis import given, settings
from hypothesis import strategies as st

from flumekit.errors import InputError
from flumekit.io.mfprof import (
    MfprofBackendEntrypoint,
    parse_parameters,
    read_mfprof,
    velocity_resolution,
    write_mfprof,
)

SAMPLE = Path(__file__).resolve().parents[2] / ".." / "shared" / "data" / "metflow" / \
    "data_sample.mfprof"
DV = 1.1779237978810106e-3  # FORMAT.md §9


@pytest.fixture(scope="module")
def sample() -> xr.Dataset:
    if not SAMPLE.is_file():
        pytest.skip("shared/data/metflow/data_sample.mfprof not available")
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # the sample must read without any warning
        return read_mfprof(SAMPLE)


# ---------------------------------------------------------------- the real file (FORMAT.md §9)

def test_sample_layout_and_time(sample):
    assert sample.sizes == {"time": 702, "channel": 654}  # 702 valid of 1024 records
    assert sample.attrs["mfprof_records_stored"] == 1024
    np.testing.assert_array_equal(sample["record"].values, np.arange(702))
    t = sample["time"].values
    assert t[0] == 0.0 and t[-1] == 35.05
    np.testing.assert_allclose(np.diff(t), 0.05, rtol=0, atol=1e-12)
    assert sample.attrs["start_time"] == "2022-01-20T17:35:58.4579027"
    assert sample.attrs["mfprof_start_time_filetime"] == 132_871_737_584_579_027


def test_sample_parameters(sample):
    a = sample.attrs
    expected = {"Frequency": 4000000, "SoundSpeed": 1480, "StartChannel": 3.7,
                "ChannelDistance": 0.37, "ChannelWidth": 0.74, "MaximumDepth": 453.99,
                "Angle": 90, "SampleTime": 50, "Iterations": 32, "CyclesPerPulse": 4,
                "Voltage": 150, "GainStart": 3, "GainEnd": 3, "NoiseLevel": 4,
                "RawDataMin": -128, "RawDataMax": 127, "RawDataRange": 256,
                "AmplDataMin": -8192, "AmplDataMax": 8191, "VelocityInterpretingMode": 0,
                "UseMultiplexer": 0, "FirstValidChannel": 0, "LastValidChannel": 653,
                "PeriodEnhNCycles": 4294967295, "Comment": "", "NumberOfCycles": 1,
                "CycleDelay": 0, "Version": 2, "Table": "0"}
    for k, v in expected.items():
        assert a[f"mfprof_{k}"] == v, k
    assert a["mfprof_MeasurementProtocol"].split("\n") == [
        "", "Measurement was stopped by user", "Profiles 702 to 1023 lost and not valid"]
    assert a["velocity_resolution"] == pytest.approx(DV, rel=1e-15)
    assert a["pulse_repetition_frequency"] == pytest.approx(1629.9918500, rel=1e-9)
    assert a["velocity_range"] == pytest.approx(0.30154849226, rel=1e-10)
    assert sample["beam_velocity"].attrs["positive"] == "away_from_transducer"
    assert "not verified" in sample["beam_velocity"].attrs["sign_convention"]


def test_sample_geometry(sample):
    r = sample["distance"].values
    np.testing.assert_allclose(r[[0, 1, 653]], [0.00370, 0.00407, 0.24531], rtol=0, atol=1e-15)


def test_sample_velocity_statistics(sample):
    v = sample["beam_velocity"].values
    assert v.size == 459_108
    assert v.min() == pytest.approx(-0.15077424612876936, rel=1e-14)
    assert v.max() == pytest.approx(0.14841839853300734, rel=1e-14)
    assert v.mean() == pytest.approx(-8.750222896214e-4, rel=1e-11)
    assert v.std() == pytest.approx(1.2416300949544e-2, rel=1e-11)
    assert np.median(v) == 0.0
    assert int(np.rint(v / DV).sum()) == -341_049
    assert int(np.sum(np.rint(v / DV) == -128)) == 1


def test_sample_point_values(sample):
    v = sample["beam_velocity"].values
    assert v[0, 100] == pytest.approx(-0.004711695191524042, rel=1e-14)
    assert v[500, 300] == pytest.approx(0.004711695191524042, rel=1e-14)
    assert v[701, 100] == pytest.approx(-0.0011779237978810106, rel=1e-14)
    assert v[701, 653] == pytest.approx(0.002355847595762021, rel=1e-14)
    assert np.all(v[0, :15] == 0.0)
    assert sample["time"].values[500] == 25.0
    np.testing.assert_array_equal(np.rint(v[0, 100:111] / DV),
                                  [-4, 0, -1, -1, 1, 1, -1, -1, -1, 1, 3])
    m = v.mean(axis=0)
    assert int(np.argmin(m)) == 644 and m.min() == pytest.approx(-6.0893e-3, abs=5e-8)
    assert int(np.argmax(m)) == 388 and m.max() == pytest.approx(3.9147e-3, abs=5e-8)
    np.testing.assert_allclose(m[[100, 300, 653]], [-2.4465e-3, 1.9414e-3, -5.4668e-3],
                               atol=5e-8)


def test_sample_amplitude(sample):
    a = sample["amplitude"].values.astype(np.int64)
    assert (a.min(), a.max(), a.sum()) == (-717, 725, 43_183_048)
    assert a.mean() == pytest.approx(94.0586, abs=5e-5)
    assert (a[0, 100], a[500, 300]) == (87, 85)


def test_sample_xarray_backend(sample):
    ds = xr.open_dataset(SAMPLE, engine="mfprof")
    xr.testing.assert_identical(ds, sample)
    assert MfprofBackendEntrypoint().guess_can_open(SAMPLE)
    assert not MfprofBackendEntrypoint().guess_can_open(Path(__file__))


def test_sample_rewrites_byte_identical(sample, tmp_path):
    out = write_mfprof(tmp_path / "copy.mfprof", sample, n_records=1024)
    assert out.read_bytes() == SAMPLE.read_bytes()


# ---------------------------------------------------------------- round trip (property)

PARAMS = dict(Frequency=2000000, SoundSpeed=1480, StartChannel=20.0, ChannelDistance=0.74,
              ChannelWidth=0.74, MaximumDepth=140.5, SampleTime=86)
text = st.text(st.characters(min_codepoint=32, max_codepoint=126, exclude_characters="\\"),
               max_size=20)


@settings(max_examples=40, deadline=None)
@given(n=st.integers(1, 12), n_ch=st.integers(1, 16), amplitude=st.booleans(),
       data=st.data(), sound=st.integers(1400, 1560), depth=st.integers(5000, 90000),
       freq=st.sampled_from([1000000, 2000000, 4000000, 8000000]),
       comment=st.lists(text, min_size=1, max_size=3), extra=st.integers(0, 3))
def test_round_trip_exact(tmp_path_factory, n, n_ch, amplitude, data, sound, depth, freq,
                          comment, extra):
    """write -> read reproduces counts x ΔV, times and parameters exactly; write again is
    byte-identical."""
    counts = np.array(data.draw(st.lists(st.integers(-128, 127), min_size=n * n_ch,
                                         max_size=n * n_ch))).reshape(n, n_ch)
    steps = np.array(data.draw(st.lists(st.integers(1, 10**8), min_size=n, max_size=n)))
    ticks = np.cumsum(steps) - steps[0]
    params = {**PARAMS, "SoundSpeed": sound, "MaximumDepth": depth / 100, "Frequency": freq,
              "Comment": "\n".join(comment)}
    dv = velocity_resolution(params)
    arrays = {"time": ticks / 1e7, "beam_velocity": counts * dv}
    if amplitude:
        arrays["amplitude"] = np.array(data.draw(st.lists(
            st.integers(-8192, 8191), min_size=n * n_ch, max_size=n * n_ch))).reshape(n, n_ch)
    d = tmp_path_factory.mktemp("rt")
    p1 = write_mfprof(d / "a.mfprof", arrays, params, n_records=n + extra)
    ds = read_mfprof(p1)
    np.testing.assert_array_equal(ds["beam_velocity"].values, counts * dv)
    np.testing.assert_array_equal(ds["time"].values, ticks / 1e7)
    if amplitude:
        np.testing.assert_array_equal(ds["amplitude"].values, arrays["amplitude"])
    else:
        assert "amplitude" not in ds
    for k, v in params.items():
        assert ds.attrs[f"mfprof_{k}"] == v, k
    p2 = write_mfprof(d / "b.mfprof", ds, n_records=n + extra)
    assert p2.read_bytes() == p1.read_bytes()


def test_writer_refuses_out_of_range_and_nan(tmp_path):
    dv = velocity_resolution(PARAMS)
    with pytest.raises(ValueError, match="raw range"):
        write_mfprof(tmp_path / "x.mfprof", {"time": np.array([0.0]),
                                             "beam_velocity": np.array([[200 * dv]])}, PARAMS)
    with pytest.raises(ValueError, match="NaN"):
        write_mfprof(tmp_path / "x.mfprof", {"time": np.array([0.0]),
                                             "beam_velocity": np.array([[np.nan]])}, PARAMS)
    assert not list(tmp_path.iterdir())  # nothing left behind


def test_sign_label_and_angle_correction(tmp_path):
    dv = velocity_resolution(PARAMS)
    arr = {"time": np.array([0.0, 0.1]), "beam_velocity": np.array([[3 * dv], [-2 * dv]])}
    p = write_mfprof(tmp_path / "s.mfprof", arr, {**PARAMS, "Angle": 60})
    ds = read_mfprof(p, positive="towards_transducer")
    assert ds["beam_velocity"].attrs["positive"] == "towards_transducer"
    np.testing.assert_array_equal(ds["beam_velocity"].values, arr["beam_velocity"])  # unchanged
    dc = read_mfprof(p, angle_correction=True)
    np.testing.assert_allclose(dc["beam_velocity"].values,
                               arr["beam_velocity"] / np.sin(np.radians(60)), rtol=1e-15)
    with pytest.raises(ValueError, match="positive"):
        read_mfprof(p, positive="up")


# ---------------------------------------------------------------- multiplexer (FORMAT.md §7)

def test_multiplexed_assignment(tmp_path):
    dv = velocity_resolution(PARAMS)
    cycles, n = 4, 12  # per cycle: socket 1 twice, then socket 3 once
    table = "2\n 1 1 2 90 0 0 0 0 0\n 1 3 1 90 0 0 0 0 0"
    counts = np.arange(n)[:, None] % 100 * np.ones((1, 3))
    p = write_mfprof(tmp_path / "m.mfprof",
                     {"time": np.arange(n) * 0.5, "beam_velocity": counts * dv},
                     {**PARAMS, "UseMultiplexer": 1, "NumberOfCycles": cycles, "Table": table})
    with pytest.raises(InputError, match=r"transducers \[1, 3\]"):
        read_mfprof(p)
    with pytest.warns(UserWarning, match="unverified"):
        one = read_mfprof(p, transducer=1)
        three = read_mfprof(p, transducer=3)
    np.testing.assert_array_equal(one["record"].values, [0, 1, 3, 4, 6, 7, 9, 10])
    np.testing.assert_array_equal(three["record"].values, [2, 5, 8, 11])
    np.testing.assert_array_equal(np.rint(three["beam_velocity"].values[:, 0] / dv), [2, 5, 8, 11])
    bad = write_mfprof(tmp_path / "bad.mfprof",
                       {"time": np.arange(n) * 0.5, "beam_velocity": counts * dv},
                       {**PARAMS, "UseMultiplexer": 1, "NumberOfCycles": 5, "Table": table})
    with pytest.raises(InputError, match="5 cycles x 3 profiles = 15"):
        read_mfprof(bad, transducer=1)


def test_parameter_table_without_backslashes():
    block = b"[UVP_PARAMETER]\nFrequency=4000000\n[MUX_PARAMETER]\nTable=2\n 1 1 1 90 0 0 0 0 0\n" \
            b" 1 2 1 90 0 0 0 0 0\n"
    sec = parse_parameters(block)
    assert sec["MUX_PARAMETER"]["Table"].split("\n")[0] == "2"
    assert len(sec["MUX_PARAMETER"]["Table"].split("\n")) == 3


def test_free_text_that_looks_like_a_number_stays_text():
    # the round trip found it: a one-line Comment "0" came back as the integer 0
    block = b"[UVP_PARAMETER]\nFrequency=4000000\nComment=0\nMeasurementProtocol=1.5\n"
    sec = parse_parameters(block)["UVP_PARAMETER"]
    assert sec["Comment"] == "0" and sec["MeasurementProtocol"] == "1.5"
    assert sec["Frequency"] == 4000000  # numbers elsewhere are still numbers


# ---------------------------------------------------------------- corrupt files

@pytest.fixture()
def good(tmp_path) -> Path:
    dv = velocity_resolution(PARAMS)
    rng = np.random.default_rng(0)
    return write_mfprof(tmp_path / "good.mfprof",
                        {"time": np.arange(6) * 0.086,
                         "beam_velocity": rng.integers(-100, 100, (6, 5)) * dv,
                         "amplitude": rng.integers(0, 500, (6, 5))}, PARAMS, n_records=8)


def _corrupt(path: Path, offset: int, data: bytes) -> Path:
    b = bytearray(path.read_bytes())
    b[offset:offset + len(data)] = data
    out = path.with_name("bad.mfprof")
    out.write_bytes(bytes(b))
    return out


def test_good_fixture_reads(good):
    ds = read_mfprof(good)
    assert ds.sizes == {"time": 6, "channel": 5}  # two unfilled records dropped


@pytest.mark.parametrize("cut, match", [(50, "shorter than the 104-byte header"),
                                        (400, "truncated"),
                                        (-30, None)])
def test_truncated(good, cut, match):
    data = good.read_bytes()
    bad = good.with_name("cut.mfprof")
    bad.write_bytes(data[:cut])
    with pytest.raises(InputError) as e:
        read_mfprof(bad)
    assert str(bad) in str(e.value)
    if match:
        assert match in str(e.value)


def test_corrupt_header_fields(good):
    rec = 16 + 2 * 5 * 2
    cases = [
        (0, b"Not a UVP file!!!!!!", "signature"),
        (64, np.int64(999).tobytes(), "param_offset"),
        (84, np.uint32(rec + 2).tobytes(), "param_offset"),
        (88, np.uint32(6).tobytes(), "ProfileLength"),
        (80, np.uint32(0).tobytes(), "AmplitudeStored"),
        (104 + 16, np.int16(500).tobytes(), "raw Doppler values"),
        (104 + rec + 8, np.int64(0).tobytes(), "not strictly increasing"),
    ]
    for offset, data, match in cases:
        bad = _corrupt(good, offset, data)
        with pytest.raises(InputError, match=match) as e:
            read_mfprof(bad)
        assert str(bad) in str(e.value)


def test_no_valid_record_and_missing_file(good, tmp_path):
    rec = 16 + 2 * 5 * 2
    b = bytearray(good.read_bytes())
    for i in range(8):
        b[104 + i * rec:104 + i * rec + 4] = np.uint32(3).tobytes()
    bad = tmp_path / "none.mfprof"
    bad.write_bytes(bytes(b))
    with pytest.raises(InputError, match="none of the 8 records"):
        read_mfprof(bad)
    with pytest.raises(InputError, match="file not found"):
        read_mfprof(tmp_path / "missing.mfprof")


def test_missing_parameter(good, tmp_path):
    b = good.read_bytes().replace(b"SoundSpeed=1480\n", b"")
    bad = tmp_path / "nosound.mfprof"
    bad.write_bytes(b)
    with pytest.raises(InputError, match="SoundSpeed"):
        read_mfprof(bad)
