"""Raw CSV readers: correct conversion, and clear errors for every kind of malformed file."""

import numpy as np
import pytest

from flumekit.errors import InputError
from flumekit.io.instruments import read_calibration, read_flap, read_probes

PROBES = ("WP1", "WP2")


def write(path, text):
    path.write_text(text)
    return path


def probes_csv(tmp_path, rows=5, header="time [s],WP1 [V],WP2 [V]"):
    lines = [header] + [f"{i * 0.04:.2f},{1 + i * 0.1:.3f},{2 - i * 0.1:.3f}" for i in range(rows)]
    return write(tmp_path / "probes.csv", "\n".join(lines) + "\n")


def test_reads_probes_in_si(tmp_path):
    p = probes_csv(tmp_path, header="time [ms],WP1 [mV],WP2 [V]")
    text = p.read_text().splitlines()
    text[1:] = [f"{i * 40},{1000 + i * 100},{2 - i * 0.1:.3f}" for i in range(5)]
    write(p, "\n".join(text))  # no final line feed, like many loggers
    ds = read_probes(p, PROBES, 25.0)
    assert ds.probe_voltage.dims == ("probe", "time")
    np.testing.assert_allclose(ds.time, np.arange(5) * 0.04)
    np.testing.assert_allclose(ds.probe_voltage.sel(probe="WP1"), 1 + np.arange(5) * 0.1)
    assert ds.probe_voltage.attrs["units"] == "V"


def test_reads_flap_pressure_in_pascal(tmp_path):
    p = write(tmp_path / "flap.csv", "time [s],encoder [counts],pressure [bar]\n"
              "0.00,0,0.5\n0.01,3,0.25\n0.02,-2,0.0\n")
    ds = read_flap(p, 100.0)
    np.testing.assert_allclose(ds.chamber_pressure, [5e4, 2.5e4, 0.0])
    assert ds.encoder_counts.dtype.kind == "i"


@pytest.mark.parametrize("mutate, message", [
    (lambda t: t[: t.rindex(",")], r"line 6.*2 fields, expected 3.*truncated"),
    (lambda t: t.replace("1.200", "1.2a0"), r"line 4.*'1.2a0' is not a number"),
    (lambda t: t.replace("1.200", "nan"), r"line 4.*non-finite"),
    (lambda t: t.replace("0.08,", "0.02,"), r"line 4.*time is not increasing"),
    (lambda t: t.replace("WP2 [V]", "WP3 [V]"), r"unknown probe column.*WP3"),
    (lambda t: t.replace(",WP2 [V]", "").replace(",2.", ",X"), r"WP2|fields"),
    (lambda t: t.replace("WP1 [V]", "WP1 [furlong]"), r"unknown unit \[furlong\]"),
    (lambda t: t.replace("WP1 [V]", "WP1 [Pa]"), r"WP1.*expected a voltage unit"),
    (lambda t: t.replace("time [s]", "time"), r"line 1.*name \[unit\]"),
    (lambda t: t.split("\n")[0] + "\n", r"no data rows"),
    (lambda t: "", r"empty"),
])
def test_malformed_probe_files_name_file_and_problem(tmp_path, mutate, message):
    p = probes_csv(tmp_path)
    write(p, mutate(p.read_text()))
    with pytest.raises(InputError, match=message) as e:
        read_probes(p, PROBES, 25.0)
    assert str(p) in str(e.value)


def test_missing_probe_column(tmp_path):
    p = write(tmp_path / "probes.csv", "time [s],WP1 [V]\n0.0,1\n0.04,2\n")
    with pytest.raises(InputError, match=r"missing column 'WP2'"):
        read_probes(p, PROBES, 25.0)


def test_wrong_sampling_rate(tmp_path):
    p = probes_csv(tmp_path)
    with pytest.raises(InputError, match=r"does not match the declared sampling rate 100 Hz"):
        read_probes(p, PROBES, 100.0)


def test_missing_file(tmp_path):
    with pytest.raises(InputError, match="file not found"):
        read_probes(tmp_path / "nope.csv", PROBES, 25.0)


def test_binary_garbage(tmp_path):
    p = tmp_path / "probes.csv"
    p.write_bytes(b"\x89PNG\r\n\x1a\n\xff\xfe\x00")
    with pytest.raises(InputError):
        read_probes(p, PROBES, 25.0)


def test_non_integer_encoder_counts(tmp_path):
    p = write(tmp_path / "flap.csv",
              "time [s],encoder [counts],pressure [Pa]\n0.00,0.5,1\n0.01,1,1\n")
    with pytest.raises(InputError, match="integers"):
        read_flap(p, 100.0)


def test_calibration_needs_two_levels(tmp_path):
    p = write(tmp_path / "cal.csv", "level [m],WP1 [V],WP2 [V]\n0.0,1,2\n0.0,1,2\n")
    with pytest.raises(InputError, match="two distinct levels"):
        read_calibration(p, PROBES)


def test_bom_crlf_and_trailing_blank_lines_are_accepted(tmp_path):
    p = probes_csv(tmp_path)
    text = p.read_text().replace("\n", "\r\n") + "\r\n\r\n"
    p.write_bytes(b"\xef\xbb\xbf" + text.encode())
    ds = read_probes(p, PROBES, 25.0)
    np.testing.assert_allclose(ds.probe_voltage.sel(probe="WP2"), 2 - np.arange(5) * 0.1)


def test_file_cut_inside_its_last_field_is_refused(tmp_path):
    p = probes_csv(tmp_path)  # every value written with three decimals
    p.write_text(p.read_text().rstrip("\n")[:-1])  # "1.600" -> "1.60", no final line feed
    with pytest.raises(InputError, match=r"line 6.*'1.60'.*truncated"):
        read_probes(p, PROBES, 25.0)
    p.write_text(p.read_text() + "0")  # whole again, still without a final line feed: fine
    assert read_probes(p, PROBES, 25.0).probe_voltage.shape == (2, 5)


def test_semicolon_file_names_the_delimiter(tmp_path):
    p = probes_csv(tmp_path)
    p.write_text(p.read_text().replace(",", ";"))
    with pytest.raises(InputError, match=r"line 1.*delimiter = ';'") as e:
        read_probes(p, PROBES, 25.0)
    assert str(p) in str(e.value)
    ds = read_probes(p, PROBES, 25.0, {"delimiter": ";"})
    assert ds.probe_voltage.shape == (2, 5)


def test_decimal_comma_without_declaration_is_explained(tmp_path):
    p = write(tmp_path / "probes.csv", "time [s];WP1 [V];WP2 [V]\n0,00;1,5;2,5\n0,04;1,6;2,4\n")
    with pytest.raises(InputError, match=r"line 2.*decimal = ','"):
        read_probes(p, PROBES, 25.0, {"delimiter": ";"})
    ds = read_probes(p, PROBES, 25.0, {"delimiter": ";", "decimal": ","})
    np.testing.assert_allclose(ds.probe_voltage.sel(probe="WP1"), [1.5, 1.6])


def test_tab_separated_without_header_time_from_rate_offset_recorded(tmp_path):
    p = write(tmp_path / "probes.txt", "# logger v2\n1.0\t2.0\n1.1\t2.1\n1.2\t2.2\n")
    ds = read_probes(p, PROBES, 25.0, {"delimiter": "\t", "header": False, "comment": "#",
                                       "time": "rate", "units": "mV"}, time_offset=0.5)
    np.testing.assert_allclose(ds.time, 0.5 + np.arange(3) / 25.0)
    np.testing.assert_allclose(ds.probe_voltage.sel(probe="WP2"), [2e-3, 2.1e-3, 2.2e-3])
    assert ds.attrs["time_offset"] == 0.5


def test_probes_in_length_units_and_a_short_record_named(tmp_path):
    p = write(tmp_path / "p.csv", "t,a,b\n0,10,20\n0.04,11,21\n")
    ds = read_probes(p, PROBES, 25.0, {"columns": ["a", "b"], "time": "t",
                                       "units": {"time": "s", "WP1": "cm", "WP2": "cm"}},
                     units="m")
    np.testing.assert_allclose(ds.probe_elevation.sel(probe="WP1"), [0.1, 0.11])
    write(p, "t,a,b\n0,10,20\n")
    with pytest.raises(InputError, match=r"p\.csv.*fewer than two samples"):
        read_probes(p, PROBES, 25.0, {"columns": ["a", "b"], "time": "t",
                                      "units": {"time": "s"}}, units="m")
